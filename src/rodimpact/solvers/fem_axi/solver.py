"""``fem_axi``: axisymmetric elastodynamics of the rod and the impactor with frictionless
unilateral contact (Lagrange multipliers), in scikit-fem.

No Hertz law anywhere: the contact force is the sum of the multipliers, each the
per-radian nodal force that keeps one impactor surface node from entering the rod's end
face (2 pi times their sum is the force). Per step, with both bodies' Newmark matrices
factorised once and G = K_eff^-1 B^T precomputed for the candidate contact nodes
(:mod:`.contact`):

    g_free = g0 + B q_free,   lambda >= 0,  g_free + (B G) lambda >= 0,  complementary,

a small LCP solved exactly; then q = q_free + G lambda. A step costs one back-substitution
and one product K q per body (:mod:`.axibody`). After a step without contact force the run
ends as soon as the bodies' conserved energies prove that no gap can close again
(:mod:`.separation`). Where a material yields, each step iterates on the plastic regions' load
(:mod:`.plastic_step`) and the run goes on to its horizon (the energy bound holds for an elastic
flight, not about a residual stress state). The model it steps (:class:`~.aximodel.AxiModel`, from
:func:`~.aximodel.build_model`) is built in :mod:`.aximodel`; both names are re-exported here.
"""

from __future__ import annotations

import logging
import math
import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rodimpact.model.gauges import Gauge
from rodimpact.solvers.fem_axi.axibody import AxiBody
from rodimpact.solvers.fem_axi.aximodel import AxiModel, build_model
from rodimpact.solvers.fem_axi.contact import ContactOperator
from rodimpact.solvers.fem_axi.film_mesh import layers_within
from rodimpact.solvers.fem_axi.gauges import STATION_HALF_SPAN, continuum_cover_m, gauge_spans
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.plastic_step import PlasticBodies
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.separation import Flight, SeparationBound
from rodimpact.solvers.gauge_series import (
    checked_gauges,
    far_end_datasets,
    gauge_datasets,
    record_until_s,
    recorded_reach_m,
)
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.stepping import Outcome, StepHistory, energy_error, limit_reached

__all__ = ["AxiModel", "build_model", "solve_fem_axi"]

log = logging.getLogger(__name__)

#: Force maxima must stand out by this fraction of the largest force (see _result).
PEAK_PROMINENCE = 0.02


@dataclass(eq=False)
class _History(StepHistory):
    """The histories every run records, and fem_axi's own: the contact radius, both bodies'
    kinetic and strain energies, the stations' and the gauges' probes, the far end's velocity
    and the LCP solves."""

    radius: list[float] = field(default_factory=list)
    kin_i: list[float] = field(default_factory=list)
    str_i: list[float] = field(default_factory=list)
    kin_r: list[float] = field(default_factory=list)
    str_r: list[float] = field(default_factory=list)
    stations: list[NDArray[np.float64]] = field(default_factory=list)
    gauges: list[NDArray[np.float64]] = field(default_factory=list)
    far_v: list[float] = field(default_factory=list)
    dissipated: list[float] = field(default_factory=list)
    n_lcp: int = 0


def _crossing(previous: float, last: float, h: float) -> float:
    """Where a force that vanishes like (t_c - t)^(3/2) reaches zero after its last positive
    value ``last`` (``previous`` one step earlier): P^(2/3) extrapolated linearly, in (0, h]."""
    y0, y1 = previous ** (2.0 / 3.0), last ** (2.0 / 3.0)
    if y1 >= y0:
        return 0.5 * h
    return min(h, y1 / (y0 - y1) * h)


