"""The end of a ``fem_axi`` run: a proof, from conserved quantities, that no contact can follow.

After a step without contact force each body moves freely. Newmark's average-acceleration
rule, like the equations of motion M q'' + K q = 0, then conserves the energy E_j of every
normal mode j of each body exactly (it turns each mode's state on its energy ellipse), and
with them the axial momentum. The uniform axial motion X (the mass-weighted mean axial
displacement) moves at a constant velocity V; write q = X 1 + d, d free of that motion (a
clamped rod has X = 0, d = q). With w_j the frequencies and beta_j = b_i.phi_j the candidate
row b_i on the M-orthonormal modes, a mode's amplitude is at most sqrt(2 E_j) / w_j, so for
any weights g_j > 0 (Cauchy-Schwarz)

    |b_i . d| <= sqrt( 2 sum_j g_j E_j * sum_j beta_j^2 / (g_j w_j^2) ).

Two weightings need no eigenvectors:

* g_j = 1: the internal energy E_int = E - m_tot V^2 / 2 (per radian; summed from d and
  v - V 1 themselves) and the static
  compliance c_s = sum beta_j^2 / w_j^2 = b_i K^+ b_i over the fields without rigid motion;
* g_j = 1 + w_j^2 / mu, mu = 4 / h^2: E_int + E_1 / mu, with E_1 = sum w_j^2 E_j =
  (v.K v + a.M a) / 2 (conserved too: (v, a) is a free motion of its own), and the dynamic
  remainder c_s - c + s_i^2 / (m_tot mu) of the compliance, c = b_i K_eff^-1 b_i the
  one-step compliance (the diagonal of B G; K_eff = K + mu M; the last term, the rigid mode's
  share of c, only for a free body). The local, fast part of a node's compliance, which
  dominates c_s on a fine mesh, is in c and drops out; the fast modes it would excite carry
  little of the energy.

With s_i = b_i.1 (+1 for the rod, -1 for the impactor) every later gap is at least

    gap0_i + sum_b s_i X^b(t) - sum_b (the smaller of the two reaches of body b),

and sum_b s_i X^b(t) never falls below its present value while sum_b s_i V^b >= 0 (the
bodies move apart). When that lower bound is positive for every candidate, no later step can
close a gap: the run has computed every contact there is. The reaches are fixed at the
flight's first state (:class:`Flight`); along the flight only X is read. The energies are
inflated by :data:`ENERGY_MARGIN` (of E_int and of the body's whole energy E) and the
compliances by :data:`COMPLIANCE_MARGIN` of c_s, far above the rounding of the steps and of
the solves. (K 1 vanishes only to rounding: the translation of a free body in q meets it; over
a run's horizon its effect on E_int stays many orders below the margin.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rodimpact.solvers.fem_axi.axibody import AxiBody, spd_inverse_rows
from rodimpact.solvers.fem_axi.contact import ContactOperator

__all__ = ["COMPLIANCE_MARGIN", "ENERGY_MARGIN", "BodyBound", "Flight", "SeparationBound"]

#: Relative inflation of the conserved energies (the steps' rounding is far below).
ENERGY_MARGIN = 1e-6
#: Inflation of both compliances, relative to the static one (the solves' rounding is far below).
COMPLIANCE_MARGIN = 1e-6
#: A body is free along the axis when |K 1| is below this fraction of max|K| |1|.
RIGID_MODE_TOL = 1e-9


@dataclass(frozen=True)
class BodyBound:
    """One body's constants in the bound, for c candidate gaps.

    Attributes
    ----------
    free : bool
        The body has the uniform axial motion as a zero-energy mode (K 1 = 0).
    weights : ndarray, shape (n,)
        X = weights . q and V = weights . v (M 1 / m_tot, the mass-weighted mean); zeros when clamped.
    mass : float
        m_tot = 1.M.1, kg per radian (0 when clamped).
    sign : ndarray, shape (c,)
        s_i = b_i.1, the closing of gap i by a unit axial translation of the body.
    static : ndarray, shape (c,)
        c_s, the static compliance over the fields without rigid motion, m per (N per radian).
    dynamic : ndarray, shape (c,)
        The dynamic remainder c_s - c (+ s_i^2 / (m_tot mu) when free), m per (N per radian).
    ones, stiff_ones : ndarray, shape (n,)
        The uniform axial field 1 and K 1 (zero to rounding when free).
    """

    free: bool
    weights: NDArray[np.float64]
    mass: float
    sign: NDArray[np.float64]
    static: NDArray[np.float64]
    dynamic: NDArray[np.float64]
    ones: NDArray[np.float64]
    stiff_ones: NDArray[np.float64]

    @classmethod
    def of(cls, body: AxiBody, rows: sp.spmatrix, GT: NDArray[np.float64]) -> BodyBound:
        """The constants of ``body`` (factorised for its step) for the gap rows ``rows``
        (shape (c, n)) and G^T = (K_eff^-1 rows^T)^T (shape (c, n)): one factorisation of K, whose
        elimination-tree block under the rows gives the static compliances
        (:func:`~.axibody.spd_inverse_rows`)."""
        ones = body.uniform_axial(1.0)
        momentum = body.M @ ones
        mass = float(ones @ momentum)
        K = sp.csr_matrix(body.K)
        rows = sp.csr_matrix(rows)
        sign = rows @ ones
        one_step = np.asarray(rows.multiply(GT).sum(axis=1)).ravel()  # the diagonal of B G, row by row
        free = bool(np.linalg.norm(K @ ones) <= RIGID_MODE_TOL * abs(K).max() * np.linalg.norm(ones))
        if free:
            # K d = f_i with f_i = b_i - s_i w, w = M 1 / m_tot (orthogonal to 1), has the
            # solutions d_p + t 1; the one with d_ground = 0 comes from K without that row and
            # column. With u = K^-1 w there: f_i.K^-1 f_i = b_i.K^-1 b_i - 2 s_i b_i.u + s_i^2 w.u,
            # one solve and the sparse rows' own block of the factor instead of c solves
            weights = momentum / mass
            keep = np.setdiff1d(np.arange(body.n), [int(np.argmax(np.abs(ones)))])
            rows_kept = rows[:, keep]
            inverse_rows, solve = spd_inverse_rows(K[keep][:, keep], rows_kept)
            u = solve(weights[keep])
            static = np.diag(inverse_rows) - 2.0 * sign * (rows_kept @ u) + sign**2 * float(weights[keep] @ u)
            one_step = one_step - sign**2 / (mass * 4.0 / body.h**2)
        else:
            static = np.diag(spd_inverse_rows(K, rows)[0]).copy()
            weights, mass = np.zeros(body.n), 0.0
        margin = COMPLIANCE_MARGIN * np.abs(static)
        return cls(
            free, weights, mass, sign, static + margin, np.maximum(static - one_step, 0.0) + margin, ones, K @ ones
        )

    def motion(self, body: AxiBody) -> tuple[float, float, float, float]:
        """X (m), V (m/s), the internal energy E_int and the energy E (J per radian) of the
        body's present state. E_int is summed from d and v - V 1 themselves: E - m_tot V^2 / 2
        would lose it to rounding when the body's translation carries almost all of E."""
        energy = 0.5 * float(body.v @ body.Mv + body.q @ body.Kq)
        if not self.free:
            return 0.0, 0.0, energy, energy
        x, velocity = float(self.weights @ body.q), float(self.weights @ body.v)
        rel_v, rel_q = body.v - velocity * self.ones, body.q - x * self.ones
        internal = 0.5 * float(
            rel_v @ (body.Mv - velocity * self.mass * self.weights) + rel_q @ (body.Kq - x * self.stiff_ones)
        )
        return x, velocity, max(internal, 0.0), energy

    def fast_energy(self, body: AxiBody) -> float:
        """E_1 / mu = (h^2 / 8)(v.K v + a.M a), J per radian (conserved in a free flight; for a
        free body with v - V 1 for v: K 1 vanishes only to rounding)."""
        v = body.v - float(self.weights @ body.v) * self.ones if self.free else body.v
        return body.h**2 / 8.0 * max(float(v @ (body.K @ v) + body.a @ body.Ma), 0.0)

    def reach(self, internal: float, fast: float, energy: float) -> NDArray[np.float64]:
        """The largest closing of each gap by d, m, for the internal energy E_int, E_1 / mu and
        the energy E (J per radian): the smaller of the two bounds, the energies inflated by
        ENERGY_MARGIN of E_int and of E."""
        grow = (1.0 + ENERGY_MARGIN) * internal + ENERGY_MARGIN * energy
        return np.minimum(
            np.sqrt(2.0 * grow * self.static), np.sqrt(2.0 * (grow + (1.0 + ENERGY_MARGIN) * fast) * self.dynamic)
        )


