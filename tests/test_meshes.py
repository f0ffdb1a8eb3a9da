"""Meshes of the rod, the spherical cap and the ball in the (r, z) half-plane: exact
geometry (volumes, boundaries on the sphere and the axis), element quality and sizes,
graded coordinates, input checks."""

import math

import numpy as np
import pytest

from rodimpact.solvers.fem_axi import mesh_geometry, meshes
from rodimpact.solvers.fem_axi.meshes import ball_mesh, cap_mesh, hertz_mesh_sizes, rod_mesh, surface_nodes

MIN_ANGLE_DEG = 20.0  # measured: 26.7 (hemisphere) to 28.7 degrees
SPHERE_RTOL = 1e-12
CHORD_VOLUME_RTOL = (meshes.SURFACE_CHORD**2) / 4 * 1.5  # chords of at most R/32

# (name, builder, R, height); the cases of the report: (b) cap, (c), (d) balls
CURVED = {
    "cap_R10_h10": (lambda: cap_mesh(10e-3, 10e-3, 60e-6, 1.8e-3), 10e-3, 10e-3, 60e-6, 1.8e-3),
    "cap_R10_h3": (lambda: cap_mesh(10e-3, 3e-3, 60e-6, 1.0e-3), 10e-3, 3e-3, 60e-6, 1.0e-3),
    "cap_R10_h15": (lambda: cap_mesh(10e-3, 15e-3, 0.2e-3, 1e-3), 10e-3, 15e-3, 0.2e-3, 1e-3),
    "ball_R1.58": (lambda: ball_mesh(1.58e-3, 5e-6, 0.2e-3), 1.58e-3, 3.16e-3, 5e-6, 0.2e-3),
    "ball_R6.365": (lambda: ball_mesh(6.365e-3, 20e-6, 0.6e-3), 6.365e-3, 12.73e-3, 20e-6, 0.6e-3),
}


@pytest.fixture(scope="module", params=sorted(CURVED))
def curved(request):
    build, radius, height, fine, extent = CURVED[request.param]
    return build(), radius, height, fine, extent


@pytest.fixture(scope="module")
def rod():
    return rod_mesh(3.99e-3, 0.5, 60e-6, 2e-3, layout="tensor")


def areas(mesh):
    """Signed triangle areas, m^2."""
    return mesh_geometry.area2(mesh.p, mesh.t) / 2


def volume(mesh):
    """2 pi * integral of r dA (exact for straight-sided triangles), m^3."""
    return 2 * math.pi * float((areas(mesh) * mesh.p[0, mesh.t].mean(axis=0)).sum())


def min_angle_deg(mesh):
    p, t = mesh.p, mesh.t
    angles = []
    for i in range(3):
        u, v = p[:, t[i - 1]] - p[:, t[i]], p[:, t[i - 2]] - p[:, t[i]]
        cos = (u * v).sum(0) / np.hypot(*u) / np.hypot(*v)
        angles.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
    return float(np.min(angles))


def edge_lengths(mesh, facets):
    return np.hypot(*(mesh.p[:, mesh.facets[0, facets]] - mesh.p[:, mesh.facets[1, facets]]))


def cap_volume(radius, height):
    return math.pi * height**2 * (3 * radius - height) / 3


def assert_boundaries_partition(body):
    """Every boundary facet is named exactly once, the names are also on the mesh."""
    named = np.concatenate(list(body.boundaries.values()))
    assert np.array_equal(np.sort(named), np.sort(body.mesh.boundary_facets()))
    for name, facets in body.boundaries.items():
        assert np.array_equal(body.mesh.boundaries[name], facets)


# ------------------------------------------------------------------------------ rod


def test_rod_coordinates_graded_and_exact(rod):
    a, length, fine, extent = 3.99e-3, 0.5, 60e-6, 2e-3
    for x, end, coarse in ((np.unique(rod.mesh.p[0]), a, a / 4), (np.unique(rod.mesh.p[1]), length, a / 2)):
        assert x[0] == 0.0 and x[-1] == end
        h = np.diff(x)
        in_fine = x[1:] <= extent * (1 + 1e-12)
        assert np.isclose(x[in_fine.sum()], extent, rtol=1e-12, atol=0)
        assert np.allclose(h[in_fine], h[0], rtol=1e-9, atol=0) and h[0] <= fine
        ratio = h[1:] / h[:-1]
        assert ratio.max() <= meshes.GROWTH_RATIO + 1e-12
        assert ratio.min() >= 1 - 1e-9  # never shrinks
        assert h.max() <= coarse * (1 + 1e-12)
    assert rod.fine_size_m <= fine and rod.contact_extent_m == extent


