"""The contact-law interface: what every solver asks of a quasi-static contact law.

A law gives the contact force P as a function of the approach alpha (the mutual
convergence of impactor and rod end, m; alpha <= 0 is a gap and carries no force). The
solvers never assume a power law: they use only the methods below.

- :meth:`ContactLaw.force` P(alpha), N;
- :meth:`ContactLaw.stiffness` dP/dalpha, N/m;
- :meth:`ContactLaw.energy` the stored energy int_0^alpha P, J;
- :meth:`ContactLaw.approach` the approach at a given force (the inverse of P), m;
- :meth:`ContactLaw.solve_step` the one root of alpha + b P(alpha) = a (b > 0), the implicit
  step of every scheme whose approach is affine in the new force, alpha = A - B P;
- :meth:`ContactLaw.contact_radius` the radius of the contact patch, m (for meshes and output);
- :meth:`ContactLaw.rigid_impact` the impact of a rigid mass on a rigid flat, the time and
  force scales of every method (the stability limit, the automatic step, the cost model).

A law must be monotone: P(0) = 0, P increasing and P' >= 0 for alpha > 0, so that the step
equation has exactly one root for b > 0. :meth:`solve_step` and :meth:`rigid_impact` have
generic implementations (safeguarded Newton; quadrature of the energy integral) that a law
may replace with closed forms.

**Laws with memory.** A law that loads on one curve and unloads on another
(:class:`MemoryLaw`, ``memory = True``) has a state: the largest approach reached,
alpha_max. Its methods above describe the virgin loading curve; :meth:`ContactLaw.branch`
gives the curve the contact follows while alpha_max is fixed: the unloading curve below
alpha_max (no force below the residual approach alpha_p, the dent), the loading curve above.
That curve is itself a monotone law, so every step above applies to it unchanged, and the step
is exact across alpha_max (the loading part of the curve is the virgin law's). A method carries
the state: it solves each step on ``law.branch(alpha_max)``, and after a node whose approach
exceeds alpha_max it takes the new branch. Contact holds while alpha > alpha_p: a ball that
separates and strikes again meets its dent. The energy the contact dissipated depends on
alpha_max alone (:meth:`MemoryLaw.dissipated_energy`); :func:`contact_energies` gives, at
every node of a run, the energy the contact stores and the energy it has dissipated, which
every method's energy balance counts. An elastic law is its own branch, stores
int_0^alpha P and dissipates nothing.

Each law also declares, once and next to its physics, what the rest of the project reads of
it (the configuration's schema and checks, the rules, the runner, the tables):

- ``name`` and ``label``, and ``reading``: the words a table uses for a case with this law;
- ``settings``: its settings in a case's ``contact`` block, a :class:`LawSettings` dataclass
  declared with :func:`~rodimpact.settings.declare.setting` (doc, unit, bounds; nested blocks
  such as a film, lists of them, materials);
- ``needs``: what it needs from the workflow before a run (:class:`Needs`: a film, a curve a
  rule computes, or nothing);
- ``method_contact``: which methods can run it, by how a method treats the contact (the
  registry's ``Method.contact``: ``law``, ``continuum``);
- ``conflicts``: the case fields it cannot be combined with, and why.

:func:`check_positive` is the check a law makes of its arguments: the mass and velocity of a
rigid impact (the generic one here, and every law's closed form), and its own constants.
"""

from __future__ import annotations

import abc
import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.settings.declare import Settings

__all__ = [
    "MAX_STEP_ITERATIONS",
    "ContactLaw",
    "ElasticMaterial",
    "LawSettings",
    "LawState",
    "MemoryLaw",
    "Needs",
    "RigidImpact",
    "StepNotConverged",
    "YieldingMaterial",
    "check_positive",
    "contact_energies",
    "contact_radii",
]

#: Newton iterations :meth:`ContactLaw.solve_step` takes at most.
MAX_STEP_ITERATIONS = 60


class ElasticMaterial(Protocol):
    """What a law reads of a material (``rodimpact.model.materials.Material``): its elastic constants."""

    youngs_modulus_pa: float
    poisson_ratio: float


