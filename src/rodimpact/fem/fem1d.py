"""``fem1d``: a rigid impactor with Hertz contact on a 1D finite-element bar.

Newmark's average-acceleration rule (beta = 1/4, gamma = 1/2) for the bar and for the
impactor: it conserves the energy of the linear part exactly, and is unconditionally
stable. With K_eff = K + (4/h^2) M factorised once, the new displacement is

    u_{n+1} = u_pred + P_{n+1} g,   g = K_eff^-1 e0,

so the approach is affine in the new force, alpha_{n+1} = A - B P_{n+1} (B > 0), and the
Hertz law is solved as one scalar equation, exactly as in the SEM
(:func:`rodimpact.hertz.solve_hertz_step`). Contact ends and starts are located between
steps by the root of the cubic Hermite interpolant of the approach.
"""

from __future__ import annotations

import logging
import math
import time as _time
from dataclasses import dataclass
from typing import Any, Literal, Mapping, Sequence

import numpy as np
from scipy.optimize import brentq
from scipy.sparse.linalg import splu

from ..hertz import solve_hertz_step
from ..result import ImpactResult, check_stepping, limit_reached, local_maxima
from ..sem.problem import ImpactProblem
from .bar import bar_model, end_vector

__all__ = ["FEM1DOptions", "solve_fem1d"]

log = logging.getLogger(__name__)

#: Below this many nodes per wavelength of the contact's wave the run warns; below the
#: hard minimum it refuses.
WARN_POINTS_PER_WAVELENGTH = 10.0
MIN_POINTS_PER_WAVELENGTH = 4.0
#: Fewer steps per Hertz contact time cannot resolve the contact.
MIN_STEPS_PER_CONTACT = 20


@dataclass(frozen=True)
class FEM1DOptions:
    """Numerical options of :func:`solve_fem1d`.

    Parameters
    ----------
    element : {"P1", "P2"}
        Lagrange element order.
    elements : int or None
        Number of elements; None chooses ``points_per_wavelength`` nodes per wavelength
        a * t_Hertz of the wave the contact excites (at least 20 elements).
    points_per_wavelength : float
        Used when ``elements`` is None.
    dt_s : float or None
        Time step, s; None gives t_Hertz / steps_per_contact.
    steps_per_contact : int
        Steps per Hertz contact time (rigid rod) when ``dt_s`` is None.
    max_time_factor : float
        Time limit in estimated contact times.
    max_contacts : int
        Contacts followed at most.
    """

    element: Literal["P1", "P2"] = "P2"
    elements: int | None = None
    points_per_wavelength: float = 200.0
    dt_s: float | None = None
    steps_per_contact: int = 2000
    max_time_factor: float = 100.0
    max_contacts: int = 50

    def __post_init__(self) -> None:
        if self.element not in ("P1", "P2"):
            raise ValueError(f"element must be 'P1' or 'P2', got {self.element!r}")
        if self.elements is not None and (int(self.elements) != self.elements or self.elements < 1):
            raise ValueError(f"elements must be a positive integer or None, got {self.elements!r}")
        if not self.points_per_wavelength > 0:
            raise ValueError(f"points_per_wavelength must be > 0, got {self.points_per_wavelength!r}")
        check_stepping(self.dt_s, self.steps_per_contact, 1, self.max_time_factor, self.max_contacts)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any]) -> "FEM1DOptions":
        """Build from a resolved ``numerics.fem1d`` mapping."""
        return cls(**{k: data[k] for k in cls.__dataclass_fields__ if data.get(k) is not None})

    def resolve(self, problem: ImpactProblem) -> tuple[int, float, list[str]]:
        """Element count, time step and warnings for ``problem``; refuses settings that
        cannot resolve the contact, naming the setting and the value it needs."""
        t_hertz = problem.rigid_hertz.contact_time_s
        wavelength = problem.rod.wave_speed * t_hertz
        order = 1 if self.element == "P1" else 2
        length = problem.rod.length_m
        n = self.elements
        if n is None:
            n = max(20, math.ceil(self.points_per_wavelength * length / (order * wavelength)))
        points = wavelength / (length / (n * order))
        needed = math.ceil(WARN_POINTS_PER_WAVELENGTH * length / (order * wavelength))
        warnings = []
        if points < MIN_POINTS_PER_WAVELENGTH:
            raise ValueError(f"elements={n} gives {points:.2f} nodes per wavelength of the contact's wave "
                             f"(a t_Hertz = {wavelength:.3g} m); needs elements >= {needed}")
        if points < WARN_POINTS_PER_WAVELENGTH:
            warnings.append(f"elements={n} gives only {points:.1f} nodes per wavelength of the contact's "
                            f"wave; elements >= {needed} recommended")
        dt = self.dt_s if self.dt_s is not None else t_hertz / self.steps_per_contact
        if dt > t_hertz / MIN_STEPS_PER_CONTACT:
            raise ValueError(f"dt_s={dt:.3g} s cannot resolve a contact of {t_hertz:.3g} s "
                             f"(Hertz time); needs dt_s <= {t_hertz / MIN_STEPS_PER_CONTACT:.3g} s "
                             f"(steps_per_contact >= {MIN_STEPS_PER_CONTACT})")
        return n, dt, warnings