def solve_fem_axi(
    problem: AxiImpact,
    options: FEMAxiOptions | None = None,
    stations: Sequence[float] = (),
    gauges: Sequence[Gauge] = (),
    far_end_velocity: bool = False,
) -> ImpactResult:
    """Solve the impact with the axisymmetric continuum model.

    Parameters
    ----------
    problem : AxiImpact
    options : FEMAxiOptions, optional
    stations : sequence of float
        Fractions of the rod length from the struck end where the cross-section-averaged
        axial displacement (and strain) are recorded, shape (n, k).
    gauges : sequence of Gauge
        Strain gauges (:class:`~rodimpact.model.gauges.Gauge`) bonded on the rod's surface
        r = a: ``gauge_strain`` (n, k) is the difference of u_z(a, z) between the gauge's
        ends over its length (a point gauge: over the sections STATION_HALF_SPAN L either
        side, one-sided at an end of the rod, :mod:`.gauges`), ``gauge_mean_strain`` the same
        of the cross-section mean u_z. The continuum then reaches one rod diameter beyond the
        last gauge's far end (the rest of a long rod stays a bar; the whole rod is a continuum
        when less than a diameter would be left): the model, and so every history, differs
        slightly from a run without gauges.
    far_end_velocity : bool
        Also record the cross-section mean axial velocity at z = L (the bar's last node when
        the far part is a bar; zero at a fixed far end), ``far_end_velocity``, m/s.

        With gauges or the far end's velocity, a run that has proven that no further contact is
        possible keeps stepping, past the time limit, until every wave its last contact sent has
        passed the farthest section recorded at the rod's bar speed sqrt(E/rho)
        (:func:`~rodimpact.solvers.gauge_series.record_until_s`; the summary's
        ``recorded_until_s``; the energy balance is taken at the node where the proof came).

    Returns
    -------
    ImpactResult
        Contact force (2 pi times the sum of the multipliers), contact intervals and
        maxima; ``approach`` is the impactor's displacement (its rigid part, or the ball's
        centre of mass) minus the mean displacement of the rod's end face (z = 0, over the
        rod's whole cross-section): with a film this is the face under the film, so the
        approach includes the film's compression; extra series: ``contact_radius`` and the
        energies (``contact_energy`` holds the impactor's strain energy; the film's strain
        and kinetic energies are in the rod's); extra summary: mesh and DOF counts, the
        largest contact radius, and with a film ``film_thickness_m``, ``film_radius_m``,
        ``film_elements`` and ``film_elements_through_thickness`` (under the contact zone,
        r <= contact_extent estimated contact radii).
    """
    options = FEMAxiOptions() if options is None else options
    started = _time.perf_counter()
    gauges = checked_gauges(gauges, problem.rod_length_m)
    cover = continuum_cover_m(gauges, problem.rod_radius_m, problem.rod_length_m)
    model = build_model(problem, options, continuum_cover_m=cover)
    rod, imp, B_rod, B_imp, gap0, r_c = model.rod, model.impactor, model.B_rod, model.B_imp, model.gap0, model.r_c
    t_contact = model.scales.contact_time_s
    h = options.step(t_contact)
    rod.factorise(h)
    imp.factorise(h)
    contact = ContactOperator.of(rod, imp, B_rod, B_imp, gap0)
    rod.start(0.0)
    imp.start(problem.velocity_m_s)
    plastic = PlasticBodies.of(problem, model, options)
    length = problem.rod_length_m
    face = rod.section_mean_uz_row(0.0, problem.rod_radius_m)
    delta = STATION_HALF_SPAN * length
    rows = [
        rod.section_mean_uz_row(z, problem.rod_radius_m)
        for s in stations
        for z in (s * length, max(s * length - delta, 0.0), min(s * length + delta, length))
    ]
    probes = sp.vstack(rows).tocsr() if rows else None
    gauge_probes = _gauge_probes(rod, gauges, problem) if gauges else None
    far_row = rod.section_mean_uz_row(length, problem.rod_radius_m) if far_end_velocity else None
    mean_weights = imp.momentum_weights / (imp.total_mass_kg / (2 * math.pi))

    c_rod = math.sqrt(problem.rod_material.youngs_modulus_pa / problem.rod_material.density_kg_m3)
    spring = math.pi * math.sqrt(
        problem.mass_kg * length / (problem.rod_material.youngs_modulus_pa * math.pi * problem.rod_radius_m**2)
    )
    t_max = options.max_time_factor * (t_contact + spring + 2 * length / c_rod)
    hist = _History()

    def record(t: float, force: float, radius: float) -> None:
        x, u_face = float(mean_weights @ imp.q), float((face @ rod.q)[0])
        hist.t.append(t)
        hist.force.append(force)
        hist.radius.append(radius)
        hist.x.append(x)
        hist.w.append(float(mean_weights @ imp.v))
        hist.u_end.append(u_face)
        hist.alpha.append(x - u_face)
        hist.kin_i.append(imp.kinetic_energy())
        hist.kin_r.append(rod.kinetic_energy())
        if plastic is None:
            hist.str_i.append(imp.strain_energy())
            hist.str_r.append(rod.strain_energy())
        else:
            hist.str_i.append(imp.strain_energy() + plastic.stored_correction(1, imp.q))
            hist.str_r.append(rod.strain_energy() + plastic.stored_correction(0, rod.q))
            hist.dissipated.append(plastic.dissipated_J)
        if probes is not None:
            hist.stations.append(probes @ rod.q)
        if gauge_probes is not None:
            hist.gauges.append(gauge_probes @ rod.q)
        if far_row is not None:
            hist.far_v.append(float((far_row @ rod.v)[0]))

    record(0.0, 0.0, 0.0)
    starts, ends, in_contact = hist.starts, hist.ends, True
    reach = recorded_reach_m(gauges, far_end_velocity, length)
    # the node at which no further contact was proven (where a run that records nothing ends)
    finished: int | None = None
    t = 0.0
    status, message = "failed", ""
    bound: SeparationBound | None = None
    flight: Flight | None = None
    while True:
        q_rod, q_imp = rod.predict(), imp.predict()
        force, radius, load_rod, load_imp = 0.0, 0.0, 0.0, 0.0
        if plastic is None:
            gap = contact.gaps(q_rod, q_imp)
            if gap.min() < 0.0:
                lam = contact.multipliers(gap)
                if lam.any():
                    d_rod, d_imp, load_rod, load_imp = contact.corrections(lam)
                    q_rod, q_imp = q_rod + d_rod, q_imp + d_imp
                    force, radius = 2 * math.pi * float(lam.sum()), float(r_c[lam > 0.0].max())
                hist.n_lcp += 1
        else:
            step = plastic.step(contact, q_rod, q_imp)
            if step is None:
                status, message = "failed", f"the plastic load did not converge at t = {t + h:.6g} s"
                break
            q_rod, q_imp, load_rod, load_imp = step.q_rod, step.q_imp, step.load_rod, step.load_imp
            if step.lam.any():
                force, radius = 2 * math.pi * float(step.lam.sum()), float(r_c[step.lam > 0.0].max())
                hist.n_lcp += 1
        rod.advance(q_rod, load_rod)
        imp.advance(q_imp, load_imp)
        if plastic is not None and plastic.accept() >= 1.0:
            status, message = (
                "failed",
                (
                    f"at t = {t + h:.6g} s the elastic stress beyond a plastic region reaches "
                    f"{plastic.worst_guard:.3g} of the yield stress: raise plastic_extent"
                ),
            )
            break
        t += h
        record(t, force, radius)
        if in_contact and force == 0.0:
            p = hist.force
            ends.append(t - h + _crossing(p[-3] if len(p) > 2 else 0.0, p[-2], h))
            in_contact = False
        elif not in_contact and force > 0.0:
            starts.append(t - h)
            in_contact, flight, finished = True, None, None
        if plastic is None and not in_contact and ends and finished is None:
            # a step without contact force: the free flight's conserved quantities bound the gaps
            if flight is None:
                bound = bound or SeparationBound.of(rod, imp, contact)
                flight = bound.flight(rod, imp)
            if flight.holds(rod, imp):
                finished = len(hist.t) - 1
                status, message = (
                    "completed",
                    (
                        f"{len(ends)} contact(s); no further contact possible "
                        f"(energy bound, {t - ends[-1]:.3g} s after the last)"
                    ),
                )
        if finished is not None:
            # a run that records gauges or the far end goes on, without the time limit, until every
            # wave the last contact sent has passed the farthest section it records (at the rod's
            # bar speed: the slowest front that matters for the pulse's end)
            if reach is None or t >= record_until_s(ends[-1], reach, c_rod):
                break
            continue
        limit = limit_reached(starts, ends, t, t_max, options)
        if limit:
            status, message = limit
            break
    recorded_until = record_until_s(ends[-1], reach, c_rod) if reach is not None and finished is not None else None
    return _result(
        problem,
        model,
        hist,
        tuple(float(s) for s in stations),
        Outcome(status, message, _time.perf_counter() - started),
        h,
        delta,
        gauges,
        far_row is not None,
        finished,
        recorded_until,
        plastic,
    )