class YieldingMaterial(ElasticMaterial, Protocol):
    """A material as a law with plasticity reads it: also its yield stress (None: elastic)."""

    yield_stress_pa: float | None


class StepNotConverged(ArithmeticError):
    """The step equation alpha + b P(alpha) = a was not solved (a law that is not monotone)."""


@dataclass(frozen=True)
class RigidImpact:
    """A rigid mass striking a rigid flat through the contact law (no wave in either body).

    Attributes
    ----------
    max_approach_m : float
        alpha_max, where the law's stored energy equals the impact energy m v0^2 / 2, m.
    contact_time_s : float
        Duration of the contact, s: 2 int_0^alpha_max d alpha / sqrt(v0^2 - 2 E(alpha) / m).
    peak_force_N : float
        P(alpha_max), N.
    restitution : float
        Rebound over impact velocity, 1 for an elastic law; below 1 for a law with memory, which
        unloads on another curve.
    residual_approach_m : float
        The approach at which the force falls to zero on unloading (the dent), m; 0 for an
        elastic law.
    """

    max_approach_m: float
    contact_time_s: float
    peak_force_N: float
    restitution: float = 1.0
    residual_approach_m: float = 0.0


@dataclass(frozen=True)
class LawState:
    """Where a contact law stands after a largest approach: its memory.

    Attributes
    ----------
    max_approach_m : float
        The largest approach reached, alpha_max, m.
    residual_approach_m : float
        alpha_p, where the unloading curve from alpha_max carries no force (the dent), m; 0 for
        an elastic law.
    dissipated_energy_J : float
        The energy the contact dissipated in reaching alpha_max: the work of the loading curve
        less what the unloading curve returns, J; 0 for an elastic law.
    """

    max_approach_m: float
    residual_approach_m: float = 0.0
    dissipated_energy_J: float = 0.0


@dataclass(frozen=True, kw_only=True)
class LawSettings(Settings):
    """A contact law's settings, as a case's ``contact`` block gives them (none: the law is
    built from the case's bodies alone)."""


@dataclass(frozen=True)
class Needs:
    """What a contact law needs from the workflow before a run.

    Attributes
    ----------
    film : bool
        The law's cases carry a film on the rod's struck end (their settings' ``film``), and
        the workflow computes the prediction band over the film's ranges for them.
    curve_rule : str or None
        The workflow rule that computes the law's curve for each case (the runner hands it to
        the law as ``contact.curve``); None: the law is built from the case alone.
    """

    film: bool = False
    curve_rule: str | None = None


def check_positive(**values: float) -> None:
    """Check that each value is a positive finite number: a rigid impact's mass and velocity,
    a law's constants.

    Parameters
    ----------
    **values : float
        The values, by the names a message gives them.

    Raises
    ------
    ValueError
        The first value that is not > 0 and finite, by name.
    """
    for name, value in values.items():
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be > 0, got {value!r}")


