"""Measures and operations on the triangle meshes of the (r, z) half-plane, shared by both meshers.

:mod:`.meshes` (the bare rod, the ball and the cap) and :mod:`.film_mesh` (the rod with its film
or stack) build their meshes from these: twice the triangles' signed areas (:func:`area2`), their
longest edges (:func:`longest_edges`) and their distances to the origin, the contact point
(:func:`distance_to_origin`); a mesh with every triangle counter-clockwise (:func:`oriented`) and
with named boundaries (:func:`tagged`); the fine size and extent of a body's mesh, checked
(:func:`fine_sizes`), the graded target size about the origin (:func:`graded_size`) and the loop
that refines until every longest edge meets its target (:func:`refine_until`).

x[0] = r >= 0, x[1] = z, in m; the origin is a corner of every body, never inside one.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from skfem import MeshTri

from rodimpact.solvers.fem_axi.layers import positive

__all__ = [
    "SIZE_GRADIENT",
    "area2",
    "distance_to_origin",
    "fine_sizes",
    "graded_size",
    "longest_edges",
    "oriented",
    "refine_until",
    "tagged",
]

SIZE_GRADIENT = 0.5
"""Growth of the target size per unit distance beyond the fine extent."""


def area2(p: NDArray[np.float64], t: NDArray[np.int64]) -> NDArray[np.float64]:
    """Twice the signed areas of triangles: positive for a counter-clockwise one in (r, z).

    Parameters
    ----------
    p : numpy.ndarray
        The points (shape (2, n)), m.
    t : numpy.ndarray
        The triangles (int, shape (3, k)), indices into ``p``'s columns.

    Returns
    -------
    numpy.ndarray
        Twice each triangle's signed area (shape (k,)), m^2.
    """
    d1, d2 = p[:, t[1]] - p[:, t[0]], p[:, t[2]] - p[:, t[0]]
    return d1[0] * d2[1] - d1[1] * d2[0]


def oriented(p: NDArray[np.float64], t: NDArray[np.int64]) -> MeshTri:
    """The mesh of the triangles ``t`` of the points ``p`` with every triangle counter-clockwise.

    A clockwise triangle has its last two vertices swapped; scikit-fem's sorting of each
    triangle's indices is switched off, so the order stays as given.

    Parameters
    ----------
    p : numpy.ndarray
        The points (shape (2, n)), m.
    t : numpy.ndarray
        The triangles (int, shape (3, k)), in either orientation; not modified.

    Returns
    -------
    skfem.MeshTri
    """
    t = np.array(t, dtype=np.int64)
    t[[1, 2]] = np.where(area2(p, t) < 0, t[[2, 1]], t[[1, 2]])
    return MeshTri(np.ascontiguousarray(p, dtype=np.float64), t, sort_t=False)


def tagged(mesh: MeshTri, vertex_sets: dict[str, NDArray[np.bool_]]) -> tuple[MeshTri, dict[str, np.ndarray]]:
    """Name every boundary facet after the first vertex set that holds both its ends.

    Parameters
    ----------
    mesh : skfem.MeshTri
    vertex_sets : dict of str to numpy.ndarray
        Boundary name -> vertex mask (bool, shape (n,)), tried in order.

    Returns
    -------
    (skfem.MeshTri, dict of str to numpy.ndarray)
        The mesh with its boundaries set, and the boundaries: name -> facet indices (int).

    Raises
    ------
    RuntimeError
        A boundary facet fits no named set.
    """
    facets, boundaries = mesh.boundary_facets(), {}
    left = np.ones(facets.size, dtype=bool)
    for name, inside in vertex_sets.items():
        hit = left & inside[mesh.facets[0, facets]] & inside[mesh.facets[1, facets]]
        boundaries[name] = facets[hit].astype(np.int64)
        left &= ~hit
    if left.any():
        raise RuntimeError(f"{left.sum()} boundary facets fit no named boundary")
    return mesh.with_boundaries(boundaries), boundaries


def longest_edges(mesh: MeshTri) -> NDArray[np.float64]:
    """Each triangle's longest edge (shape (k,)), m: the element size of every mesher here."""
    p, t = mesh.p, mesh.t
    return np.max([np.hypot(*(p[:, t[i]] - p[:, t[i - 1]])) for i in range(3)], axis=0)


def distance_to_origin(mesh: MeshTri) -> NDArray[np.float64]:
    """Distance from the origin (a corner, never inside) to each triangle's edges (shape (k,)), m."""
    p, t = mesh.p, mesh.t
    best = np.full(t.shape[1], np.inf)
    for i in range(3):
        a, e = p[:, t[i - 1]], p[:, t[i]] - p[:, t[i - 1]]
        s = np.clip(-(a * e).sum(0) / (e * e).sum(0), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(a + s * e)))
    return best


def fine_sizes(fine_size_m: float, fine_extent_m: float, body_m: float) -> tuple[float, float]:
    """A body's fine size and fine extent, checked.

    Parameters
    ----------
    fine_size_m : float
        The element size near the origin, m (> 0, at most ``body_m``).
    fine_extent_m : float
        The radius about the origin within which the elements are that fine, m (> 0).
    body_m : float
        The body's smallest dimension, m.

    Returns
    -------
    (float, float)
        The fine size and the fine extent, m.

    Raises
    ------
    ValueError
        Either is not a positive finite number, or the fine size exceeds ``body_m``; the
        message names the argument.
    """
    fine = positive("fine_size_m", fine_size_m)
    if fine > body_m:
        raise ValueError(
            f"fine_size_m must not exceed the body's smallest dimension ({body_m!r} m), got {fine_size_m!r}"
        )
    return fine, positive("fine_extent_m", fine_extent_m)


def graded_size(mesh: MeshTri, fine: float, extent: float, coarse: float) -> NDArray[np.float64]:
    """Target longest edge of each triangle, m: ``fine`` within ``extent`` of the origin, growing
    by :data:`SIZE_GRADIENT` per metre beyond it, at most ``coarse``.

    Parameters
    ----------
    mesh : skfem.MeshTri
    fine, extent, coarse : float
        The fine size, the fine extent and the largest size, m.

    Returns
    -------
    numpy.ndarray
        The target of each triangle (shape (k,)), m.
    """
    beyond = np.maximum(distance_to_origin(mesh) - extent, 0.0)
    return np.where(beyond > 0.0, np.minimum(coarse, fine + SIZE_GRADIENT * beyond), fine)


def refine_until(
    mesh: MeshTri, target: Callable[[MeshTri], NDArray[np.float64]], max_levels: int
) -> tuple[MeshTri, int]:
    """Refine the triangles whose longest edge exceeds ``target(mesh)`` until none does.

    Parameters
    ----------
    mesh : skfem.MeshTri
        The coarse mesh.
    target : callable
        A mesh -> each triangle's target longest edge (shape (k,)), m.
    max_levels : int
        Refinement passes allowed (``MeshTri.refined`` of the marked triangles each).

    Returns
    -------
    (skfem.MeshTri, int)
        The mesh and the number of refinement passes.

    Raises
    ------
    RuntimeError
        Still too coarse after ``max_levels`` passes.
    """
    for levels in range(max_levels):
        marked = np.nonzero(longest_edges(mesh) > target(mesh) * (1 + 1e-9))[0]
        if marked.size == 0:
            return mesh, levels
        mesh = mesh.refined(marked)
    raise RuntimeError("the refinement did not converge")