def test_rod_mesh_geometry_and_boundaries(rod):
    a, length = 3.99e-3, 0.5
    mesh, p = rod.mesh, rod.mesh.p
    assert np.all(areas(mesh) > 0)
    assert volume(mesh) == pytest.approx(math.pi * a * a * length, rel=1e-12)
    assert_boundaries_partition(rod)
    for name, index, value in (("axis", 0, 0.0), ("lateral", 0, a), ("end", 1, 0.0), ("far", 1, length)):
        assert np.all(p[index, mesh.facets[:, rod.boundaries[name]]] == value), name
    n_r, n_z = np.unique(p[0]).size, np.unique(p[1]).size
    assert [rod.boundaries[k].size for k in ("axis", "lateral", "end", "far")] == [n_z - 1, n_z - 1, n_r - 1, n_r - 1]
    # square cells near the struck end; elongated ones (fine r, coarse z) far from it
    near = p[:, mesh.t].max(axis=(0, 1)) <= 2e-3
    sub = type(mesh)(p, np.ascontiguousarray(mesh.t[:, near]), sort_t=False)
    assert min_angle_deg(sub) == pytest.approx(45.0, abs=1e-9)
    h_r, h_z = np.diff(np.unique(p[0])), np.diff(np.unique(p[1]))
    assert min_angle_deg(mesh) == pytest.approx(
        math.degrees(math.atan(h_r.min() / h_z.max())), abs=1e-9
    )  # 1.7 degrees here


def test_rod_grading_corner_cases():
    # fine extent beyond the rod: uniform fine spacing everywhere
    body = rod_mesh(1e-3, 2e-3, 0.1e-3, 5e-3, layout="tensor")
    assert np.allclose(np.diff(np.unique(body.mesh.p[1])), 0.1e-3, rtol=1e-9, atol=0)
    # a tail too short to grade: uniform at the fine spacing (<= fine)
    x = meshes._graded(1.0e-3, 0.1e-3, 0.95e-3, 1.0)
    assert x[-1] == 1.0e-3 and np.diff(x).max() <= 0.1e-3 * (1 + 1e-12)
    # an explicit coarse size caps r and z
    body = rod_mesh(5e-3, 0.1, 0.1e-3, 1e-3, coarse_size_m=0.4e-3, layout="tensor")
    for k in range(2):
        h = np.diff(np.unique(body.mesh.p[k]))
        assert h.max() <= 0.4e-3 * (1 + 1e-12)
        assert (h[1:] / h[:-1]).max() <= meshes.GROWTH_RATIO + 1e-12


@pytest.mark.parametrize(
    ("radius", "length", "size_r", "size_z"), [(1e-3, 2e-3, 0.25e-3, 0.5e-3), (5e-3, 0.1, 1.3e-3, 2.6e-3)]
)
def test_the_coarse_rod_grid_is_uniform_and_no_finer_than_needed(radius, length, size_r, size_z):
    """Equal spacings of at most the size, as few as that allows (an integral quotient is not
    rounded up), from 0 to exactly a and L."""
    r, z = meshes.coarse_rod_grid(radius, length, size_r, size_z)
    for x, end, size in ((r, radius, size_r), (z, length, size_z)):
        h = np.diff(x)
        assert x[0] == 0.0 and x[-1] == end
        assert np.allclose(h, h[0], rtol=1e-12, atol=0) and h[0] <= size * (1 + 1e-12)
        assert x.size - 1 == math.ceil(end / size - 1e-9)


# ---------------------------------------------------------------------- curved bodies


def test_curved_triangles_oriented_and_well_shaped(curved):
    body, radius, height, *_ = curved
    assert np.all(areas(body.mesh) > 0)
    corner = math.degrees(math.acos(1 - height / radius)) if height < radius else 90.0
    assert min_angle_deg(body.mesh) >= min(MIN_ANGLE_DEG, 0.8 * corner)