class ContactLaw(abc.ABC):
    """A monotone quasi-static contact law P(alpha) (see the module docstring).

    Subclasses are frozen dataclasses holding the law's parameters; ``name`` is the law's
    name in a case file (``contact: {law: <name>}``), ``label`` its name in words.
    """

    name: str = ""
    #: The law's name in words, for messages, legends and captions.
    label: str = ""
    #: How a table reads a case with this law, in words (e.g. "Hertz contact").
    reading: str = ""
    #: Its settings in a case's ``contact`` block (beside ``law``).
    settings: type[LawSettings] = LawSettings
    #: What it needs from the workflow before a run.
    needs: Needs = Needs()
    #: The methods that can run it, by how they treat the contact (``Method.contact`` of the
    #: registry): ``law``, a method that takes P(alpha); ``continuum``, one that meshes the
    #: bodies and resolves the contact itself, which can run only a law that describes bodies
    #: (a sphere, a flat, a bonded film), not a law that is only a force-approach curve.
    method_contact: frozenset[str] = frozenset({"law", "continuum"})
    #: Case fields the law cannot be combined with -> why.
    conflicts: Mapping[str, str] = MappingProxyType({})
    #: The law approximates what it describes beyond its range of validity (a thin layer at
    #: contact sizes comparable to its thickness): its numbers are no bound on a measurement.
    approximation: bool = False
    #: The law has memory: it unloads on another curve than it loads (:class:`MemoryLaw`);
    #: only a method that carries its state can run it (the registry's ``Method.memory``).
    memory: bool = False

    @classmethod
    def bodies_problem(
        cls, spec: Mapping[str, Any], impactor: YieldingMaterial, rod: YieldingMaterial
    ) -> tuple[str, str] | None:
        """What is wrong with a case's ``contact`` block ``spec`` for its bodies' materials, as
        (setting, reason), or None (the configuration's check, before any job): a setting a law
        can take from the materials when they give it, a setting that contradicts them."""
        return None

    @abc.abstractmethod
    def force(self, approach_m: float) -> float:
        """Contact force P(alpha), N (0 for alpha <= 0)."""

    @abc.abstractmethod
    def stiffness(self, approach_m: float) -> float:
        """Tangent stiffness dP/dalpha, N/m (0 for alpha <= 0)."""

    @abc.abstractmethod
    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """Stored energy int_0^alpha P d alpha, J; 0 for alpha <= 0. Shape as ``approach_m``."""

    @abc.abstractmethod
    def approach(self, force_N: float) -> float:
        """The approach at which the law carries ``force_N`` (>= 0), m."""

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float | None:
        """Radius of the contact patch, m (shape as ``approach_m``); None when the law has no
        geometry (a law that is only a force-approach curve)."""
        return None

    def summary(self) -> dict[str, float | str]:
        """The law's name and parameters, stored with every run (``contact_law``, ...)."""
        return {"contact_law": self.name}

    def branch(self, max_approach_m: float) -> ContactLaw:
        """The monotone law the contact follows while its largest approach is
        ``max_approach_m`` (m): an elastic law is its own (see the module docstring)."""
        return self

    def state(self, max_approach_m: float) -> LawState:
        """The law's state after reaching ``max_approach_m`` (m): for an elastic law no dent
        and no dissipation."""
        return LawState(max_approach_m=float(max_approach_m))

    def run_summary(self, max_approach_m: float) -> dict[str, float]:
        """Entries a run through this law adds to its summary, given the run's largest
        approach, m (e.g. where the law stands in its range of validity); may log a warning."""
        return {}

    def solve_step(self, a: float, b: float, guess: float) -> tuple[float, int]:
        """The root alpha >= 0 of alpha + b P(alpha) = a, and the iteration count.

        Parameters
        ----------
        a : float
            The approach the step would reach with no force, m (> 0).
        b : float
            The compliance of the step, m/N (>= 0; > 0 makes the root unique).
        guess : float
            A first guess, m (clipped into the bracket [0, a]).

        Returns
        -------
        alpha : float
            The root, m.
        iterations : int
            Newton iterations taken.

        Notes
        -----
        f(alpha) = alpha + b P(alpha) - a increases on [0, a] from -a to b P(a) >= 0, so the
        root is bracketed; Newton's steps are kept inside the shrinking bracket (bisection
        when a step leaves it).
        """
        lo, hi = 0.0, a
        alpha = min(max(guess, lo), hi)
        for iteration in range(1, MAX_STEP_ITERATIONS + 1):
            f = alpha + b * self.force(alpha) - a
            if f == 0.0:
                return alpha, iteration
            if f < 0.0:
                lo = alpha
            else:
                hi = alpha
            slope = 1.0 + b * self.stiffness(alpha)
            alpha_new = alpha - f / slope
            if not (lo < alpha_new < hi):
                alpha_new = 0.5 * (lo + hi)
            if abs(alpha_new - alpha) <= 1e-15 * alpha_new or alpha_new == alpha:
                return alpha_new, iteration
            alpha = alpha_new
        raise StepNotConverged(
            f"the step of the {self.name or type(self).__name__} law did not converge (a={a!r}, b={b!r})"
        )

    def solve_step_force(self, a: float, b: float, guess: float) -> tuple[float, float, int]:
        """:meth:`solve_step` and the force there: (alpha, P(alpha), iterations).

        A law whose step is solved in another variable (the film's s = P^(1/6)) gives the force
        from it, without a second root.
        """
        alpha, iterations = self.solve_step(a, b, guess)
        return alpha, self.force(alpha), iterations

    def energy_between(self, lower_m: float, upper_m: float) -> float:
        """int_lower^upper P d alpha, J, without the cancellation of E(upper) - E(lower)
        (generic: adaptive quadrature of :meth:`force`)."""
        from scipy.integrate import quad

        return quad(self.force, lower_m, upper_m, epsabs=0.0, epsrel=1e-13)[0]

    def rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        """The impact of a rigid mass on a rigid flat through this law.

        Parameters
        ----------
        mass_kg : float
            Impactor mass m, kg (> 0).
        velocity_m_s : float
            Impact velocity v0, m/s (> 0).

        Returns
        -------
        RigidImpact
            By quadrature of the energy integral: alpha_max from E(alpha_max) = m v0^2 / 2;
            the contact time 2 int_0^alpha_max d alpha / v(alpha) with v^2 = 2 (E(alpha_max)
            - E(alpha)) / m, integrated in u = sqrt(alpha_max - alpha), which removes the
            inverse square root at the turning point.
        """
        try:
            return _rigid_impact_memo(self, float(mass_kg), float(velocity_m_s))
        except TypeError:  # a law holding arrays (not hashable): computed each time
            return self._rigid_impact(mass_kg, velocity_m_s)

    def _rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        """:meth:`rigid_impact` by quadrature (its docstring), without the memo."""
        # imported here: a law with a closed form (Hertz) never needs them, and the
        # configuration check of every workflow job should not pay for them
        from scipy.integrate import quad
        from scipy.optimize import brentq

        check_positive(mass_kg=mass_kg, velocity_m_s=velocity_m_s)
        kinetic = 0.5 * mass_kg * velocity_m_s**2
        upper = velocity_m_s * 1e-9
        while float(self.energy(upper)) < kinetic:
            upper *= 4.0
        alpha_max = brentq(lambda x: float(self.energy(x)) - kinetic, 0.0, upper, xtol=1e-300, rtol=8.9e-16)

        def integrand(u: float) -> float:
            # d alpha = 2 u du; v = sqrt(2 (E_max - E(alpha)) / m), E_max - E = int_alpha^alpha_max P
            alpha = alpha_max - u * u
            stored = self.energy_between(alpha, alpha_max)
            if stored > 0.0:
                return 2.0 * u / math.sqrt(2.0 * stored / mass_kg)
            return 2.0 / math.sqrt(2.0 * self.force(alpha_max) / mass_kg)  # the limit u -> 0

        half = quad(integrand, 0.0, math.sqrt(alpha_max), epsabs=0.0, epsrel=1e-12, limit=200)[0]
        return RigidImpact(max_approach_m=alpha_max, contact_time_s=2.0 * half, peak_force_N=self.force(alpha_max))


