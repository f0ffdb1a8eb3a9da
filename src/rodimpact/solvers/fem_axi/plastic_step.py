"""J2 plasticity in ``fem_axi``'s dynamic run: the plastic regions of both bodies, stepped with the
elastic Newmark factorisation.

Where a material yields, each body's internal force is f_int(q) = K q - U p(q)
(:mod:`.plastic_region`: p = E^T W D_e eps_p, the plastic strain's load on the region's
coordinates). A Newmark step then solves

    K_eff q = y + B^T lambda + U p(q),   lambda >= 0 complementary to the gaps,

with K_eff = K + (4/h^2) M factorised once for the elastic run. The step iterates on p with that
factorisation (the initial-stiffness method: each iterate is the elastic step with the last
iterate's plastic load, its contact LCP solved with the elastic Delassus operator, then the
return map at the new displacement). The plastic load only relaxes the elastic stiffness (D_t
<= D_e), so the iteration contracts, but linearly, and slowly where the plastic zone is large (a
factor of 0.97 an iterate measured on the 4.75 mm ball on the yielding rod): Anderson's
acceleration (Walker and Ni, SIAM J. Numer. Anal. 49, 2011) fits each new residual by the last
:data:`ANDERSON_DEPTH` differences of residuals and steps on from the fit. It stops when p
changes by less than :data:`PLASTIC_RTOL` of the larger of its norm and the contact force (per
radian). No other factorisation is made: the rest of the mesh,
and the plastic region too, keep the elastic step's.

The energy stored in a body is then (1/2) (eps - eps_p) : D : (eps - eps_p), that is
pi (q.K q - 2 q_R.p + sum_points w eps_p.D.eps_p) in 3-D, and the plastic work done, summed
over the steps, is the energy dissipated: the run's energy balance counts both.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from rodimpact.solvers.fem_axi.axibody import AxiBody
from rodimpact.solvers.fem_axi.aximodel import AxiModel, material_groups
from rodimpact.solvers.fem_axi.contact import ContactOperator
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.plastic_region import PlasticRegion, RegionResponse, YieldGuard, plastic_region
from rodimpact.solvers.fem_axi.plasticity import J2State
from rodimpact.solvers.fem_axi.problem import AxiImpact

__all__ = ["MAX_PLASTIC_ITERATIONS", "PLASTIC_RTOL", "PlasticBodies", "PlasticStep"]

log = logging.getLogger(__name__)

#: A step's iteration on the plastic load stops when it changes by less than this fraction.
PLASTIC_RTOL = 1e-10
#: Iterations allowed per step.
MAX_PLASTIC_ITERATIONS = 500
#: Differences Anderson's acceleration fits the residual with.
ANDERSON_DEPTH = 8


@dataclass
class _Yielding:
    """One body's plastic region, its history and its guard."""

    body: AxiBody
    region: PlasticRegion
    guard: YieldGuard
    state: J2State
    load: NDArray[np.float64]  # p of the state, N per radian, on the region's coordinates
    response: RegionResponse | None = None

    def spread(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """U p: the region's load on the body's free coordinates."""
        full = np.zeros(self.body.n)
        full[self.region.coordinates] = p
        return full


@dataclass(frozen=True)
class PlasticStep:
    """A step's displacements and loads with the plastic regions' loads included.

    Attributes
    ----------
    q_rod, q_imp : ndarray
        The new displacements of both bodies, m.
    load_rod, load_imp : ndarray or float
        The generalised loads of the step (contact and plastic), N per radian, for
        :meth:`~.axibody.AxiBody.advance`.
    lam : ndarray
        The contact multipliers, N per radian.
    iterations : int
        Iterations on the plastic load.
    """

    q_rod: NDArray[np.float64]
    q_imp: NDArray[np.float64]
    load_rod: NDArray[np.float64] | float
    load_imp: NDArray[np.float64] | float
    lam: NDArray[np.float64]
    iterations: int


@dataclass
class PlasticBodies:
    """The yielding regions of a run's two bodies (either may have none).

    Attributes
    ----------
    rod, impactor : _Yielding or None
    dissipated_J : float
        The plastic work done so far, J (3-D).
    iterations : int
        Iterations on the plastic load over the run.
    """

    rod: _Yielding | None
    impactor: _Yielding | None
    dissipated_J: float = 0.0
    iterations: int = 0
    worst_guard: float = 0.0
    _parts: tuple = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._parts = (self.rod, self.impactor)

    @classmethod
    def of(cls, problem: AxiImpact, model: AxiModel, options: FEMAxiOptions) -> PlasticBodies | None:
        """The plastic regions of ``problem``'s yielding materials within ``plastic_extent``
        estimated contact radii of the contact point; None when nothing yields."""
        if not problem.yields:
            return None
        radius = options.plastic_extent * model.scales.contact_radius_m
        rod_groups, imp_groups = material_groups(problem, model)
        parts = []
        for body, groups in ((model.rod, rod_groups), (model.impactor, imp_groups)):
            region = plastic_region(body.basis, body.T, groups, radius)
            if region is None:
                parts.append(None)
                continue
            parts.append(
                _Yielding(
                    body=body,
                    region=region,
                    guard=YieldGuard.beyond(body.basis, groups, region),
                    state=region.virgin(),
                    load=np.zeros(len(region.coordinates)),
                )
            )
        if parts == [None, None]:
            return None
        return cls(parts[0], parts[1])

    def step(
        self, contact: ContactOperator, q_rod: NDArray[np.float64], q_imp: NDArray[np.float64]
    ) -> PlasticStep | None:
        """The step from the bodies' predictions ``q_rod``, ``q_imp`` (K_eff^-1 y, m); None when
        the iteration on the plastic load does not converge."""
        predicted = (q_rod, q_imp)
        used = [part.load.copy() if part is not None else None for part in self._parts]
        history: list[tuple[NDArray[np.float64], NDArray[np.float64]]] = []
        images: list[NDArray[np.float64]] = []
        residuals: list[NDArray[np.float64]] = []
        for iteration in range(1, MAX_PLASTIC_ITERATIONS + 1):
            free = [
                pred if part is None or not used[k].any() else pred + part.body.solve(part.spread(used[k]))
                for k, (part, pred) in enumerate(zip(self._parts, predicted))
            ]
            gap = contact.gaps(free[0], free[1])
            lam = np.zeros(len(gap))
            loads: list[NDArray[np.float64] | float] = [0.0, 0.0]
            if gap.min() < 0.0:
                lam = contact.multipliers(gap)
                if lam.any():
                    d_rod, d_imp, load_rod, load_imp = contact.corrections(lam)
                    free = [free[0] + d_rod, free[1] + d_imp]
                    loads = [load_rod, load_imp]
            change, scale = 0.0, float(lam.sum())
            for k, part in enumerate(self._parts):
                if part is None:
                    continue
                part.response = part.region.respond(free[k][part.region.coordinates], part.state)
                change = max(change, float(np.linalg.norm(part.response.load - used[k])))
                scale = max(scale, float(np.linalg.norm(part.response.load)))
            log.debug("iterate %d: change %.3e of %.3e, %d in contact", iteration, change, scale, int((lam > 0).sum()))
            if change <= PLASTIC_RTOL * scale or change == 0.0:
                self.iterations += iteration
                for k, part in enumerate(self._parts):
                    if part is not None and used[k].any():
                        loads[k] = loads[k] + part.spread(used[k])
                return PlasticStep(free[0], free[1], loads[0], loads[1], lam, iteration)
            # Anderson's acceleration of the iteration p <- G(p) (type II, the last ANDERSON_DEPTH
            # differences): p_next = G(p) - dG gamma, gamma the least-squares fit of the residual
            # r = G(p) - p by the residuals' differences dR
            image = np.concatenate([part.response.load for part in self._parts if part is not None])
            residual = image - np.concatenate([used[k] for k, part in enumerate(self._parts) if part is not None])
            if history:
                last_image, last_residual = history[-1]
                images.append(image - last_image)
                residuals.append(residual - last_residual)
                del images[:-ANDERSON_DEPTH], residuals[:-ANDERSON_DEPTH]
            history[:] = [(image, residual)]
            step = image
            if residuals:
                gamma = np.linalg.lstsq(np.column_stack(residuals), residual, rcond=None)[0]
                step = image - np.column_stack(images) @ gamma
            used = self._split(step)
        return None

    def _split(self, flat: NDArray[np.float64]) -> list[NDArray[np.float64] | None]:
        """The bodies' plastic loads from their concatenation (the rod's first)."""
        out: list[NDArray[np.float64] | None] = []
        start = 0
        for part in self._parts:
            if part is None:
                out.append(None)
                continue
            size = len(part.region.coordinates)
            out.append(flat[start : start + size].copy())
            start += size
        return out

    def accept(self) -> float:
        """Take the last step's histories; returns the largest von Mises stress over the yield
        stress beyond the regions (1 or more: a region is too small)."""
        worst = 0.0
        for part in self._parts:
            if part is None:
                continue
            response = part.response
            part.state = response.state
            part.load = response.load
            self.dissipated_J += response.plastic_work_J
            worst = max(worst, part.guard.ratio(part.body.T @ part.body.q))
        self.worst_guard = max(self.worst_guard, worst)
        return worst

    def stored_correction(self, which: int, q: NDArray[np.float64]) -> float:
        """What the plastic strain takes from a body's elastic energy pi q.K q, J (3-D): -2 pi
        q_R.p + pi sum w eps_p.D.eps_p (``which``: 0 the rod, 1 the impactor)."""
        part = self._parts[which]
        if part is None or not part.load.any():
            return 0.0
        eps_p = part.state.plastic_strain
        own = 0.0
        for k, material in enumerate(part.region.materials):
            at = part.region.point_material == k
            tangent = material.elastic_tangent
            own += float(np.einsum("p,pi,ij,pj->", part.region.weights[at], eps_p[at], tangent, eps_p[at]))
        return math.pi * (own - 2.0 * float(q[part.region.coordinates] @ part.load))