def test_curved_boundaries_exact(curved):
    body, radius, height, *_ = curved
    mesh = body.mesh
    assert_boundaries_partition(body)
    names = {"axis", "surface"} | ({"back"} if height < 2 * radius else set())
    assert set(body.boundaries) == names
    sphere = np.unique(mesh.facets[:, body.boundaries["surface"]])
    distance = np.hypot(mesh.p[0, sphere], mesh.p[1, sphere] + radius)
    assert np.abs(distance / radius - 1).max() <= SPHERE_RTOL
    axis = np.unique(mesh.facets[:, body.boundaries["axis"]])
    assert np.all(mesh.p[0, axis] == 0.0) and np.all(mesh.p[0] >= 0.0)
    assert mesh.p[1, axis].max() == 0.0 and mesh.p[1, axis].min() == -height
    if "back" in names:
        back = np.unique(mesh.facets[:, body.boundaries["back"]])
        assert np.all(mesh.p[1, back] == -height)
    # the surface is one open chain from the contact point to the rim (or the far pole)
    assert sphere.size == body.boundaries["surface"].size + 1
    assert np.any(np.all(mesh.p[:, sphere] == 0.0, axis=0))


def test_curved_element_sizes(curved):
    body, radius, height, fine, extent = curved
    mesh = body.mesh
    longest = mesh_geometry.longest_edges(mesh)
    near = mesh_geometry.distance_to_origin(mesh) <= extent
    assert near.sum() > 0
    assert longest[near].max() <= fine and body.fine_size_m == longest[near].max()
    assert body.contact_extent_m == extent
    assert longest.max() <= min(radius, height) / 4
    chords = edge_lengths(mesh, body.boundaries["surface"])
    assert chords.max() <= meshes.SURFACE_CHORD * radius
    # the contact surface carries nodes at most fine apart out to the extent
    contact = surface_nodes(body, "surface", max_r=extent)
    assert np.diff(mesh.p[0, contact]).max() <= fine and mesh.p[0, contact[-1]] > 0.9 * extent


def test_curved_volume_within_the_chord_error(curved):
    body, radius, height, *_ = curved
    error = 1 - volume(body.mesh) / cap_volume(radius, height)
    assert 0 < error <= CHORD_VOLUME_RTOL * max(1.0, 2 * radius / height)


def test_ball_volume_converges_at_second_order(monkeypatch):
    """Uniformly fine balls (fine extent 3R), chord limit off: the lost volume falls 4x per
    halving; 4.5e-4 relative at R/16."""
    monkeypatch.setattr(meshes, "SURFACE_CHORD", 1.0)
    radius = 1.0
    errors = [
        1 - volume(ball_mesh(radius, radius / k, 3 * radius).mesh) / cap_volume(radius, 2 * radius) for k in (8, 16, 32)
    ]
    assert errors[1] < 1e-3
    orders = np.log2(np.array(errors[:-1]) / errors[1:])
    assert np.all((orders > 1.8) & (orders < 2.2)), orders
    hemisphere = 1 - volume(cap_mesh(radius, radius, radius / 16, 3 * radius).mesh) / (2 * math.pi / 3)
    assert 0 < hemisphere < 1e-3


def test_element_counts_stay_modest():
    """R = 1.58 mm, 5 um within 0.2 mm: about 7300 triangles (the fine zone alone, a
    quarter disc of 0.2 mm, needs about 4000 triangles of edge <= 5 um)."""
    body = ball_mesh(1.58e-3, 5e-6, 0.2e-3)
    assert body.mesh.t.shape[1] < 9000
    body = ball_mesh(1.58e-3, 5e-6, 0.15e-3)  # fine extent 3a for a = 50 um
    assert body.mesh.t.shape[1] < 6000


def test_surface_nodes_sorted_and_local():
    body = ball_mesh(1.58e-3, 20e-6, 0.1e-3)
    p = body.mesh.p
    nodes = surface_nodes(body, "surface")
    assert nodes.size == np.unique(body.mesh.facets[:, body.boundaries["surface"]]).size
    assert np.all(np.diff(p[0, nodes]) >= 0)
    near = surface_nodes(body, "surface", max_r=0.1e-3)
    assert near[0] == nodes[0] and np.all(p[:, near[0]] == 0.0)  # the contact point first
    assert np.all(np.diff(p[0, near]) > 0) and p[0, near].max() <= 0.1e-3
    assert p[1, near].min() > -0.1e-3  # not the far pole, although its r is small too
    rod = rod_mesh(1e-3, 0.01, 50e-6, 0.3e-3, layout="tensor")
    end = surface_nodes(rod, "end", max_r=0.2e-3)
    assert np.allclose(rod.mesh.p[0, end], np.arange(5) * 50e-6, rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="name"):
        surface_nodes(body, "back")
    with pytest.raises(ValueError, match="max_r"):
        surface_nodes(body, "surface", max_r=-1.0)