def _gauge_probes(rod: AxiBody, gauges: tuple[Gauge, ...], problem: AxiImpact) -> sp.csr_matrix:
    """The gauges' strain rows on the rod's free coordinates, shape (2k, n): at the surface
    r = a (rows 0..k-1), then of the cross-section mean u_z (rows k..2k-1); each the
    difference of u_z between the two sections of :func:`~.gauges.gauge_spans` over their
    distance."""
    radius, spans = problem.rod_radius_m, gauge_spans(gauges, problem.rod_length_m)
    end = rod.bar.start_m if rod.bar is not None else problem.rod_length_m
    if max(high for _, high in spans) > end:
        raise ValueError(f"a gauge reaches beyond the continuum (z_c = {end:g} m): its surface strain is not modelled")
    low, high = np.array(spans).T
    surface = rod.uz_probe_rows(np.vstack([np.full(2 * len(spans), radius), np.concatenate([low, high])]))
    k = len(spans)
    scale = sp.diags(1.0 / (high - low))
    mean = sp.vstack([rod.section_mean_uz_row(z2, radius) - rod.section_mean_uz_row(z1, radius) for z1, z2 in spans])
    return sp.vstack([scale @ (surface[k:] - surface[:k]), scale @ mean]).tocsr()


def _result(
    problem: AxiImpact,
    model: AxiModel,
    hist: _History,
    stations: tuple[float, ...],
    outcome: Outcome,
    h: float,
    delta: float,
    gauges: tuple[Gauge, ...] = (),
    far_end: bool = False,
    finished: int | None = None,
    recorded_until: float | None = None,
    plastic: PlasticBodies | None = None,
) -> ImpactResult:
    """The run's result. Its energy balance and the rod's energy are those at the node where no
    further contact was proven (``finished``; the last node when None), where a run that records
    nothing ends; ``recorded_until`` (s): the time a run that records had to reach, in the
    summary's ``recorded_until_s``."""
    rod, imp, length = model.rod, model.impactor, problem.rod_length_m
    nodes = hist.nodes()
    end = len(nodes.time) if finished is None else finished + 1
    kin_i, str_i = np.asarray(hist.kin_i), np.asarray(hist.str_i)
    kin_r, str_r = np.asarray(hist.kin_r), np.asarray(hist.str_r)
    radius = np.asarray(hist.radius)
    if len(model.r_c) and radius.max() >= model.r_c.max():
        log.warning(
            "the contact reached the edge of the candidate zone (r = %.3g m): raise contact_extent",
            float(model.r_c.max()),
        )
    series = {
        "contact_radius": (
            radius,
            "m",
            "radius of the outermost candidate node in contact (the impactor's; the film's with a film)",
        ),
        "impactor_kinetic_energy": (kin_i, "J", "kinetic energy of the impactor (elastic part and rigid part)"),
        "contact_energy": (
            str_i,
            "J",
            "strain energy of the impactor (holds what a contact law lumps into the contact)",
        ),
        "rod_energy": (kin_r + str_r, "J", "energy in the rod (kinetic + strain)"),
        "rod_kinetic_energy": (kin_r, "J", "kinetic energy of the rod"),
        "rod_strain_energy": (str_r, "J", "strain energy of the rod"),
    }
    extra: dict[str, Any] = {
        "rod_dofs": int(rod.n),
        "impactor_dofs": int(imp.n),
        "rod_elements": int(rod.basis.mesh.t.shape[1]),
        "impactor_elements": int(imp.basis.mesh.t.shape[1]),
        "fine_size_m": float(model.fine_size_m),
        "estimated_contact_radius_m": float(model.scales.contact_radius_m),
        "max_contact_radius_m": float(radius.max()),
        "n_lcp_solves": int(hist.n_lcp),
        "impactor_mass_kg": float(imp.total_mass_kg),
        "continuum_length_m": float(rod.bar.start_m if rod.bar else problem.rod_length_m),
        "bar_elements": int(rod.bar.elements if rod.bar else 0),
        # with no yielding region the contact dissipates nothing and leaves no dent
        "dissipated_energy_J": 0.0,
        "residual_approach_m": 0.0,
    }
    parts = (kin_i[:end], str_i[:end], kin_r[:end], str_r[:end])
    if plastic is not None:
        dissipated = np.asarray(hist.dissipated)
        parts = (*parts, dissipated[:end])
        force = np.asarray(hist.force)
        first_end = int(np.argmax((force[1:] == 0.0) & (force[:-1] > 0.0))) + 1 if np.any(force > 0) else 0
        extra.update(
            dissipated_energy_J=float(dissipated[end - 1]),
            residual_approach_m=float(np.asarray(hist.alpha)[first_end]) if first_end else 0.0,
            plastic_iterations=int(plastic.iterations),
            plastic_region_m=float(next(p for p in (plastic.rod, plastic.impactor) if p is not None).region.radius_m),
            plastic_guard=float(plastic.worst_guard),
        )
        series["contact_dissipated_energy"] = (dissipated, "J", "plastic work done in the bodies so far")
    if model.film is not None:
        film = model.film
        extra.update(
            film_thickness_m=float(film.film_thickness_m),
            film_radius_m=float(film.film_radius_m),
            film_elements=int(film.film_elements.size),
            film_elements_through_thickness=layers_within(film, film.body.contact_extent_m),
        )
        if len(film.layer_elements) > 1:
            extra["stack_layers"] = len(film.layer_elements)
    if stations:
        values = np.asarray(hist.stations).reshape(len(nodes.time), len(stations), 3)
        series["station_displacement"] = (values[:, :, 0], "m", "cross-section mean axial displacement at station_x_m")
        # the sections' distance: 2 delta inside, delta at either end of the rod
        spans = np.asarray([min(s * length + delta, length) - max(s * length - delta, 0.0) for s in stations])
        series["station_strain"] = (
            (values[:, :, 2] - values[:, :, 1]) / spans,
            "1",
            "cross-section mean axial strain at station_x_m (negative in compression)",
        )
        extra["station_x_m"] = np.asarray([s * length for s in stations])
    if gauges:
        values = np.asarray(hist.gauges)
        k = len(gauges)
        gauge_series, gauge_summary = gauge_datasets(
            gauges, values[:, :k], "at the rod's surface r = a", mean_strain=values[:, k:]
        )
        series.update(gauge_series)
        extra.update(gauge_summary)
    if far_end:
        series.update(far_end_datasets(np.asarray(hist.far_v), "cross-section mean, Newmark's velocity"))
    if recorded_until is not None:
        extra["recorded_until_s"] = float(recorded_until)
    # nodes enter the contact one at a time: ripples far smaller than the physical maxima
    return hist.result(
        nodes,
        outcome,
        scheme="fem_axi-newmark-lcp",
        dt_s=h,
        energy_error=energy_error(*parts),
        rod_energy_J=float(kin_r[end - 1] + str_r[end - 1]),
        n_events=len(hist.ends),
        extra=extra,
        extra_series=series,
        min_prominence=PEAK_PROMINENCE * nodes.force.max(),
    )
