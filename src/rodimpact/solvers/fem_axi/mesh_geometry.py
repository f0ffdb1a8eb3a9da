"""Geometry and refinement helpers of the (r, z) meshes (:mod:`.meshes`, :mod:`.film_mesh`).

Graded coordinates (:func:`_graded`), triangle areas, longest edges and distances to the
origin (the contact point), counter-clockwise meshes (:func:`_oriented`), named boundaries
(:func:`_tagged`), the graded target size and the refinement loop (:func:`graded_size`,
:func:`refine_until`), and the curved bodies' coarse mesh: a Delaunay mesh of a smoothed,
well-spaced point set (:func:`_coarse_mesh`) and its refinement with the new sphere vertices
projected onto the sphere (:func:`_refined`). All triangles are counter-clockwise in (r, z).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq
from scipy.spatial import Delaunay
from skfem import MeshTri

from rodimpact.solvers.fem_axi.layers import positive as _positive

__all__ = ["GROWTH_RATIO", "SIZE_GRADIENT", "graded_size", "refine_until"]

GROWTH_RATIO = 1.3
"""Largest ratio of two neighbouring spacings of the rod's graded coordinates."""
SIZE_GRADIENT = 0.5
"""Growth of the curved bodies' target size per unit distance beyond the fine extent."""


def _fine_sizes(fine_size_m: float, fine_extent_m: float, body_m: float) -> tuple[float, float]:
    fine = _positive("fine_size_m", fine_size_m)
    if fine > body_m:
        raise ValueError(
            f"fine_size_m must not exceed the body's smallest dimension ({body_m!r} m), got {fine_size_m!r}"
        )
    return fine, _positive("fine_extent_m", fine_extent_m)


def _ceil(x: float) -> int:  # ceil, forgiving the rounding of an integral quotient
    return math.ceil(x * (1.0 - 1e-12))


def _graded(
    length: float, fine: float, extent: float, coarse: float, ratio: float = GROWTH_RATIO
) -> NDArray[np.float64]:
    """Coordinates 0 = x_0 < ... < x_n = length: spacing h0 <= fine on [0, extent], then
    min(coarse, h0 g^i) with g <= ratio chosen so that the last one ends at ``length``."""
    if extent >= length:
        return np.linspace(0.0, length, _ceil(length / fine) + 1)
    n0 = _ceil(extent / fine)
    h0, rest = extent / n0, length - extent
    count = 1
    while np.minimum(coarse, h0 * ratio ** np.arange(1, count + 1)).sum() < rest:
        count += 1
    powers = np.arange(1, count + 1)

    def excess(g: float) -> float:
        return float(np.minimum(coarse, h0 * g**powers).sum() - rest)

    if excess(1.0) >= 0.0:  # too short to grade: the fine spacing throughout
        return np.linspace(0.0, length, _ceil(length / h0) + 1)
    g = brentq(excess, 1.0, ratio, xtol=1e-15) if excess(ratio) > 0.0 else ratio
    x = np.concatenate([np.linspace(0.0, extent, n0 + 1), extent + np.cumsum(np.minimum(coarse, h0 * g**powers))])
    x[-1] = length
    return x


def _area2(p: NDArray[np.float64], t: NDArray[np.int64]) -> NDArray[np.float64]:
    """Twice the signed areas of the triangles t (shape (3, k)) of the points p, m^2."""
    d1, d2 = p[:, t[1]] - p[:, t[0]], p[:, t[2]] - p[:, t[0]]
    return d1[0] * d2[1] - d1[1] * d2[0]


def _oriented(p: NDArray[np.float64], t: NDArray[np.int64]) -> MeshTri:
    """MeshTri with every triangle counter-clockwise (skfem's index sorting switched off)."""
    t = np.array(t, dtype=np.int64)
    t[[1, 2]] = np.where(_area2(p, t) < 0, t[[2, 1]], t[[1, 2]])
    return MeshTri(np.ascontiguousarray(p, dtype=np.float64), t, sort_t=False)