@dataclass(frozen=True)
class Flight:
    """A free flight from a state that a step without contact force reached.

    Its conserved quantities fix, once, each candidate's largest closing by both bodies'
    deformations (``reach``, m, shape (c,)) and whether the bodies move apart (``apart``); only
    the bodies' translations X change along the flight.
    """

    bound: SeparationBound
    reach: NDArray[np.float64]
    apart: bool

    @classmethod
    def start(cls, bound: SeparationBound, rod: AxiBody, impactor: AxiBody) -> Flight:
        """The flight from the bodies' present state."""
        reach = np.zeros_like(bound.gap0)
        opening = np.zeros_like(bound.gap0)
        for part, body in ((bound.rod, rod), (bound.impactor, impactor)):
            _, velocity, internal, energy = part.motion(body)
            opening += part.sign * velocity
            reach += part.reach(internal, part.fast_energy(body), energy)
        return cls(bound, reach, bool(np.all(opening >= 0.0)))

    def margin(self, rod: AxiBody, impactor: AxiBody) -> float:
        """The smallest lower bound of a later gap, m; -inf when the bodies do not move apart."""
        if not self.apart:
            return -math.inf
        lower = self.bound.gap0 - self.reach
        for part, body in ((self.bound.rod, rod), (self.bound.impactor, impactor)):
            if part.free:
                lower = lower + part.sign * float(part.weights @ body.q)
        return float(lower.min())

    def holds(self, rod: AxiBody, impactor: AxiBody) -> bool:
        """No later step can bring the bodies into contact (see the module's docstring)."""
        return self.margin(rod, impactor) > 0.0


@dataclass(frozen=True)
class SeparationBound:
    """The bound's constants for the rod and the impactor."""

    gap0: NDArray[np.float64]
    rod: BodyBound
    impactor: BodyBound

    @classmethod
    def of(cls, rod: AxiBody, impactor: AxiBody, contact: ContactOperator) -> SeparationBound:
        """The constants of both bodies for the contact's candidates (one factorisation of each stiffness)."""
        return cls(
            contact.gap0,
            BodyBound.of(rod, contact.B_rod, contact.GT_rod),
            BodyBound.of(impactor, contact.B_imp, contact.GT_imp),
        )

    def flight(self, rod: AxiBody, impactor: AxiBody) -> Flight:
        """The free flight from the present state (which a step without contact force reached)."""
        return Flight.start(self, rod, impactor)