def test_hertz_mesh_sizes():
    assert hertz_mesh_sizes(50e-6) == pytest.approx((5e-6, 150e-6), rel=1e-15)
    assert hertz_mesh_sizes(0.2e-3, 20) == pytest.approx((10e-6, 0.6e-3), rel=1e-15)
    with pytest.raises(ValueError, match="contact_radius_m"):
        hertz_mesh_sizes(0.0)
    for bad in (0, 2.5, True):
        with pytest.raises(ValueError, match="elements_across"):
            hertz_mesh_sizes(1e-4, bad)


@pytest.mark.parametrize(
    "call, argument",
    [
        (lambda: rod_mesh(0.0, 0.5, 1e-4, 1e-3), "radius_m"),
        (lambda: rod_mesh(1e-3, -0.5, 1e-4, 1e-3), "length_m"),
        (lambda: rod_mesh(1e-3, 0.5, 0.0, 1e-3), "fine_size_m"),
        (lambda: rod_mesh(1e-3, 0.5, float("nan"), 1e-3), "fine_size_m"),
        (lambda: rod_mesh(1e-3, 0.5, 1e-4, 0.0), "fine_extent_m"),
        (lambda: rod_mesh(1e-3, 0.5, 2e-3, 1e-3), "fine_size_m"),
        (lambda: rod_mesh(1e-3, 0.5, 1e-4, 1e-3, coarse_size_m=5e-5), "coarse_size_m"),
        (lambda: rod_mesh(1e-3, 0.5, 1e-4, 1e-3, coarse_size_m=-1.0), "coarse_size_m"),
        (lambda: cap_mesh(-1e-3, 1e-3, 1e-5, 1e-4), "sphere_radius_m"),
        (lambda: cap_mesh(1e-3, 0.0, 1e-5, 1e-4), "height_m"),
        (lambda: cap_mesh(1e-3, 2e-3, 1e-5, 1e-4), "height_m"),
        (lambda: cap_mesh(1e-3, 0.5e-3, 0.6e-3, 1e-4), "fine_size_m"),
        (lambda: cap_mesh(1e-3, 1e-3, 1e-5, float("inf")), "fine_extent_m"),
        (lambda: ball_mesh(0.0, 1e-5, 1e-4), "sphere_radius_m"),
        (lambda: ball_mesh(1e-3, -1e-5, 1e-4), "fine_size_m"),
        (lambda: ball_mesh(1e-3, 1.5e-3, 1e-4), "fine_size_m"),
        (lambda: ball_mesh(1e-3, 1e-5, -1e-4), "fine_extent_m"),
    ],
)
def test_bad_input_names_the_argument(call, argument):
    with pytest.raises(ValueError, match=argument):
        call()


def test_coarse_fine_size_gives_a_uniform_body():
    """A fine size above R/4 leaves every element at most min(fine, R/4)."""
    body = ball_mesh(1e-3, 0.5e-3, 0.1e-3)
    assert mesh_geometry.longest_edges(body.mesh).max() <= 0.25e-3
    assert np.all(areas(body.mesh) > 0)


def test_refined_rod_is_fine_only_near_the_contact():
    """The default layout: fine within the extent, coarse along the rest of the rod."""
    fine, extent = 80e-6, 2.5e-3
    body = rod_mesh(3.99e-3, 0.5, fine, extent)
    mesh = body.mesh
    p = mesh.p
    edges = np.max(np.stack([np.hypot(*(p[:, mesh.t[i]] - p[:, mesh.t[(i + 1) % 3]])) for i in range(3)]), axis=0)
    centres = p[:, mesh.t].mean(axis=1)
    near = np.hypot(*centres) <= extent
    assert edges[near].max() <= fine * (1 + 1e-9)
    assert edges[np.hypot(*centres) > 0.1].min() > 5 * fine  # no fine elements far away
    assert mesh.t.shape[1] < 15_000  # a tensor grid graded the same way needs about 25,000
    assert np.isclose(p[0].min(), 0) and np.isclose(p[0].max(), 3.99e-3) and np.isclose(p[1].max(), 0.5)
    d1, d2 = p[:, mesh.t[1]] - p[:, mesh.t[0]], p[:, mesh.t[2]] - p[:, mesh.t[0]]
    area = 0.5 * np.abs(d1[0] * d2[1] - d1[1] * d2[0])
    assert area.sum() == pytest.approx(3.99e-3 * 0.5, rel=1e-12)
    for name, (coord, value) in {"axis": (0, 0.0), "end": (1, 0.0), "far": (1, 0.5), "lateral": (0, 3.99e-3)}.items():
        facets = body.boundaries[name]
        assert len(facets) > 0 and np.allclose(p[coord, mesh.facets[:, facets]], value)
