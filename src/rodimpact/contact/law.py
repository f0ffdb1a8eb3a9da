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

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.settings.declare import Settings

__all__ = [
    "MAX_STEP_ITERATIONS",
    "ContactLaw",
    "LawSettings",
    "Needs",
    "RigidImpact",
    "StepNotConverged",
    "check_positive",
]

#: Newton iterations :meth:`ContactLaw.solve_step` takes at most.
MAX_STEP_ITERATIONS = 60


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
    """

    max_approach_m: float
    contact_time_s: float
    peak_force_N: float


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


@functools.lru_cache(maxsize=1024)
def _rigid_impact_memo(law: ContactLaw, mass_kg: float, velocity_m_s: float) -> RigidImpact:
    """A hashable (frozen) law's rigid impact, computed once per law, mass and velocity: the
    configuration check, the cost models and the solvers of one process ask for the same."""
    return law._rigid_impact(mass_kg, velocity_m_s)
