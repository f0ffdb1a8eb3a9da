"""The impact of a rigid mass on a rigid flat through the thin-layer law, in closed form and by
Gauss-Legendre quadrature (numpy only).

The law of :class:`~rodimpact.contact.film.HertzFilmLaw` (and of the stack, in series) reads, in
s = P^(1/6),

    alpha = A s^4 + B s^3,    E = int_0^alpha P d alpha = 0.4 A s^10 + B s^9 / 3,

with A = k^(-2/3) (Hertz) and B = c^(-1/2) (the layer). A rigid mass m striking at v0 stops at
s_max, where E(s_max) = m v0^2 / 2, and the contact lasts

    t_c = 2 int_0^alpha_max d alpha / v,    v = sqrt(2 (E(s_max) - E(s)) / m).

With E(s_max) - E(s) = (s_max - s) Q(s), Q = 0.4 A S_10 + B S_9 / 3 and S_n = sum_k s_max^k
s^(n-1-k) (sums of positive terms: no cancellation), and s = s_max - u^2,

    t_c = 4 sqrt(m / 2) int_0^sqrt(s_max) (4 A s^3 + 3 B s^2) / sqrt(Q(s)) du.

The integrand is analytic on the interval: Q is positive there (its zeros lie near
s_max e^(2 pi i j / 10), j = 1..9, off the real axis), so Gauss-Legendre quadrature converges
geometrically: 24 nodes already agree with 200 to 2.3e-15 over films from 1e-6 to 1e20 N/m^2 and
impacts from 1 mg at 50 m/s to 10 kg at 1 cm/s, and :data:`NODES` is 32
(``tests/test_film_law.py`` checks it against Hertz's closed form and against adaptive
quadrature). A configuration check
computes this for every distinct law of a project: it needs no scipy and no nested
quadrature.
"""

from __future__ import annotations

import math

import numpy as np

from rodimpact.contact.law import MAX_STEP_ITERATIONS, RigidImpact, StepNotConverged, check_positive

__all__ = ["NODES", "thin_layer_rigid_impact"]

#: Gauss-Legendre nodes of the contact-time integral.
NODES = 32

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(NODES)


def _stop_root(a: float, b: float, energy_J: float) -> float:
    """s_max >= 0 with 0.4 A s^10 + B s^9 / 3 = energy (> 0): Newton from above.

    The left side is increasing and convex for s > 0, and the root of each term alone lies above
    the root of the sum: Newton from the smaller of those decreases monotonically to the root.
    """
    terms = [(0.4 * a, 10.0), (b / 3.0, 9.0)]
    s = min((energy_J / c) ** (1.0 / p) for c, p in terms if c > 0.0)
    for _ in range(MAX_STEP_ITERATIONS):
        s8 = s**8
        f = (0.4 * a * s + b / 3.0) * s8 * s - energy_J
        slope = (4.0 * a * s + 3.0 * b) * s8
        if f <= 0.0 or slope <= 0.0:
            return s
        s_new = s - f / slope
        if s_new >= s or s - s_new <= 4e-16 * s:
            return max(s_new, 0.0)
        s = s_new
    raise StepNotConverged(f"the thin-layer law's largest approach did not converge (energy={energy_J!r} J)")


def thin_layer_rigid_impact(a: float, b: float, mass_kg: float, velocity_m_s: float) -> RigidImpact:
    """The rigid impact through alpha = A s^4 + B s^3, P = s^6 (the module's docstring).

    Parameters
    ----------
    a : float
        A = k^(-2/3), m / N^(2/3) (> 0, or 0 with ``b`` > 0).
    b : float
        B = c^(-1/2), m / N^(1/2) (>= 0; 0 is Hertz's law).
    mass_kg, velocity_m_s : float
        The impactor's mass, kg, and velocity, m/s, as for :meth:`.ContactLaw.rigid_impact`.

    Returns
    -------
    RigidImpact
        alpha_max = A s_max^4 + B s_max^3, the contact time, and the peak force s_max^6.
    """
    check_positive(mass_kg=mass_kg, velocity_m_s=velocity_m_s)
    s_max = _stop_root(a, b, 0.5 * mass_kg * velocity_m_s**2)
    root = math.sqrt(s_max)
    u = 0.5 * root * (_NODES + 1.0)  # the nodes on [0, sqrt(s_max)]
    s = s_max - u * u
    ratio = s / s_max
    # S_n / s_max^(n-1) = sum_{j<n} ratio^j, by Horner (positive terms)
    sum9 = np.ones_like(ratio)
    for _ in range(8):
        sum9 = sum9 * ratio + 1.0
    sum10 = sum9 * ratio + 1.0
    q = 0.4 * a * s_max**9 * sum10 + (b / 3.0) * s_max**8 * sum9
    integrand = (4.0 * a * s + 3.0 * b) * s * s / np.sqrt(q)
    integral = 0.5 * root * float(_WEIGHTS @ integrand)
    return RigidImpact(
        max_approach_m=(a * s_max + b) * s_max**3,
        contact_time_s=4.0 * math.sqrt(0.5 * mass_kg) * integral,
        peak_force_N=s_max**6,
    )
