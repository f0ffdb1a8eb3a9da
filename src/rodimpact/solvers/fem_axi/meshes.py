"""Meshes in the (r, z) half-plane for the axisymmetric contact model.

x[0] = r >= 0, x[1] = z, in m. The rod occupies 0 <= r <= a, 0 <= z <= L (struck face
z = 0); the impactor's sphere (radius R, centre (0, -R)) touches it at the origin. Element
size: the grid spacing of the rod's tensor mesh; the longest edge of a curved body's
triangle. Curved bodies: a coarse Delaunay mesh of a smoothed, well-spaced point set, then
``MeshTri.refined(marked)`` (longest-edge red-green-blue) wherever an edge exceeds the
target size; after every refinement the new sphere vertices are projected onto the sphere.
Boundaries are tagged by index arrays. All triangles are counter-clockwise in (r, z).
The geometry and refinement helpers these builders share with :mod:`.film_mesh` live in
:mod:`.mesh_geometry`.
"""

from __future__ import annotations

import logging
import math
import numbers
from dataclasses import dataclass

import numpy as np
from skfem import MeshTri

from rodimpact.solvers.fem_axi.layers import positive as _positive
from rodimpact.solvers.fem_axi.mesh_geometry import (
    SIZE_GRADIENT,
    _ceil,
    _coarse_mesh,
    _distance_to_origin,
    _fine_sizes,
    _graded,
    _longest_edges,
    _oriented,
    _refined,
    _tagged,
    graded_size,
    refine_until,
)

__all__ = ["BodyMesh", "rod_mesh", "cap_mesh", "ball_mesh", "surface_nodes", "hertz_mesh_sizes"]

log = logging.getLogger(__name__)

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
    a, length = _positive("radius_m", radius_m), _positive("length_m", length_m)
    fine, extent = _fine_sizes(fine_size_m, fine_extent_m, min(a, length))
    if coarse_size_m is None:
        coarse_r, coarse_z = max(a / 4, fine), max(a / 2, fine)
    else:
        coarse_r = coarse_z = _positive("coarse_size_m", coarse_size_m)
        if coarse_r < fine:
            raise ValueError(f"coarse_size_m must be >= fine_size_m ({fine!r} m), got {coarse_size_m!r}")
    if layout == "refined":
        return _refined_rod(a, length, fine, extent, coarse_r, coarse_z)
    if layout != "tensor":
        raise ValueError(f"layout must be 'refined' or 'tensor', got {layout!r}")
    r, z = _graded(a, fine, extent, coarse_r), _graded(length, fine, extent, coarse_z)
    base = MeshTri.init_tensor(r, z)
    p = base.p
    mesh, boundaries = _tagged(
        _oriented(p, base.t), {"axis": p[0] == 0.0, "lateral": p[0] == a, "end": p[1] == 0.0, "far": p[1] == length}
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


def _refined_rod(a: float, length: float, fine: float, extent: float, coarse_r: float, coarse_z: float) -> BodyMesh:
    """Uniform mesh of cells coarse_r x coarse_z, refined around the origin down to ``fine``
    (longest edges); far from the origin the cells' own diagonal is the target."""
    mesh = MeshTri.init_tensor(
        np.linspace(0.0, a, max(1, _ceil(a / coarse_r)) + 1),
        np.linspace(0.0, length, max(1, _ceil(length / coarse_z)) + 1),
    )
    coarse = float(_longest_edges(mesh).max())
    mesh, levels = refine_until(mesh, lambda m: graded_size(m, fine, extent, coarse), 65)
    p = mesh.p
    mesh, boundaries = _tagged(
        _oriented(p, mesh.t), {"axis": p[0] == 0.0, "lateral": p[0] == a, "end": p[1] == 0.0, "far": p[1] == length}
    )
    fine_reached = float(_longest_edges(mesh)[_distance_to_origin(mesh) <= extent].max())
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


def _curved_body(radius: float, height: float, fine_size_m: float, fine_extent_m: float) -> BodyMesh:
    """Coarse mesh sized so that k halvings bring the triangles near the origin just below
    ``fine``, refined until every longest edge is within the target size (fine within the
    extent, + SIZE_GRADIENT * distance beyond, <= min(R, height)/4) and every chord of the
    sphere within SURFACE_CHORD * R."""
    fine, extent = _fine_sizes(fine_size_m, fine_extent_m, min(radius, height))
    coarse = _MARGIN * min(radius, height) / 4
    if fine < coarse:
        coarse = _MARGIN * fine * 2.0 ** math.floor(math.log2(coarse / fine))
    mesh, on_sphere = _coarse_mesh(radius, height, coarse / 1.35)
    longest = _longest_edges(mesh)[_distance_to_origin(mesh) <= extent].max(initial=coarse)
    mesh, on_sphere = _coarse_mesh(radius, height, coarse / 1.35 * 0.99 * coarse / longest)
    for levels in range(65):  # noqa: B007 (the count is logged after the loop)
        beyond = np.maximum(_distance_to_origin(mesh) - extent, 0.0)
        target = np.where(beyond > 0.0, np.minimum(coarse, fine + SIZE_GRADIENT * beyond), min(fine, coarse))
        bf = mesh.boundary_facets()
        chord = np.hypot(*(mesh.p[:, mesh.facets[0, bf]] - mesh.p[:, mesh.facets[1, bf]]))
        long = bf[on_sphere[mesh.facets[:, bf]].all(0) & (chord > SURFACE_CHORD * radius)]
        marked = np.union1d(np.nonzero(_longest_edges(mesh) > target)[0], mesh.f2t[0, long])
        if marked.size == 0:
            break
        mesh, on_sphere = _refined(mesh, marked, on_sphere, radius)
    else:
        raise RuntimeError("the refinement did not converge")
    back = {"back": mesh.p[1] == -height} if height < 2 * radius else {}
    mesh, boundaries = _tagged(mesh, {"axis": mesh.p[0] == 0.0, **back, "surface": on_sphere})
    fine_reached = float(_longest_edges(mesh)[_distance_to_origin(mesh) <= extent].max())
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
    radius = _positive("sphere_radius_m", sphere_radius_m)
    height = _positive("height_m", height_m)
    if height >= 2 * radius:
        raise ValueError(
            f"height_m must be below 2 * sphere_radius_m = {2 * radius!r} m "
            f"(use ball_mesh for the whole ball), got {height_m!r}"
        )
    return _curved_body(radius, height, fine_size_m, fine_extent_m)


def ball_mesh(sphere_radius_m: float, fine_size_m: float, fine_extent_m: float) -> BodyMesh:
    """Mesh of the whole ball {r >= 0, r^2 + (z + R)^2 <= R^2}, sized as :func:`cap_mesh`
    (at most R/4 away from the contact). Boundaries 'axis' (r = 0) and 'surface'."""
    radius = _positive("sphere_radius_m", sphere_radius_m)
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
        max_r = _positive("max_r", max_r)
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
    a = _positive("contact_radius_m", contact_radius_m)
    n = elements_across
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
        raise ValueError(f"elements_across must be a positive integer, got {n!r}")
    return a / int(n), 3.0 * a
