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
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import cholesky, solve_triangular
from scipy.optimize import nnls

from rodimpact.solvers.fem_axi.axibody import spd_inverse_rows
from rodimpact.solvers.fem_axi.axisym import cross_section_mean_uz
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import build_model

__all__ = ["Indentation", "static_indentation"]


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
    """

    displacement_m: NDArray[np.float64]
    force_N: NDArray[np.float64]
    contact_radius_m: NDArray[np.float64]
    node_spacing_m: float
    face_displacement_m: NDArray[np.float64] | None = None
    surface_displacement_m: NDArray[np.float64] | None = None


def static_indentation(
    problem: AxiImpact, displacements_m: Sequence[float], options: FEMAxiOptions | None = None
) -> Indentation:
    """Push the rigid back of a ``cap`` impactor by each displacement and solve the contact.

    Parameters
    ----------
    problem : AxiImpact
        Must have ``body="cap"`` and a fixed far end.
    displacements_m : sequence of float
        Displacements d of the rigid back towards the rod, m (> 0).
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