def _tagged(mesh: MeshTri, vertex_sets: dict[str, NDArray[np.bool_]]) -> tuple[MeshTri, dict[str, np.ndarray]]:
    """Name every boundary facet after the first vertex set that holds both its ends."""
    facets, boundaries = mesh.boundary_facets(), {}
    left = np.ones(facets.size, dtype=bool)
    for name, inside in vertex_sets.items():
        hit = left & inside[mesh.facets[0, facets]] & inside[mesh.facets[1, facets]]
        boundaries[name] = facets[hit].astype(np.int64)
        left &= ~hit
    if left.any():
        raise RuntimeError(f"{left.sum()} boundary facets fit no named boundary")
    return mesh.with_boundaries(boundaries), boundaries


def graded_size(mesh: MeshTri, fine: float, extent: float, coarse: float) -> NDArray[np.float64]:
    """Target longest edge of each triangle, m: ``fine`` within ``extent`` of the origin, growing
    by :data:`SIZE_GRADIENT` per metre beyond it, at most ``coarse``."""
    beyond = np.maximum(_distance_to_origin(mesh) - extent, 0.0)
    return np.where(beyond > 0.0, np.minimum(coarse, fine + SIZE_GRADIENT * beyond), fine)


def refine_until(
    mesh: MeshTri, target: Callable[[MeshTri], NDArray[np.float64]], max_levels: int
) -> tuple[MeshTri, int]:
    """Refine the triangles whose longest edge exceeds ``target(mesh)`` until none does;
    the mesh and the number of refinement passes.

    Raises
    ------
    RuntimeError
        Still too coarse after ``max_levels`` passes.
    """
    for levels in range(max_levels):
        marked = np.nonzero(_longest_edges(mesh) > target(mesh) * (1 + 1e-9))[0]
        if marked.size == 0:
            return mesh, levels
        mesh = mesh.refined(marked)
    raise RuntimeError("the refinement did not converge")


# --------------------------------------------------------------------- curved bodies


def _longest_edges(mesh: MeshTri) -> NDArray[np.float64]:
    p, t = mesh.p, mesh.t
    return np.max([np.hypot(*(p[:, t[i]] - p[:, t[i - 1]])) for i in range(3)], axis=0)


def _distance_to_origin(mesh: MeshTri) -> NDArray[np.float64]:
    """Distance from the origin (a corner, never inside) to each triangle's edges, m."""
    p, t = mesh.p, mesh.t
    best = np.full(t.shape[1], np.inf)
    for i in range(3):
        a, e = p[:, t[i - 1]], p[:, t[i]] - p[:, t[i - 1]]
        s = np.clip(-(a * e).sum(0) / (e * e).sum(0), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(a + s * e)))
    return best


def _coarse_points(radius: float, height: float, spacing: float) -> tuple[NDArray[np.float64], int, NDArray[np.bool_]]:
    """Points of {r >= 0, r^2 + (z + R)^2 <= R^2, z >= -height} about ``spacing`` apart.

    Returns the points (shape (2, n), m); the number b of boundary points, which come first
    in polygon order (sphere from the origin down, back, axis up); the sphere mask (n,).
    """
    ball = height == 2 * radius
    phi_max = math.acos(1.0 - height / radius)  # pi for the ball
    phi = np.linspace(0.0, phi_max, max(2, math.ceil(radius * phi_max / spacing)) + 1)
    arc = np.vstack([radius * np.sin(phi), radius * (np.cos(phi) - 1.0)])
    arc[:, -1] = (0.0 if ball else arc[0, -1]), -height
    back_r = np.linspace(arc[0, -1], 0.0, math.ceil(arc[0, -1] / spacing) + 1)[1:]
    back = np.vstack([back_r, np.full_like(back_r, -height)])[:, : 0 if ball else None]
    axis_z = np.linspace(-height, 0.0, max(2, math.ceil(height / spacing)) + 1)[1:-1]
    fixed = np.hstack([arc, back, np.vstack([np.zeros_like(axis_z), axis_z])])
    rows = np.arange(-height + 0.433 * spacing, 0.0, spacing * math.sqrt(3) / 2)
    lattice = [
        (r, np.full_like(r, z))
        for i, z in enumerate(rows)
        for r in [np.arange(spacing * (0.5 + 0.5 * (i % 2)), radius, spacing)]
    ]
    r, z = (np.concatenate(c) for c in zip(*lattice))
    keep = np.minimum.reduce([r, radius - np.hypot(r, z + radius), z + height]) >= spacing / 2
    points = np.hstack([fixed, np.vstack([r[keep], z[keep]])])
    return points, fixed.shape[1], np.arange(points.shape[1]) < arc.shape[1]


