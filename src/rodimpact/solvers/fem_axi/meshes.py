"""Meshes in the (r, z) half-plane for the axisymmetric contact model.

x[0] = r >= 0, x[1] = z, in m. The rod occupies 0 <= r <= a, 0 <= z <= L (struck face
z = 0); the impactor's sphere (radius R, centre (0, -R)) touches it at the origin. Element
size: the grid spacing of the rod's tensor mesh; the longest edge of a curved body's
triangle. Curved bodies: a coarse Delaunay mesh of a smoothed, well-spaced point set, then
``MeshTri.refined(marked)`` (longest-edge red-green-blue) wherever an edge exceeds the
target size; after every refinement the new sphere vertices are projected onto the sphere.
Boundaries are tagged by index arrays. All triangles are counter-clockwise in (r, z).
The measures and operations on triangle meshes these builders share with :mod:`.film_mesh`
(areas, longest edges, orientation, named boundaries, the graded target size and the refinement
loop) live in :mod:`.mesh_geometry`; :func:`coarse_rod_grid`, the refined rod's starting grid,
is the film-coated rod's too.
"""

from __future__ import annotations

import logging
import math
import numbers
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq
from scipy.spatial import Delaunay
from skfem import MeshTri

from rodimpact.solvers.fem_axi.layers import positive
from rodimpact.solvers.fem_axi.mesh_geometry import (
    SIZE_GRADIENT,
    area2,
    distance_to_origin,
    fine_sizes,
    graded_size,
    longest_edges,
    oriented,
    refine_until,
    tagged,
)

__all__ = [
    "GROWTH_RATIO",
    "BodyMesh",
    "rod_mesh",
    "coarse_rod_grid",
    "cap_mesh",
    "ball_mesh",
    "surface_nodes",
    "hertz_mesh_sizes",
]

log = logging.getLogger(__name__)

GROWTH_RATIO = 1.3
"""Largest ratio of two neighbouring spacings of the rod's graded coordinates (the tensor layout)."""
SURFACE_CHORD = 1 / 32
"""Longest chord of the sphere over R (the chords then lose ~1e-4 of a ball's volume)."""
_MARGIN = 0.98  # coarse size = _MARGIN * fine * 2**k: k halvings land just below fine


@dataclass(frozen=True)
class BodyMesh:
    """A body's triangle mesh with named boundaries.

    Attributes
    ----------
    mesh : skfem.MeshTri
        Vertices ``p`` (shape (2, n), m), triangles ``t`` (shape (3, k)), boundaries set.
    boundaries : dict of str to numpy.ndarray
        Boundary name -> facet indices (int, shape (f,)), the same as ``mesh.boundaries``.
    fine_size_m : float
        Largest element size reached within ``contact_extent_m`` of the origin, m.
    contact_extent_m : float
        Radius about the origin (the contact point) within which sizes are that fine, m.
    """

    mesh: MeshTri
    boundaries: dict[str, np.ndarray]
    fine_size_m: float
    contact_extent_m: float


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


def rod_mesh(
    radius_m: float,
    length_m: float,
    fine_size_m: float,
    fine_extent_m: float,
    coarse_size_m: float | None = None,
    layout: str = "refined",
) -> BodyMesh:
    """Mesh of the rod 0 <= r <= a, 0 <= z <= L, fine near the struck end's centre.

    ``layout="refined"`` (default): a uniform coarse mesh refined locally
    (``MeshTri.refined``) until every longest edge is within its target (fine within the
    extent, + SIZE_GRADIENT * distance beyond, at most the coarse size): fine only where
    the contact needs it, so far fewer DOFs than a tensor grid on a long rod.

    ``layout="tensor"``: graded tensor mesh (``MeshTri.init_tensor``). In r and in z the
    spacing is uniform and <= ``fine_size_m`` up to the fine extent, then grows
    geometrically (ratio <= 1.3 between neighbours) to at most the coarse size. The cells
    far from the struck end are elongated (fine in r, coarse in z): the smallest angle is
    arctan(fine / coarse_z).

    Parameters
    ----------
    radius_m, length_m : float
        Rod radius a and length L, m.
    fine_size_m : float
        Grid spacing near the struck end's centre, m (at most min(a, L)).
    fine_extent_m : float
        Extent of the fine spacing in r and in z from the origin, m.
    coarse_size_m : float, optional
        Largest spacing in r and z, m (>= fine_size_m). Default: max(a/4, fine) in r and
        max(a/2, fine) in z (waves along the rod need the z spacing small).

    Returns
    -------
    BodyMesh
        Boundaries 'axis' (r = 0), 'end' (z = 0), 'far' (z = L), 'lateral' (r = a).
    """
    a, length = positive("radius_m", radius_m), positive("length_m", length_m)
    fine, extent = fine_sizes(fine_size_m, fine_extent_m, min(a, length))
    if coarse_size_m is None:
        coarse_r, coarse_z = max(a / 4, fine), max(a / 2, fine)
    else:
        coarse_r = coarse_z = positive("coarse_size_m", coarse_size_m)
        if coarse_r < fine:
            raise ValueError(f"coarse_size_m must be >= fine_size_m ({fine!r} m), got {coarse_size_m!r}")
    if layout == "refined":
        return _refined_rod(a, length, fine, extent, coarse_r, coarse_z)
    if layout != "tensor":
        raise ValueError(f"layout must be 'refined' or 'tensor', got {layout!r}")
    r, z = _graded(a, fine, extent, coarse_r), _graded(length, fine, extent, coarse_z)
    base = MeshTri.init_tensor(r, z)
    p = base.p
    mesh, boundaries = tagged(
        oriented(p, base.t), {"axis": p[0] == 0.0, "lateral": p[0] == a, "end": p[1] == 0.0, "far": p[1] == length}
    )
    fine_reached = float(max(np.diff(x)[x[1:] <= extent].max() for x in (r, z)))
    log.info(
        "rod mesh: %d x %d coordinates, %d triangles, spacing %.3g m up to %.3g m",
        r.size,
        z.size,
        mesh.t.shape[1],
        fine_reached,
        extent,
    )
    return BodyMesh(mesh, boundaries, fine_reached, extent)


