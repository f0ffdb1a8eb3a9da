"""The paper's materials and problems the physics tests share: the balls' steel and the
experiment's aluminium (Table 1), the Model problem of Table 1, Table 2's two-contact case, and
an end-pressure pulse driven through an axisymmetric rod."""

from __future__ import annotations

import math
from dataclasses import dataclass

from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.model.materials import Material
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod

#: The balls and the Model column of Table 1 (docs/paper-notes.md, "Materials").
STEEL = Material(2.1e11, 0.30, 7800.0, "steel")
#: The experiment's rod: Table 1, column Experiment (docs/paper-notes.md, "Materials").
ALUMINIUM = Material(7.342e10, 0.34, 2696.6, "aluminium")


@dataclass(frozen=True)
class PulseRun:
    """What :func:`end_pulse_response` recorded: the station's displacement (m), d'Alembert's
    there (m), the body's energy after the pulse (J), the 1-D history and rod behind d'Alembert."""

    values: object
    exact: object
    energies: object
    history: object
    rod: Rod


def end_pulse_response(body, load, station, length: float, area: float, h: float, duration: float) -> PulseRun:
    """Drive an axisymmetric rod ``body`` (factorised at step ``h``, started at rest) by a smooth
    end-pressure pulse of 1 MPa peak and ``duration`` s through its unit-pressure ``load``, for
    2.2 wave transits of ``length``; record the ``station`` row's displacement.

    d'Alembert's 1-D displacement is taken at the station's height, ``0.75 length``."""
    import numpy as np

    from rodimpact.solvers.sem.history import ForceHistory

    def pressure(t):
        return 1e6 * np.sin(np.pi * np.clip(t, 0, duration) / duration) ** 2

    rod = Rod(length, area, STEEL)
    history = ForceHistory(rod, linear=True)
    unit = body.solve(load)
    times, values, energies = [0.0], [0.0], []
    for n in range(1, int(2.2 * length / rod.wave_speed / h)):
        t = n * h
        body.advance(body.predict() + pressure(t) * unit)
        history.append(t, float(pressure(t) * area))
        times.append(t)
        values.append(float((station @ body.q)[0]))
        if t > duration:
            energies.append(body.kinetic_energy() + body.strain_energy())
    exact = history.displacement_at(0.75 * length, np.asarray(times))
    return PulseRun(np.asarray(values), exact, np.asarray(energies), history, rod)


def model_problem(far_end: str = "fixed") -> ImpactProblem:
    """Table 1, column Model: a 0.5 kg steel impactor (R = 10 mm) at 1 m/s on a 0.5 m steel rod."""
    return ImpactProblem(0.5, 1.0, HertzLaw(hertz_constant(0.01, STEEL)), Rod(0.5, 5e-5, STEEL, far_end))


def two_contact_problem() -> ImpactProblem:
    """Table 2's 5.56 mm steel ball (0.71 g, R = 2.78 mm) at 0.3225 m/s on the thin 301 mm
    aluminium rod (radius 1 mm): the ball strikes twice."""
    return ImpactProblem(
        0.71e-3, 0.3225, HertzLaw(hertz_constant(2.78e-3, STEEL, ALUMINIUM)), Rod(0.301, math.pi * 1e-6, ALUMINIUM)
    )