def _hermite_root(a0: float, a1: float, d0: float, d1: float, h: float) -> float:
    """Zero in (0, h) of the cubic Hermite interpolant of values a0, a1 and slopes d0, d1."""
    def cubic(s: float) -> float:
        q = s / h
        return ((2 * q**3 - 3 * q**2 + 1) * a0 + (q**3 - 2 * q**2 + q) * h * d0
                + (-2 * q**3 + 3 * q**2) * a1 + (q**3 - q**2) * h * d1)

    if cubic(0.0) * cubic(h) > 0:  # interpolant without a sign change: fall back to linear
        return h * a0 / (a0 - a1)
    return brentq(cubic, 0.0, h, xtol=1e-14 * h)


def solve_fem1d(problem: ImpactProblem, options: FEM1DOptions | None = None,
                stations: Sequence[float] = ()) -> ImpactResult:
    """Solve the impact with the rod as a finite-element bar.

    Parameters
    ----------
    problem : ImpactProblem
        The impact (same Hertz law and constant as the SEM).
    options : FEM1DOptions, optional
        Discretisation; defaults to ``FEM1DOptions()``.
    stations : sequence of float
        Fractions of the rod length, from the struck end, where the displacement and the
        strain are recorded (``station_displacement``, ``station_strain``, shape (n, k)).

    Returns
    -------
    ImpactResult
        As the SEM's, plus the station histories and the energies (impactor, contact, rod
        kinetic and strain) as extra series, and the element count in ``extra``.
    """
    options = FEM1DOptions() if options is None else options
    started = _time.perf_counter()
    n_el, h, warnings = options.resolve(problem)
    for warning in warnings:
        log.warning(warning)
    rod, m, k = problem.rod, problem.mass_kg, problem.hertz_k
    xs = [float(s) * rod.length_m for s in stations]
    bar = bar_model(rod, options.element, n_el, xs)
    M, K = bar.mass, bar.stiffness
    solve = splu((K + (4.0 / h**2) * M).tocsc()).solve
    e0 = end_vector(bar)
    g = solve(e0)
    b_rod = g[bar.end]
    static_end = splu(K).solve(e0)[bar.end] if rod.far_end == "fixed" else math.inf
    rod_momentum = M.T @ np.ones(M.shape[0])  # momentum of the rod = rod_momentum @ v

    d = M.shape[0]
    u, v, a = np.zeros(d), np.zeros(d), np.zeros(d)
    x, w, p, alpha = 0.0, problem.velocity_m_s, 0.0, 0.0
    T, P, X, W, U, AL = [0.0], [0.0], [0.0], [w], [0.0], [0.0]
    station_u, station_e = [bar.station_probes @ u], [bar.strain_probes @ u]
    e_rod_kin, e_rod_str = [0.0], [0.0]
    starts, ends = [0.0], []
    in_contact, n_newton = True, 0
    t_max = options.max_time_factor * problem.contact_time_estimate()
    status, message = "failed", ""
    t = 0.0
    while True:
        u_pred = solve(M @ ((4.0 / h**2) * u + (4.0 / h) * v + a))
        big_a = x + h * w - h * h * p / (4.0 * m) - u_pred[bar.end]
        big_b = h * h / (4.0 * m) + b_rod
        if big_a > 0.0:
            guess = 2.0 * AL[-1] - AL[-2] if len(AL) > 1 else big_a
            alpha_new, iterations = solve_hertz_step(big_a, big_b, k, guess)
            n_newton += iterations
            p_new = k * alpha_new**1.5
        else:
            alpha_new, p_new = big_a, 0.0
        u_new = u_pred + p_new * g
        a_new = (4.0 / h**2) * (u_new - u) - (4.0 / h) * v - a
        v_new = v + 0.5 * h * (a + a_new)
        x_new = x + h * w - h * h * (p + p_new) / (4.0 * m)
        w_new = w - h * (p + p_new) / (2.0 * m)
        if (p_new > 0.0) != in_contact:  # a contact ends or begins inside this step
            crossing = t + _hermite_root(AL[-1], alpha_new, w - v[bar.end], w_new - v_new[bar.end], h)
            (starts if p_new > 0.0 else ends).append(crossing)
            in_contact = p_new > 0.0
        u, v, a, x, w, p, alpha = u_new, v_new, a_new, x_new, w_new, p_new, alpha_new
        t += h
        T.append(t); P.append(p); X.append(x); W.append(w); U.append(u[bar.end]); AL.append(alpha)
        station_u.append(bar.station_probes @ u)
        station_e.append(bar.strain_probes @ u)
        e_rod_kin.append(0.5 * v @ (M @ v))
        e_rod_str.append(0.5 * u @ (K @ u))
        if not in_contact and ends and _no_further_contact(rod, x, w, e_rod_kin[-1] + e_rod_str[-1],
                                                           static_end, t - ends[-1], rod_momentum @ v):
            status, message = "completed", f"{len(ends)} contact(s); no further contact possible"
            break
        limit = limit_reached(starts, ends, t, t_max, options.max_contacts)
        if limit:
            status, message = limit
            break
    return _result(problem, options, locals())