def coarse_rod_grid(
    radius_m: float, length_m: float, size_r_m: float, size_z_m: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The coordinates of the uniform grid the refined rod mesh starts from (``layout="refined"``
    of :func:`rod_mesh`, and the rod under a film, :func:`~.film_mesh.film_rod_mesh`).

    Parameters
    ----------
    radius_m, length_m : float
        The rod's radius a and length L, m.
    size_r_m, size_z_m : float
        The largest spacing in r and in z, m (> 0).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        r from 0 to a and z from 0 to L, each in the fewest equal spacings of at most the size
        (at least one), m.
    """
    r = np.linspace(0.0, radius_m, max(1, _ceil(radius_m / size_r_m)) + 1)
    z = np.linspace(0.0, length_m, max(1, _ceil(length_m / size_z_m)) + 1)
    return r, z


def _refined_rod(a: float, length: float, fine: float, extent: float, coarse_r: float, coarse_z: float) -> BodyMesh:
    """Uniform mesh of cells coarse_r x coarse_z, refined around the origin down to ``fine``
    (longest edges); far from the origin the cells' own diagonal is the target."""
    mesh = MeshTri.init_tensor(*coarse_rod_grid(a, length, coarse_r, coarse_z))
    coarse = float(longest_edges(mesh).max())
    mesh, levels = refine_until(mesh, lambda m: graded_size(m, fine, extent, coarse), 65)
    p = mesh.p
    mesh, boundaries = tagged(
        oriented(p, mesh.t), {"axis": p[0] == 0.0, "lateral": p[0] == a, "end": p[1] == 0.0, "far": p[1] == length}
    )
    fine_reached = float(longest_edges(mesh)[distance_to_origin(mesh) <= extent].max())
    log.info(
        "rod mesh (refined): %d vertices, %d triangles after %d refinements; size %.3g m within %.3g m, coarse %.3g m",
        mesh.nvertices,
        mesh.t.shape[1],
        levels,
        fine_reached,
        extent,
        coarse,
    )
    return BodyMesh(mesh, boundaries, fine_reached, extent)


# --------------------------------------------------------------------- curved bodies


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
    return t[:, np.abs(area2(points, t)) > 1e-12 * np.ptp(points, axis=1).max() ** 2]


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
    mesh = oriented(p, _delaunay(p))
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
    return oriented(p, fine.t), flags


def _curved_body(radius: float, height: float, fine_size_m: float, fine_extent_m: float) -> BodyMesh:
    """Coarse mesh sized so that k halvings bring the triangles near the origin just below
    ``fine``, refined until every longest edge is within the target size (fine within the
    extent, + SIZE_GRADIENT * distance beyond, <= min(R, height)/4) and every chord of the
    sphere within SURFACE_CHORD * R."""
    fine, extent = fine_sizes(fine_size_m, fine_extent_m, min(radius, height))
    coarse = _MARGIN * min(radius, height) / 4
    if fine < coarse:
        coarse = _MARGIN * fine * 2.0 ** math.floor(math.log2(coarse / fine))
    mesh, on_sphere = _coarse_mesh(radius, height, coarse / 1.35)
    longest = longest_edges(mesh)[distance_to_origin(mesh) <= extent].max(initial=coarse)
    mesh, on_sphere = _coarse_mesh(radius, height, coarse / 1.35 * 0.99 * coarse / longest)
    for levels in range(65):  # noqa: B007 (the count is logged after the loop)
        beyond = np.maximum(distance_to_origin(mesh) - extent, 0.0)
        target = np.where(beyond > 0.0, np.minimum(coarse, fine + SIZE_GRADIENT * beyond), min(fine, coarse))
        bf = mesh.boundary_facets()
        chord = np.hypot(*(mesh.p[:, mesh.facets[0, bf]] - mesh.p[:, mesh.facets[1, bf]]))
        long = bf[on_sphere[mesh.facets[:, bf]].all(0) & (chord > SURFACE_CHORD * radius)]
        marked = np.union1d(np.nonzero(longest_edges(mesh) > target)[0], mesh.f2t[0, long])
        if marked.size == 0:
            break
        mesh, on_sphere = _refined(mesh, marked, on_sphere, radius)
    else:
        raise RuntimeError("the refinement did not converge")
    back = {"back": mesh.p[1] == -height} if height < 2 * radius else {}
    mesh, boundaries = tagged(mesh, {"axis": mesh.p[0] == 0.0, **back, "surface": on_sphere})
    fine_reached = float(longest_edges(mesh)[distance_to_origin(mesh) <= extent].max())
    log.info(
        "R = %.4g m, height %.4g m: %d vertices, %d triangles after %d refinements; "
        "size %.3g m within %.3g m, coarse %.3g m",
        radius,
        height,
        mesh.nvertices,
        mesh.t.shape[1],
        levels,
        fine_reached,
        extent,
        coarse,
    )
    return BodyMesh(mesh, boundaries, fine_reached, extent)


def cap_mesh(sphere_radius_m: float, height_m: float, fine_size_m: float, fine_extent_m: float) -> BodyMesh:
    """Mesh of the spherical cap {r >= 0, r^2 + (z + R)^2 <= R^2, z >= -height}.

    A hemisphere for height = R. Longest edges: at most ``fine_size_m`` within
    ``fine_extent_m`` of the origin, growing beyond by SIZE_GRADIENT times the distance to
    at most min(R, height)/4; chords of the sphere at most SURFACE_CHORD * R.

    Parameters
    ----------
    sphere_radius_m : float
        R, m.
    height_m : float
        Height of the cap, m, 0 < height < 2R.
    fine_size_m : float
        Largest element size (longest edge) near the contact point, m (<= min(R, height)).
    fine_extent_m : float
        Radius around the origin in which the elements are that fine, m.

    Returns
    -------
    BodyMesh
        Boundaries 'axis' (r = 0), 'surface' (the sphere), 'back' (z = -height). The
        smallest angle cannot exceed the rim's corner angle arccos(1 - height/R).
    """
    radius = positive("sphere_radius_m", sphere_radius_m)
    height = positive("height_m", height_m)
    if height >= 2 * radius:
        raise ValueError(
            f"height_m must be below 2 * sphere_radius_m = {2 * radius!r} m "
            f"(use ball_mesh for the whole ball), got {height_m!r}"
        )
    return _curved_body(radius, height, fine_size_m, fine_extent_m)


def ball_mesh(sphere_radius_m: float, fine_size_m: float, fine_extent_m: float) -> BodyMesh:
    """Mesh of the whole ball {r >= 0, r^2 + (z + R)^2 <= R^2}, sized as :func:`cap_mesh`
    (at most R/4 away from the contact). Boundaries 'axis' (r = 0) and 'surface'."""
    radius = positive("sphere_radius_m", sphere_radius_m)
    return _curved_body(radius, 2 * radius, fine_size_m, fine_extent_m)


def surface_nodes(body: BodyMesh, name: str, max_r: float | None = None) -> np.ndarray:
    """Vertex indices (int, shape (k,)) on a named boundary, sorted by r, then by |x|.

    Parameters
    ----------
    body : BodyMesh
    name : str
        One of ``body.boundaries``.
    max_r : float, optional
        Keep only the vertices with r <= max_r that lie within 2 max_r of the origin, m:
        the part of the boundary around the contact point (on the ball this leaves out the
        far pole, where r is small too).
    """
    if name not in body.boundaries:
        raise ValueError(f"name must be one of {sorted(body.boundaries)}, got {name!r}")
    nodes = np.unique(body.mesh.facets[:, body.boundaries[name]])
    r, dist = body.mesh.p[0, nodes], np.hypot(*body.mesh.p[:, nodes])
    if max_r is not None:
        max_r = positive("max_r", max_r)
        keep = (r <= max_r) & (dist <= 2 * max_r)
        nodes, r, dist = nodes[keep], r[keep], dist[keep]
    return nodes[np.lexsort((dist, r))]


def hertz_mesh_sizes(contact_radius_m: float, elements_across: int = 10) -> tuple[float, float]:
    """Mesh sizes for a Hertz contact of radius a.

    Parameters
    ----------
    contact_radius_m : float
        Expected (largest) contact radius a, m.
    elements_across : int
        Elements across the contact radius (>= 1).

    Returns
    -------
    (fine_size_m, fine_extent_m) : tuple of float
        a / elements_across and 3 a, m. The pressure acts on r <= a and the largest shear
        stress lies at depth 0.48 a; on the axis the normal stress p0 a^2 / (a^2 + z^2) has
        fallen to p0 / 10 at z = 3 a, so the fine zone holds the steep part of the field.
    """
    a = positive("contact_radius_m", contact_radius_m)
    n = elements_across
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
        raise ValueError(f"elements_across must be a positive integer, got {n!r}")
    return a / int(n), 3.0 * a