class MemoryLaw(ContactLaw):
    """A contact law with memory: it loads on the virgin curve (:meth:`force`,
    :meth:`energy`, ...) and unloads from its largest approach alpha_max on another
    (:meth:`branch`), leaving a residual approach and dissipating energy.

    A subclass gives the branch and three functions of alpha_max (and of the approach), each
    taking arrays of any shape: :meth:`residual_approach`, :meth:`dissipated_energy`,
    :meth:`stored_energy`; and :meth:`contact_radius_after` where it has a geometry.
    """

    memory = True

    @abc.abstractmethod
    def branch(self, max_approach_m: float) -> ContactLaw:
        """The monotone law that holds while the largest approach is ``max_approach_m`` (m):
        the unloading curve from there below it (zero force up to the residual approach), the
        virgin loading curve above it."""

    @abc.abstractmethod
    def residual_approach(self, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """alpha_p, where the unloading curve from alpha_max carries no force, m (shape as
        ``max_approach_m``)."""

    @abc.abstractmethod
    def dissipated_energy(self, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """Energy dissipated by loading to alpha_max and unloading: int_0^alpha_max P_load less
        int_alpha_p^alpha_max P_unload, J (shape as ``max_approach_m``)."""

    @abc.abstractmethod
    def stored_energy(self, approach_m: ArrayLike, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """Energy the contact stores at ``approach_m`` on the unloading curve from
        ``max_approach_m`` (approach <= max), what unloading would return: int_alpha_p^alpha
        P_unload, J (shapes broadcast)."""

    def contact_radius_after(
        self, approach_m: ArrayLike, max_approach_m: ArrayLike
    ) -> NDArray[np.float64] | float | None:
        """Radius of the contact patch at ``approach_m`` on the unloading curve from
        ``max_approach_m``, m; None without a geometry."""
        return None

    def state(self, max_approach_m: float) -> LawState:
        peak = max(float(max_approach_m), 0.0)
        return LawState(
            max_approach_m=peak,
            residual_approach_m=float(self.residual_approach(peak)),
            dissipated_energy_J=float(self.dissipated_energy(peak)),
        )

    def _rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        """The rigid impact by quadrature: loading on the virgin curve (the elastic law's
        quadrature of :meth:`ContactLaw._rigid_impact`, half its contact time), unloading on
        the branch from alpha_max to alpha_p, which returns the stored energy as the rebound's."""
        loading = super()._rigid_impact(mass_kg, velocity_m_s)
        peak = loading.max_approach_m
        branch = self.branch(peak)
        residual = float(self.residual_approach(peak))
        stored = float(self.stored_energy(peak, peak))
        rebound = math.sqrt(2.0 * stored / mass_kg)
        # the branch is an elastic law with no force below alpha_p: its own rigid impact at the
        # rebound velocity turns at alpha_max and spends alpha_p / v in free flight each way
        unloading = 0.5 * branch.rigid_impact(mass_kg, rebound).contact_time_s - residual / rebound
        return RigidImpact(
            max_approach_m=peak,
            contact_time_s=0.5 * loading.contact_time_s + unloading,
            peak_force_N=loading.peak_force_N,
            restitution=rebound / velocity_m_s,
            residual_approach_m=residual,
        )


def contact_energies(law: ContactLaw, approach_m: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The energy a run's contact stores and the energy it has dissipated, at each node.

    Parameters
    ----------
    law : ContactLaw
        The run's law.
    approach_m : array_like, shape (n,)
        The approach at the run's nodes, in time order, m.

    Returns
    -------
    stored, dissipated : ndarray, shape (n,)
        J. An elastic law stores :meth:`ContactLaw.energy` and dissipates nothing; a law with
        memory stores what its unloading curve from the largest approach so far returns and
        has dissipated :meth:`MemoryLaw.dissipated_energy` of that largest approach.
    """
    alpha = np.asarray(approach_m, dtype=float)
    if not isinstance(law, MemoryLaw):
        return np.asarray(law.energy(alpha), dtype=float), np.zeros_like(alpha)
    peak = np.maximum.accumulate(np.maximum(alpha, 0.0)) if alpha.size else alpha
    return (
        np.asarray(law.stored_energy(alpha, peak), dtype=float),
        np.asarray(law.dissipated_energy(peak), dtype=float),
    )


def contact_radii(law: ContactLaw, approach_m: ArrayLike) -> NDArray[np.float64] | None:
    """The radius of the contact patch at each node of a run (``approach_m`` in time order,
    shape (n,)), m; None when the law has no geometry. A law with memory gives the radius on
    its unloading curve from the largest approach so far."""
    alpha = np.asarray(approach_m, dtype=float)
    if not isinstance(law, MemoryLaw):
        radius = law.contact_radius(alpha)
    else:
        peak = np.maximum.accumulate(np.maximum(alpha, 0.0)) if alpha.size else alpha
        radius = law.contact_radius_after(alpha, peak)
    return None if radius is None else np.asarray(radius, dtype=float)


@functools.lru_cache(maxsize=1024)
def _rigid_impact_memo(law: ContactLaw, mass_kg: float, velocity_m_s: float) -> RigidImpact:
    """A hashable (frozen) law's rigid impact, computed once per law, mass and velocity: the
    configuration check, the cost models and the solvers of one process ask for the same."""
    return law._rigid_impact(mass_kg, velocity_m_s)