def _no_further_contact(rod, x: float, w: float, rod_energy: float, static_end: float,
                        since_separation: float, rod_momentum: float) -> bool:
    """Fixed far end: the end can never be further out than sqrt(2 E_rod C_static), so an
    impactor moving away beyond that never returns (rigorous). Free far end: the impactor
    is no faster than the rod's centre of mass and has stayed clear for 8T (a heuristic:
    the end oscillates about the centre-of-mass motion)."""
    if rod.far_end == "fixed":
        return w <= 0.0 and x + math.sqrt(2.0 * rod_energy * static_end) < 0.0
    return w <= rod_momentum / rod.mass_kg and since_separation >= 4.0 * rod.reflection_period


def _result(problem: ImpactProblem, options: FEM1DOptions, s: dict) -> ImpactResult:
    time = np.asarray(s["T"])
    force = np.asarray(s["P"])
    alpha = np.asarray(s["AL"])
    velocity = np.asarray(s["W"])
    m, k = problem.mass_kg, problem.hertz_k
    kinetic = 0.5 * m * velocity**2
    contact = 0.4 * k * np.maximum(alpha, 0.0) ** 2.5
    rod_kin, rod_str = np.asarray(s["e_rod_kin"]), np.asarray(s["e_rod_str"])
    total = kinetic + contact + rod_kin + rod_str
    energy_error = float((total[0] - total[-1]) / total[0])
    ends = np.asarray(s["ends"])
    starts = np.asarray(s["starts"][: len(ends)])
    peak_t, peak_p = local_maxima(time, force)
    series = {
        "impactor_kinetic_energy": (kinetic, "J", "kinetic energy of the impactor"),
        "contact_energy": (contact, "J", "Hertz energy stored in the contact"),
        "rod_energy": (rod_kin + rod_str, "J", "energy in the rod (kinetic + strain)"),
        "rod_kinetic_energy": (rod_kin, "J", "kinetic energy of the rod, v^T M v / 2"),
        "rod_strain_energy": (rod_str, "J", "strain energy of the rod, u^T K u / 2"),
    }
    if problem.sphere_radius_m is not None:
        series["contact_radius"] = (np.sqrt(problem.sphere_radius_m * np.maximum(alpha, 0.0)), "m",
                                    "contact radius, Hertz: sqrt(R alpha)")
    extra: dict[str, Any] = {"n_elements": int(s["n_el"]), "element": options.element,
                             "n_dofs": int(s["d"]), "warnings": "; ".join(s["warnings"])}
    if s["xs"]:
        series["station_displacement"] = (np.asarray(s["station_u"]), "m",
                                          "axial displacement of the cross-sections at station_x_m (FEM)")
        series["station_strain"] = (np.asarray(s["station_e"]), "1",
                                    "axial strain du/dx at station_x_m (negative in compression; FEM)")
        extra["station_x_m"] = np.asarray(s["xs"])
    status, message = s["status"], s["message"]
    if status != "failed" and not math.isfinite(energy_error):
        status, message = "failed", "non-finite energy balance"
    return ImpactResult(
        success=status != "failed", status=status, message=message,
        scheme=f"fem1d-{options.element}-newmark", dt_s=float(s["h"]),
        time=time, contact_force=force, approach=alpha,
        impactor_displacement=np.asarray(s["X"]), impactor_velocity=velocity,
        rod_end_displacement=np.asarray(s["U"]),
        contact_start_s=starts, contact_end_s=ends, peak_time_s=peak_t, peak_force_N=peak_p,
        rebound_velocity_m_s=float(velocity[-1]), rod_energy_J=float(rod_kin[-1] + rod_str[-1]),
        energy_error=energy_error, n_steps=len(time) - 1, n_newton_iterations=int(s["n_newton"]),
        n_events=len(ends) + len(starts) - 1, wall_time_s=_time.perf_counter() - s["started"],
        extra=extra, extra_series=series,
    )