def _delaunay(points: NDArray[np.float64]) -> NDArray[np.int64]:
    """Delaunay triangles (shape (3, k)) without flat ones along straight boundaries."""
    t = Delaunay(points.T).simplices.T
    return t[:, np.abs(_area2(points, t)) > 1e-12 * np.ptp(points, axis=1).max() ** 2]


def _coarse_mesh(radius: float, height: float, spacing: float) -> tuple[MeshTri, NDArray[np.bool_]]:
    """Delaunay mesh of the point set after 8 sweeps of Laplacian smoothing of the interior
    points (the region is convex, so averages of neighbours stay inside); checks that its
    boundary is the closed polygon through the boundary points. Returns it, the sphere mask."""
    p, n_fixed, on_sphere = _coarse_points(radius, height, spacing)
    for _ in range(8):
        t = _delaunay(p)
        edges = np.unique(np.sort(np.hstack([t[[0, 1]], t[[1, 2]], t[[2, 0]]]), 0), axis=1)
        edges = np.hstack([edges, edges[::-1]])
        total = np.zeros_like(p)
        np.add.at(total.T, edges[0], p[:, edges[1]].T)
        count = np.bincount(edges[0], minlength=p.shape[1])
        p[:, n_fixed:] = total[:, n_fixed:] / count[n_fixed:]
    mesh = _oriented(p, _delaunay(p))
    ends = np.sort(mesh.facets[:, mesh.boundary_facets()], axis=0)
    polygon = np.sort([np.arange(n_fixed), (np.arange(n_fixed) + 1) % n_fixed], axis=0)
    if not np.array_equal(np.unique(ends, axis=1), np.unique(polygon, axis=1)):
        raise RuntimeError("the coarse triangulation does not match the body's boundary")
    return mesh, on_sphere


def _refined(
    mesh: MeshTri, marked: NDArray[np.int64], on_sphere: NDArray[np.bool_], radius: float
) -> tuple[MeshTri, NDArray[np.bool_]]:
    """``mesh.refined(marked)``, with the new vertices of the sphere projected onto it.

    A new vertex lies on the sphere iff it is the midpoint of a boundary facet whose ends
    are both on the sphere; these ends are its two neighbours along the new boundary.
    Returns the mesh and the sphere mask of its vertices.
    """
    n_old = mesh.nvertices
    fine = mesh.refined(np.asarray(marked, dtype=np.int64))
    pairs = fine.facets[:, fine.boundary_facets()]
    pairs = np.hstack([pairs, pairs[::-1]])
    pairs = pairs[:, pairs[0] >= n_old]
    pairs = pairs[:, np.argsort(pairs[0], kind="stable")]
    new, parents = pairs[0, ::2], pairs[1].reshape(-1, 2)
    if np.any(pairs[0, 1::2] != new) or np.any(parents >= n_old):
        raise RuntimeError("unexpected split of the boundary by MeshTri.refined")
    flags = np.concatenate([on_sphere, np.zeros(fine.nvertices - n_old, dtype=bool)])
    flags[new] = on_sphere[parents[:, 0]] & on_sphere[parents[:, 1]]
    moved = new[flags[new]]
    p, centre = fine.p.copy(), np.array([[0.0], [-radius]])
    d = p[:, moved] - centre
    p[:, moved] = centre + radius * d / np.hypot(*d)
    return _oriented(p, fine.t), flags
