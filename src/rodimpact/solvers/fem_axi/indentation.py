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

__all__ = ["NEWTON_RTOL", "Indentation", "static_indentation"]

log = logging.getLogger(__name__)

NEWTON_RTOL = 1e-10
"""A displacement's Newton iteration has converged when the out-of-balance force on the plastic
regions is below this fraction of the larger of the contact force and the plastic strain's load
(the residual stresses' scale, which stays when the contact force vanishes), both per radian."""
MAX_NEWTON = 60
"""Newton iterations allowed per displacement."""


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
    status : {"ok", "not_converged", "plastic_region"}
        "not_converged": a displacement's Newton iteration did not converge within
        ``MAX_NEWTON``; "plastic_region": the elastic stress beyond a plastic region reached the
        yield stress (raise ``plastic_extent``). The arrays hold the displacements solved before.
    message : str
        Why, when ``status`` is not "ok".
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
    status: str = "ok"
    message: str = ""

    @property
    def success(self) -> bool:
        """Every displacement was solved (``status`` "ok")."""
        return self.status == "ok"


def static_indentation(
    problem: AxiImpact, displacements_m: Sequence[float], options: FEMAxiOptions | None = None
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

    Returns
    -------
    Indentation
    """
    if problem.body != "cap" or problem.far_end != "fixed":
        raise ValueError("problem: static indentation needs body='cap' and a fixed far end")
    options = FEMAxiOptions() if options is None else options
    model = build_model(problem, options, dynamic=False)  # statics: no mass matrices
    if _yields(problem):
        return _plastic_path(problem, model, displacements_m, options)
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
    face = rod.reduce_rows(cross_section_mean_uz(rod.basis, 0.0, problem.rod_radius_m))
    if model.film is None:
        surface = face
    else:
        surface = rod.reduce_rows(
            cross_section_mean_uz(rod.basis, -model.film.film_thickness_m, model.film.film_radius_m)
        )
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


def _yields(problem: AxiImpact) -> bool:
    """A material of either body yields (the impactor, the rod or a layer)."""
    layers = problem.stack.layers if problem.stack is not None else ()
    return (
        problem.impactor_material.yields
        or problem.rod_material.yields
        or any(layer.yield_stress_pa is not None for layer in layers)
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
    problem: AxiImpact, model: AxiModel, displacements_m: Sequence[float], options: FEMAxiOptions
) -> Indentation:
    """:func:`static_indentation` where a material yields: the displacements as a path."""
    radius = options.plastic_extent * model.scales.contact_radius_m
    rod_groups, imp_groups = material_groups(problem, model)
    rod, imp = model.rod, model.impactor
    free = np.arange(imp.n - 1)  # the rigid back's W is held: a translation by d closes the gaps by d
    face = rod.reduce_rows(cross_section_mean_uz(rod.basis, 0.0, problem.rod_radius_m))
    if model.film is None:
        surface = face
    else:
        surface = rod.reduce_rows(
            cross_section_mean_uz(rod.basis, -model.film.film_thickness_m, model.film.film_radius_m)
        )
    means_rows = sp.vstack([face, surface]).tocsr()
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
    forces, radii, moved, work, yielded = [], [], [], [], []
    iterations, status, message = 0, "ok", ""
    done_work = 0.0
    lam = np.zeros(len(gap0))
    for d in displacements_m:
        trials = [body.respond(body.q) for body, _, _ in yielding]
        converged = False
        for _ in range(MAX_NEWTON):
            iterations += 1
            delassus = fixed_delassus.copy()
            gap = gap0 - d
            steps = []
            for (body, _, _), trial in zip(yielding, trials):
                K_t = body.K_c
                if trial.tangent_change.nnz:
                    change = _embed(trial.tangent_change, body.region_at, len(body.kept))
                    K_t = sp.csc_matrix(K_t + change)
                A_t, solve_t = spd_inverse_rows(K_t, body.B)
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
            log.debug("d = %.6g m: residual %.3e of the force scale", d, math.sqrt(residual) / max(scale, 1e-300))
            if math.sqrt(residual) <= NEWTON_RTOL * max(scale, 1e-300) or residual == 0.0:
                converged = True
                break
        if not converged:
            status = "not_converged"
            message = f"the Newton iteration at d = {d:.6g} m did not converge in {MAX_NEWTON} iterations"
            break
        escaped = None
        for (body, axi, guard), trial in zip(yielding, trials):
            body.state = trial.state
            done_work += trial.plastic_work_J
            ratio = guard.ratio(axi.T @ _padded(body.full(body.q), axi.n))
            log.debug("d = %.6g m: beyond the plastic region %.3g of the yield stress", d, ratio)
            if ratio >= 1.0:
                escaped = ratio
        forces.append(2 * math.pi * lam.sum())
        radii.append(float(r_c[lam > 0].max()) if (lam > 0).any() else 0.0)
        means = fixed_means @ lam
        for body, _, _ in yielding:
            if len(body.extra):
                means = means + body.extra @ body.q
        moved.append(means)
        work.append(done_work)
        yielded.append(sum(int((t.state.equivalent_plastic_strain > 0).sum()) for t in trials))
        if escaped is not None:
            status = "plastic_region"
            message = (
                f"at d = {d:.6g} m the elastic stress beyond the plastic region (radius {radius:.4g} m) reaches "
                f"{escaped:.3g} of the yield stress: raise plastic_extent"
            )
            break
    spacing = float(np.min(np.diff(np.unique(r_c)))) if len(r_c) > 1 else model.fine_size_m
    moved_a = np.asarray(moved, dtype=float).reshape(-1, 2)
    return Indentation(
        np.asarray(displacements_m, float)[: len(forces)],
        np.asarray(forces),
        np.asarray(radii),
        spacing,
        face_displacement_m=moved_a[:, 0],
        surface_displacement_m=moved_a[:, 1],
        plastic_work_J=np.asarray(work),
        yielded_points=np.asarray(yielded, dtype=np.int64),
        newton_iterations=iterations,
        status=status,
        message=message,
    )


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
