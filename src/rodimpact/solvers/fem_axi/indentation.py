"""Static indentation of the rod's end face by the impactor's elastic cap (verification).

The cap's rigid back is pushed towards the rod by d; the multipliers solve the static
contact LCP exactly as in :mod:`.fem_axi`. With the bulk of both bodies adding a linear
compliance C, Hertz predicts d = (P / k)^(2/3) + C P with k = (4/3) E* sqrt(R), and the
contact radius a = (3 P R / (4 E*))^(1/3): a check of the continuum against the Hertz law.

With a film or stack (``problem.stack``) the cap presses its surface and the rod is the rod
and its layers (:mod:`.film_mesh`): the force against the rigid back's displacement is the static
force-approach curve P(d) of the film-coated rod (d includes the cap's, the film's and the
rod's compliance). The mean axial displacements of the rod's end face (z = 0, under the film)
and of the struck surface are returned too: d minus the first is the approach relative to
the rod's end face, as in :func:`~rodimpact.solvers.fem_axi.solver.solve_fem_axi`.

Where a material yields (the cap, a layer or the rod's struck end), the displacements are a
path, solved in order from the history the last one left: each body's elastic operators are
condensed once on its plastic region (:mod:`.plastic_region`) and the contact candidates, and
each displacement is a Newton iteration on the region's equilibrium with J2's consistent
tangent (:mod:`.plasticity`), the contact's LCP solved with the tangent's Delassus operator
at every iterate (the gaps are linear in the displacements, so a converged iterate satisfies
the contact exactly). A path that goes down again unloads: the force falls on another curve,
and the last displacement where the force vanishes marks the dent.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.linalg import cholesky, solve_triangular
from scipy.optimize import nnls

from rodimpact.solvers.fem_axi.axibody import spd_inverse_rows
from rodimpact.solvers.fem_axi.aximodel import AxiModel, material_groups
from rodimpact.solvers.fem_axi.axisym import cross_section_mean_uz
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.plastic_region import PlasticRegion, YieldGuard, plastic_region
from rodimpact.solvers.fem_axi.plasticity import J2State
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import build_model

__all__ = ["NEWTON_FLOOR_RTOL", "NEWTON_RTOL", "Indentation", "UnloadingPlan", "static_indentation"]

log = logging.getLogger(__name__)

NEWTON_RTOL = 1e-10
"""A displacement's Newton iteration has converged when the out-of-balance force on the plastic
regions is below this fraction of the larger of the contact force and the plastic strain's load
(the residual stresses' scale, which stays when the contact force vanishes), both per radian."""
NEWTON_FLOOR_RTOL = 1e-8
"""A residual below this fraction of the same scale that no longer falls (not halved over the
last ``NEWTON_STALL`` iterations) is the solves' rounding floor and counts as converged: a
perfectly plastic layer a few micrometres thick between steel and aluminium makes the consistent
tangent ill-conditioned enough (the layers' 2-10 GPa against the bodies' 70-200 GPa, elements 5
to 7 um thick) that the iteration settles near 1e-9 of the force scale (the sensor's 12.73 mm
ball: 4 of its 143 path points)."""
NEWTON_STALL = 4
"""Iterations over which a residual must halve to count as still falling."""
MAX_NEWTON = 60
"""Newton iterations allowed per displacement."""
MAX_CUTS = 4
"""Halvings of a displacement increment that failed (its iteration did not converge, or its
state left the plastic region) before the path fails: an increment is retried as two halves from
the last converged state, down to 1/16 of it."""


@dataclass(frozen=True)
class UnloadingPlan:
    """Unloading curves taken along an elastic-plastic indentation's loading path.

    Parameters
    ----------
    every : int
        An unloading curve from the first loading displacement that dissipates, from every
        ``every``-th after it, and from the last (>= 1).
    points : int
        Displacements of each unloading curve, evenly spaced from its maximum down to zero (it
        stops at the first with no force) (>= 3).
    reload : int
        Displacements back up to the maximum before the path goes on (>= 1).
    """

    every: int = 4
    points: int = 12
    reload: int = 3

    def __post_init__(self) -> None:
        for name, least in (("every", 1), ("points", 3), ("reload", 1)):
            value = getattr(self, name)
            if not isinstance(value, int) or value < least:
                raise ValueError(f"{name} must be an integer >= {least}, got {value!r}")


@dataclass(frozen=True)
class Indentation:
    """A static indentation, one entry per displacement of the rigid back (shape (n,) each).

    Attributes
    ----------
    displacement_m : ndarray
        Displacement d of the cap's rigid back towards the rod, m.
    force_N : ndarray
        Contact force, N.
    contact_radius_m : ndarray
        Radius of the outermost candidate node in contact (the cap's; the film's surface node
        with a film), m.
    node_spacing_m : float
        Smallest radial spacing of the candidate contact nodes, m.
    face_displacement_m : ndarray
        Mean axial displacement of the rod's end face z = 0 over the rod's cross-section (under
        the film, if any), m (positive into the rod).
    surface_displacement_m : ndarray
        Mean axial displacement of the struck surface: the film's disc z = -h, r <= r_f with a
        film, the end face without, m.
    plastic_work_J : ndarray or None
        The plastic work done from the start of the path to each displacement, J (None: no
        material yields).
    yielded_points : ndarray of int or None
        Quadrature points that yielded at each displacement.
    newton_iterations : int
        Newton iterations over the path (0: elastic, one solve per displacement).
    elastic_tangent_iterations : int
        Of them, those whose consistent tangent was singular (a perfectly plastic zone) and that
        took the elastic tangent instead.
    floor_converged : int
        Displacements whose iteration settled at the solves' rounding floor (below
        ``NEWTON_FLOOR_RTOL``, no longer falling) rather than below ``NEWTON_RTOL``.
    increment_cuts : int
        Displacement increments halved because they failed (``MAX_CUTS``).
    status : {"ok", "not_converged", "plastic_region", "contact_extent"}
        "not_converged": a displacement's Newton iteration did not converge within
        ``MAX_NEWTON``; "plastic_region": the elastic stress beyond a plastic region reached the
        yield stress (raise ``plastic_extent``); "contact_extent": the contact reached the
        outermost candidate (raise ``contact_extent``; checked where a material yields, whose
        contact outgrows Hertz's). The arrays hold the displacements solved before.
    message : str
        Why, when ``status`` is not "ok".
    unloading_curve : ndarray of int or None
        With an :class:`UnloadingPlan`, for each point of the unloading curves, the index of the
        loading displacement its curve starts from (the curve's maximum), shape (u,).
    unloading_displacement_m, unloading_force_N : ndarray or None
        The unloading curves' displacements and forces, in path order (each curve from just below
        its maximum down to its first point with no force), m and N, shape (u,).
    """

    displacement_m: NDArray[np.float64]
    force_N: NDArray[np.float64]
    contact_radius_m: NDArray[np.float64]
    node_spacing_m: float
    face_displacement_m: NDArray[np.float64] | None = None
    surface_displacement_m: NDArray[np.float64] | None = None
    plastic_work_J: NDArray[np.float64] | None = None
    yielded_points: NDArray[np.int64] | None = None
    newton_iterations: int = 0
    elastic_tangent_iterations: int = 0
    floor_converged: int = 0
    increment_cuts: int = 0
    status: str = "ok"
    message: str = ""
    unloading_curve: NDArray[np.int64] | None = None
    unloading_displacement_m: NDArray[np.float64] | None = None
    unloading_force_N: NDArray[np.float64] | None = None

    @property
    def success(self) -> bool:
        """Every displacement was solved (``status`` "ok")."""
        return self.status == "ok"


def static_indentation(
    problem: AxiImpact,
    displacements_m: Sequence[float],
    options: FEMAxiOptions | None = None,
    unloading: UnloadingPlan | None = None,
    until_force_N: float | None = None,
) -> Indentation:
    """Push the rigid back of a ``cap`` impactor by each displacement and solve the contact.

    Parameters
    ----------
    problem : AxiImpact
        Must have ``body="cap"`` and a fixed far end.
    displacements_m : sequence of float
        Displacements d of the rigid back towards the rod, m (> 0); where a material yields, a
        path in this order (a displacement below the last unloads).
    options : FEMAxiOptions, optional
        The mesh's settings (``elements_across``, ``contact_extent``, ``cap_height``, ``element``).
    unloading : UnloadingPlan, optional
        Where a material yields, the unloading curves to take along the path (the continuum's
        law with memory); None: none. Ignored where nothing yields (the loading curve is the
        unloading curve).
    until_force_N : float, optional
        Where a material yields, the path ends at the first loading displacement whose force
        reaches this, N (its unloading curve taken, with a plan); None: every displacement.

    Returns
    -------
    Indentation
    """
    if problem.body != "cap" or problem.far_end != "fixed":
        raise ValueError("problem: static indentation needs body='cap' and a fixed far end")
    options = FEMAxiOptions() if options is None else options
    model = build_model(problem, options, dynamic=False)  # statics: no mass matrices
    if problem.yields:
        return _plastic_path(problem, model, displacements_m, options, unloading, until_force_N)
    rod, imp, B_rod, B_imp, gap0, r_c, fine = (
        model.rod,
        model.impactor,
        model.B_rod,
        model.B_imp,
        model.gap0,
        model.r_c,
        model.fine_size_m,
    )
    free = np.arange(imp.n - 1)  # the rigid coordinate W (last) is prescribed
    # the Delassus operator B K^-1 B^T of each body from its factor's elimination tree alone
    # (spd_inverse_rows): no full solve per candidate
    delassus_rod, solve_rod = spd_inverse_rows(rod.K, B_rod)
    delassus_imp, _ = spd_inverse_rows(imp.K[free][:, free], B_imp[:, free])
    chol = cholesky(delassus_rod + delassus_imp, lower=True)
    # the rod's displacement is K^-1 B^T lam: the mean displacements are (K^-1 rows^T)^T B^T lam
    face, surface = _mean_rows(problem, model)
    means = np.asarray(B_rod @ solve_rod(np.column_stack([face.toarray().ravel(), surface.toarray().ravel()]))).T
    # a rigid translation of the whole cap by d closes every gap by d
    forces, radii, moved = [], [], []
    for d in displacements_m:
        gap = gap0 - d
        lam, _ = nnls(chol.T, -solve_triangular(chol, gap, lower=True), maxiter=50 * len(gap0))
        forces.append(2 * math.pi * lam.sum())
        radii.append(float(r_c[lam > 0].max()) if (lam > 0).any() else 0.0)
        moved.append(means @ lam)
    spacing = float(np.min(np.diff(np.unique(r_c)))) if len(r_c) > 1 else fine
    moved_a = np.asarray(moved).reshape(-1, 2)
    return Indentation(
        np.asarray(displacements_m, float),
        np.asarray(forces),
        np.asarray(radii),
        spacing,
        face_displacement_m=moved_a[:, 0],
        surface_displacement_m=moved_a[:, 1],
    )


@dataclass
class _CondensedBody:
    """A body that yields, condensed on the coordinates its plastic region and its contact
    candidates touch (k of them): the elastic rest is eliminated once,

        K_c = K_kk - K_kx K_xx^-1 K_xk,

    a sparse matrix with a dense block on the coordinates next to the rest (the rest keeps its
    one factorisation), and each Newton iterate factorises K_c + dK (dK on the yielded points'
    coordinates only)."""

    region: PlasticRegion
    kept: NDArray[np.int64]
    region_at: NDArray[np.int64]
    K_c: sp.csc_matrix
    B: sp.csr_matrix
    extra: NDArray[np.float64]
    rest: NDArray[np.int64]
    rest_solve: object
    coupling: sp.csr_matrix
    n: int
    state: J2State
    q: NDArray[np.float64]
    _elastic: object = None

    @classmethod
    def of(cls, K: sp.spmatrix, B: sp.spmatrix, region: PlasticRegion, extra: sp.spmatrix | None) -> _CondensedBody:
        K = sp.csr_matrix(K)
        n = K.shape[0]
        B = sp.csr_matrix(B)
        kept = np.union1d(region.coordinates, np.unique(B.indices)).astype(np.int64)
        rest = np.setdiff1d(np.arange(n), kept).astype(np.int64)
        K_kx = sp.csr_matrix(K[kept][:, rest])
        # the kept coordinates next to the rest: the only rows of the Schur complement
        border = np.flatnonzero(np.diff(K_kx.indptr))
        schur, rest_solve = spd_inverse_rows(K[rest][:, rest], K_kx[border])
        coo = sp.coo_matrix(schur)
        correction = sp.csr_matrix((coo.data, (border[coo.row], border[coo.col])), shape=(len(kept), len(kept)))
        K_c = sp.csc_matrix(K[kept][:, kept] - correction)
        # the extra rows (mean displacements) on the kept coordinates: M_k q_k + M_x q_x with
        # q_x = -K_xx^-1 K_xk q_k
        if extra is None:
            extra_k = np.zeros((0, len(kept)))
        else:
            extra = sp.csr_matrix(extra)
            M_x = extra[:, rest].toarray()
            extra_k = extra[:, kept].toarray() - (K_kx @ rest_solve(M_x.T)).T
        return cls(
            region=region,
            kept=kept,
            region_at=np.searchsorted(kept, region.coordinates).astype(np.int64),
            K_c=K_c,
            B=sp.csr_matrix(B[:, kept]),
            extra=extra_k,
            rest=rest,
            rest_solve=rest_solve,
            coupling=sp.csr_matrix(K_kx),
            n=n,
            state=region.virgin(),
            q=np.zeros(len(kept)),
        )

    def elastic_delassus(self):
        """B K_c^-1 B^T and K_c's solver: the elastic tangent's, factorised once."""
        if self._elastic is None:
            self._elastic = spd_inverse_rows(self.K_c, self.B)
        return self._elastic

    def respond(self, q: NDArray[np.float64]):
        """The region's response at the kept coordinates ``q``."""
        return self.region.respond(q[self.region_at], self.state)

    def full(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """Every free coordinate of the body from the kept ones, m."""
        out = np.zeros(self.n)
        out[self.kept] = q
        out[self.rest] = -self.rest_solve(self.coupling.T @ q)
        return out


def _elastic_delassus(K: sp.spmatrix, B: sp.spmatrix, extra: sp.spmatrix | None):
    """A body that does not yield: B K^-1 B^T, and the extra rows' images M K^-1 B^T."""
    rows = sp.vstack([B] + ([extra] if extra is not None else [])).tocsr()
    inverse, _ = spd_inverse_rows(K, rows)
    c = B.shape[0]
    return inverse[:c, :c], inverse[c:, :c]


def _plastic_path(
    problem: AxiImpact,
    model: AxiModel,
    displacements_m: Sequence[float],
    options: FEMAxiOptions,
    unloading: UnloadingPlan | None,
    until_force_N: float | None,
) -> Indentation:
    """:func:`static_indentation` where a material yields: the displacements as a path."""
    radius = options.plastic_extent * model.scales.contact_radius_m
    rod_groups, imp_groups = material_groups(problem, model)
    rod, imp = model.rod, model.impactor
    free = np.arange(imp.n - 1)  # the rigid back's W is held: a translation by d closes the gaps by d
    means_rows = sp.vstack(_mean_rows(problem, model)).tocsr()
    specs = [
        (rod, rod.K, sp.csr_matrix(model.B_rod), rod_groups, means_rows, ()),
        (imp, imp.K[free][:, free], sp.csr_matrix(model.B_imp)[:, free], imp_groups, None, (imp.n - 1,)),
    ]
    yielding: list[tuple[_CondensedBody, object, YieldGuard]] = []
    fixed_delassus = np.zeros((len(model.gap0), len(model.gap0)))
    fixed_means = np.zeros((2, len(model.gap0)))
    for axi, K, B, groups, extra, held in specs:
        region = plastic_region(axi.basis, axi.T, groups, radius, held=held)
        if region is None:
            A, M = _elastic_delassus(K, B, extra)
            fixed_delassus += A
            if extra is not None:
                fixed_means += M
        else:
            yielding.append((_CondensedBody.of(K, B, region, extra), axi, YieldGuard.beyond(axi.basis, groups, region)))
    gap0, r_c = model.gap0, model.r_c
    counters = {"iterations": 0, "work": 0.0, "elastic_tangent": 0, "floor": 0, "cuts": 0, "d": 0.0}

    def solve(d: float) -> tuple[dict[str, object] | None, str, str]:
        """One displacement from the history the last converged one left, the increment cut into
        halves where it fails (:data:`MAX_CUTS`): its record, or None and why."""
        return advance(counters["d"], d, 0)

    def advance(start: float, d: float, cuts: int) -> tuple[dict[str, object] | None, str, str]:
        saved = [(body.q.copy(), body.state) for body, _, _ in yielding], counters["work"]
        record, status, message = attempt(d)
        if record is not None:
            counters["d"] = d
            return record, status, message
        for (body, _, _), (q, state) in zip(yielding, saved[0]):
            body.q, body.state = q, state
        counters["work"] = saved[1]
        if cuts >= MAX_CUTS:
            return record, status, f"{message} (the increment from d = {start:.6g} m halved {cuts} times)"
        counters["cuts"] += 1
        middle, _, _ = advance(start, 0.5 * (start + d), cuts + 1)
        if middle is None:
            return record, status, message
        return advance(0.5 * (start + d), d, cuts + 1)

    def attempt(d: float) -> tuple[dict[str, object] | None, str, str]:
        """One displacement from the current state, without cutting."""
        trials = [body.respond(body.q) for body, _, _ in yielding]
        history: list[float] = []
        for _ in range(MAX_NEWTON):
            counters["iterations"] += 1
            delassus = fixed_delassus.copy()
            gap = gap0 - d
            steps = []
            for (body, _, _), trial in zip(yielding, trials):
                A_t, solve_t = None, None
                if trial.tangent_change.nnz:
                    K_t = sp.csc_matrix(body.K_c + _embed(trial.tangent_change, body.region_at, len(body.kept)))
                    try:
                        A_t, solve_t = spd_inverse_rows(K_t, body.B)
                    except np.linalg.LinAlgError:
                        # a perfectly plastic zone can make the consistent tangent singular: this
                        # iterate takes the elastic one (a modified Newton step, converging linearly)
                        counters["elastic_tangent"] += 1
                if A_t is None:
                    A_t, solve_t = body.elastic_delassus()
                load = np.zeros(len(body.kept))
                load[body.region_at] = trial.load
                dq0 = solve_t(load - body.K_c @ body.q)
                delassus = delassus + A_t
                gap = gap + body.B @ (body.q + dq0)
                steps.append((solve_t, dq0))
            lam = _lcp(delassus, gap)
            residual, scale = 0.0, float(lam.sum())
            for i, ((body, _, _), (solve_t, dq0)) in enumerate(zip(yielding, steps)):
                body.q = body.q + dq0 + solve_t(body.B.T @ lam)
                trials[i] = body.respond(body.q)
                out = body.B.T @ lam - body.K_c @ body.q
                out[body.region_at] += trials[i].load
                residual += float(out @ out)
                scale = max(scale, float(np.linalg.norm(trials[i].load)))
            relative = math.sqrt(residual) / max(scale, 1e-300)
            log.debug("d = %.6g m: residual %.3e of the force scale", d, relative)
            if relative <= NEWTON_RTOL or residual == 0.0:
                break
            stalled = len(history) >= NEWTON_STALL and relative > 0.5 * min(history[-NEWTON_STALL:])
            if relative <= NEWTON_FLOOR_RTOL and stalled:
                counters["floor"] += 1
                break
            history.append(relative)
        else:
            return (
                None,
                "not_converged",
                f"the Newton iteration at d = {d:.6g} m did not converge in {MAX_NEWTON} iterations",
            )
        escaped = 0.0
        for (body, axi, guard), trial in zip(yielding, trials):
            body.state = trial.state
            counters["work"] += trial.plastic_work_J
            ratio = guard.ratio(axi.T @ _padded(body.full(body.q), axi.n))
            log.debug(
                "d = %.6g m: force %.6g N, beyond the plastic region %.3g of the yield stress",
                d,
                2 * math.pi * lam.sum(),
                ratio,
            )
            escaped = max(escaped, ratio)
        if escaped >= 1.0:
            return (
                None,
                "plastic_region",
                (
                    f"at d = {d:.6g} m the elastic stress beyond the plastic region (radius {radius:.4g} m) reaches "
                    f"{escaped:.3g} of the yield stress: raise plastic_extent"
                ),
            )
        if lam[np.argmax(r_c)] > 0.0:
            return (
                None,
                "contact_extent",
                (
                    f"at d = {d:.6g} m the contact reaches the outermost candidate (r = {r_c.max():.4g} m): "
                    "raise contact_extent"
                ),
            )
        means = fixed_means @ lam
        for body, _, _ in yielding:
            if len(body.extra):
                means = means + body.extra @ body.q
        record = {
            "force": 2 * math.pi * lam.sum(),
            "radius": float(r_c[lam > 0].max()) if (lam > 0).any() else 0.0,
            "means": means,
            "work": counters["work"],
            "yielded": sum(int((t.state.equivalent_plastic_strain > 0).sum()) for t in trials),
        }
        return record, "ok", ""

    loading: list[dict[str, object]] = []
    curves: list[tuple[int, float, dict[str, object]]] = []
    status, message = "ok", ""
    since_yield = None  # loading points since the first that dissipated
    for index, d in enumerate(displacements_m):
        record, status, message = solve(float(d))
        if record is None:
            break
        loading.append(record)
        last = index == len(displacements_m) - 1 or (until_force_N is not None and record["force"] >= until_force_N)
        if unloading is None or record["work"] <= 0.0:
            if last:
                break
            continue
        since_yield = 0 if since_yield is None else since_yield + 1
        if since_yield % unloading.every and not last:
            continue
        # an unloading curve from here, down to no force, and back up to here
        for fraction in np.linspace(1.0, 0.0, unloading.points + 1)[1:]:
            down, status, message = solve(float(d) * fraction)
            if down is None:
                break
            curves.append((index, float(d) * fraction, down))
            if down["force"] == 0.0:
                break
        if status != "ok" or last:
            break
        bottom = curves[-1][1]
        for fraction in np.linspace(0.0, 1.0, unloading.reload + 1)[1:]:
            back, status, message = solve(bottom + (float(d) - bottom) * fraction)
            if back is None:
                break
        if status != "ok":
            break
    spacing = float(np.min(np.diff(np.unique(r_c)))) if len(r_c) > 1 else model.fine_size_m
    moved_a = np.asarray([r["means"] for r in loading], dtype=float).reshape(-1, 2)
    return Indentation(
        np.asarray(displacements_m, float)[: len(loading)],
        np.asarray([r["force"] for r in loading]),
        np.asarray([r["radius"] for r in loading]),
        spacing,
        face_displacement_m=moved_a[:, 0],
        surface_displacement_m=moved_a[:, 1],
        plastic_work_J=np.asarray([r["work"] for r in loading]),
        yielded_points=np.asarray([r["yielded"] for r in loading], dtype=np.int64),
        newton_iterations=counters["iterations"],
        elastic_tangent_iterations=counters["elastic_tangent"],
        floor_converged=counters["floor"],
        increment_cuts=counters["cuts"],
        status=status,
        message=message,
        unloading_curve=np.asarray([c[0] for c in curves], dtype=np.int64) if unloading is not None else None,
        unloading_displacement_m=np.asarray([c[1] for c in curves]) if unloading is not None else None,
        unloading_force_N=np.asarray([c[2]["force"] for c in curves]) if unloading is not None else None,
    )


def _mean_rows(problem: AxiImpact, model: AxiModel) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """The rows of the mean axial displacement of the rod's end face z = 0 and of the struck
    surface (the film's disc z = -h with a film, the end face without), on the rod's free
    coordinates, shape (1, n) each."""
    rod = model.rod
    face = rod.reduce_rows(cross_section_mean_uz(rod.basis, 0.0, problem.rod_radius_m))
    if model.film is None:
        return face, face
    surface = rod.reduce_rows(cross_section_mean_uz(rod.basis, -model.film.film_thickness_m, model.film.film_radius_m))
    return face, surface


def _embed(matrix: sp.spmatrix, at: NDArray[np.int64], size: int) -> sp.csr_matrix:
    """``matrix`` (on the region's coordinates) placed at rows and columns ``at`` of a size x size matrix."""
    coo = sp.coo_matrix(matrix)
    return sp.csr_matrix((coo.data, (at[coo.row], at[coo.col])), shape=(size, size))


def _padded(q: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """The free coordinates ``q`` with the held ones (the rigid back's W) appended as zeros."""
    out = np.zeros(n)
    out[: len(q)] = q
    return out


def _lcp(delassus: NDArray[np.float64], gap: NDArray[np.float64]) -> NDArray[np.float64]:
    """The contact LCP: lam >= 0, gap + A lam >= 0, complementary (non-negative least squares)."""
    chol = cholesky(0.5 * (delassus + delassus.T), lower=True)
    lam, _ = nnls(chol.T, -solve_triangular(chol, gap, lower=True), maxiter=50 * len(gap))
    return lam
