"""The rod with a film, or a stack of layers, bonded on its struck end: one conforming mesh.

Geometry in the (r, z) half-plane, m: the rod occupies 0 <= r <= a, 0 <= z <= L (its end
face z = 0, as in :func:`~rodimpact.solvers.fem_axi.meshes.rod_mesh`); the layers, discs of
radius r_f <= a and thicknesses h_1, ..., h_n (from the struck face to the rod; H their sum),
occupy 0 <= r <= r_f, -H <= z <= 0 and are bonded to each other and to the end face (the
regions share the vertices of their interfaces). A film is a stack of one layer. The layers are
added on top of the end face: the rod keeps its length, and outside the disc (r > r_f) the end
face is the bare rod, a step of height H at r = r_f.

The rod's part is meshed as :func:`~rodimpact.solvers.fem_axi.meshes.rod_mesh` (the same
uniform coarse grid, refined by longest-edge bisection down to ``fine`` within the fine extent
of the origin), and also wherever it is near the disc, to face edges of at most
``aspect * dz`` there, dz the height of the layers' elements (the target grows by
SIZE_GRADIENT times the distance from the disc); then the end-face vertex nearest to r = r_f
is moved there along the face (by at most half a face edge; no triangle folds, checked). The
layers are the extrusion of the rod's end-face vertices r_0 = 0 < ... < r_m = r_f: the
thickest layer through ``layers`` equal elements of height dz = h_max / layers, every other
layer through as many equal elements as make them at most dz high (at least one), every cell
split into two triangles. The mesh conforms to the interfaces and to the disc's edge, with the
same elements through the thickness everywhere (so also under the contact), columns as fine as
the rod's face (about fine / 2 within the fine extent, then graded up to the column spacing),
and flat cells of aspect up to ``aspect`` (1.5 ``aspect`` in the column at the edge) away from
the contact. For one layer this is ``layers`` elements of h / layers.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from skfem import MeshTri

from rodimpact.solvers.fem_axi.layers import FILM_ASPECT, layer_elements, positive
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
from rodimpact.solvers.fem_axi.meshes import BodyMesh, coarse_rod_grid
from rodimpact.solvers.fem_axi.options import FILM_LAYERS

__all__ = ["FILM_ASPECT", "FILM_LAYERS", "FilmRodMesh", "film_rod_mesh", "layer_elements", "layers_within"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class FilmRodMesh:
    """The rod and its film in one mesh.

    Attributes
    ----------
    body : BodyMesh
        The mesh; boundaries 'axis' (r = 0), 'lateral' (r = a), 'far' (z = L), 'end' (the
        bare end face z = 0, r >= r_f; empty when r_f = a), 'film' (the film's surface
        z = -h), 'film_edge' (r = r_f, -h <= z <= 0; empty when r_f = a, where it is 'lateral').
    film_elements, rod_elements : numpy.ndarray
        Triangle indices (int) of the layers (all of them) and of the rod.
    film_radius_m, film_thickness_m : float
        r_f and the total thickness H, m.
    layers : int
        Elements through the total thickness.
    layer_elements : tuple of numpy.ndarray
        Triangle indices of each layer, from the struck face to the rod (one for a film).
    """

    body: BodyMesh
    film_elements: NDArray[np.int64]
    rod_elements: NDArray[np.int64]
    film_radius_m: float
    film_thickness_m: float
    layers: int
    layer_elements: tuple[NDArray[np.int64], ...] = ()


def _distance_to_disc(mesh: MeshTri, radius: float) -> NDArray[np.float64]:
    """Distance from each triangle (in z >= 0) to the segment {z = 0, 0 <= r <= radius}, m."""
    p, t = mesh.p, mesh.t
    r, z = p[0, t], p[1, t]
    vertex = np.where(r <= radius, z, np.hypot(r - radius, z)).min(axis=0)
    shifted = MeshTri(p - np.array([[radius], [0.0]]), t, sort_t=False, validate=False)
    return np.minimum.reduce([vertex, distance_to_origin(mesh), distance_to_origin(shifted)])


def _rod_under_film(
    a: float, length: float, fine: float, extent: float, film_radius: float, face_spacing: float
) -> MeshTri:
    """The rod's mesh refined as ``rod_mesh(layout='refined')`` (the same coarse grid,
    :func:`~rodimpact.solvers.fem_axi.meshes.coarse_rod_grid`, the same
    target about the origin) and, near the film's disc, to face edges of ``face_spacing``;
    then the end-face vertex nearest to r = film_radius is moved there (along the face)."""
    coarse_r, coarse_z = max(a / 4, fine), max(a / 2, fine)
    r, z = coarse_rod_grid(a, length, coarse_r, coarse_z)
    mesh = MeshTri.init_tensor(r, z)
    # red refinement keeps the coarse triangles' shape: a face edge is 1/kappa of the longest
    kappa = math.hypot(r[1], z[1]) / r[1]
    coarse = float(longest_edges(mesh).max())

    def target(m: MeshTri) -> NDArray[np.float64]:
        band = kappa * face_spacing + SIZE_GRADIENT * _distance_to_disc(m, film_radius)
        return np.minimum(graded_size(m, fine, extent, coarse), np.minimum(coarse, band))

    mesh, _ = refine_until(mesh, target, 80)
    p = mesh.p.copy()
    if film_radius == a:
        return mesh
    face = np.nonzero((p[1] == 0.0) & (p[0] > 0.0) & (p[0] < a))[0]  # not the corners
    nearest = face[np.argmin(np.abs(p[0, face] - film_radius))]
    p[0, nearest] = film_radius
    if np.any(area2(p, mesh.t) * area2(mesh.p, mesh.t) <= 0.0):
        raise RuntimeError("moving a vertex to the film's edge folded a triangle")
    return MeshTri(p, mesh.t, sort_t=False)


def film_rod_mesh(
    radius_m: float,
    length_m: float,
    fine_size_m: float,
    fine_extent_m: float,
    film_radius_m: float,
    film_thickness_m: float | Sequence[float],
    layers: int = FILM_LAYERS,
    aspect: float = FILM_ASPECT,
) -> FilmRodMesh:
    """Mesh of the rod 0 <= r <= a, 0 <= z <= L with layers 0 <= r <= r_f, -H <= z <= 0 on its end.

    Parameters
    ----------
    radius_m, length_m : float
        Rod radius a and length L, m.
    fine_size_m, fine_extent_m : float
        Longest edges at most ``fine_size_m`` within ``fine_extent_m`` of the origin (the
        centre of the rod's end face, h below the contact point), m, as in ``rod_mesh``.
    film_radius_m : float
        Radius r_f of the film's disc, m, 0 < r_f <= a.
    film_thickness_m : float or sequence of float
        Thickness h of the film, or of each layer from the struck face to the rod, m (their sum
        at most the rod's length).
    layers : int
        Elements through the thickest layer (>= 1); see :func:`layer_elements`.
    aspect : float
        The columns of the layers (and the rod's face under them) are at most ``aspect`` times
        the height of the layers' elements wide (> 0).

    Returns
    -------
    FilmRodMesh
    """
    a, length = positive("radius_m", radius_m), positive("length_m", length_m)
    fine, extent = fine_sizes(fine_size_m, fine_extent_m, min(a, length))
    thicknesses = [film_thickness_m] if isinstance(film_thickness_m, (int, float)) else list(film_thickness_m)
    counts = layer_elements(thicknesses, layers)
    film_radius = positive("film_radius_m", film_radius_m)
    h = thicknesses[0] if len(thicknesses) == 1 else math.fsum(thicknesses)
    if film_radius > a:
        raise ValueError(f"film_radius_m must not exceed the rod's radius {a!r} m, got {film_radius_m!r}")
    if h > length:
        raise ValueError(f"film_thickness_m must not exceed the rod's length {length!r} m, got {film_thickness_m!r}")
    height = min(t / n for t, n in zip(thicknesses, counts))
    face_spacing = min(positive("aspect", aspect) * height, film_radius / 2)
    rod = _rod_under_film(a, length, fine, extent, film_radius, face_spacing)
    p, n_rod = rod.p, rod.nvertices
    face = np.nonzero((p[1] == 0.0) & (p[0] <= film_radius))[0]
    face = face[np.argsort(p[0, face])]
    if p[0, face[-1]] != film_radius:
        raise RuntimeError("the rod's mesh has no vertex at the film's edge")
    m = face.size - 1
    # the levels above the face, from the rod's face up to the struck face -H; each layer's rows
    levels, row_layer, bottom = [], [], 0.0
    for index in reversed(range(len(thicknesses))):
        top = -h if index == 0 else bottom - thicknesses[index]
        level = bottom + (top - bottom) * np.arange(1, counts[index] + 1) / counts[index]
        level[-1] = top
        levels.append(level)
        row_layer += [index] * counts[index]
        bottom = top
    z = np.concatenate(levels)
    rows = z.size
    new = np.vstack([np.tile(p[0, face], rows), np.repeat(z, m + 1)])
    index = np.vstack([face, n_rod + np.arange(rows * (m + 1)).reshape(rows, m + 1)])
    lo_l, lo_r = index[:-1, :-1].ravel(), index[:-1, 1:].ravel()
    hi_l, hi_r = index[1:, :-1].ravel(), index[1:, 1:].ravel()
    film_t = np.hstack([np.vstack([lo_l, lo_r, hi_r]), np.vstack([lo_l, hi_r, hi_l])])
    points = np.hstack([p, new])
    mesh = oriented(points, np.hstack([rod.t, film_t]))
    q = mesh.p
    mesh, boundaries = tagged(
        mesh,
        {
            "axis": q[0] == 0.0,
            "lateral": q[0] == a,
            "far": q[1] == length,
            "end": (q[1] == 0.0) & (q[0] >= film_radius),
            "film": q[1] == -h,
            "film_edge": (q[0] == film_radius) & (q[1] <= 0.0),
        },
    )
    n_rod_t = rod.t.shape[1]
    element_layer = np.tile(np.repeat(np.asarray(row_layer), m), 2)
    per_layer = tuple(n_rod_t + np.nonzero(element_layer == i)[0].astype(np.int64) for i in range(len(thicknesses)))
    fine_reached = float(longest_edges(mesh)[distance_to_origin(mesh) <= extent].max())
    log.info(
        "rod + film mesh: %d vertices, %d triangles (%d in %d layer(s), %s elements through, %.3g m in all, "
        "%d columns out to r = %.3g m); size %.3g m within %.3g m",
        mesh.nvertices,
        mesh.t.shape[1],
        film_t.shape[1],
        len(thicknesses),
        counts,
        h,
        m,
        film_radius,
        fine_reached,
        extent,
    )
    return FilmRodMesh(
        BodyMesh(mesh, boundaries, fine_reached, extent),
        film_elements=np.arange(n_rod_t, mesh.t.shape[1], dtype=np.int64),
        rod_elements=np.arange(n_rod_t, dtype=np.int64),
        film_radius_m=film_radius,
        film_thickness_m=h,
        layers=rows,
        layer_elements=per_layer,
    )


def layers_within(mesh: FilmRodMesh, radius_m: float) -> int:
    """The fewest film elements through the thickness along the vertical lines of the film's
    vertices within ``radius_m`` of the axis (counted from the vertices' heights)."""
    p = mesh.body.mesh.p
    t = mesh.body.mesh.t[:, mesh.film_elements]
    nodes = np.unique(t)
    nodes = nodes[p[0, nodes] <= radius_m]
    r, counts = np.unique(p[0, nodes], return_counts=True)
    return int(counts.min()) - 1 if r.size else 0
