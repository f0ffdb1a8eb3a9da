"""Axisymmetric elasticity (rodimpact.solvers.fem_axi.axisym) against mathematics: exact uniform-strain
solutions (axial stress with Poisson contraction; uniform radial expansion, which loads the
hoop strain), the mass of a cylinder, the null space of K, and observed orders of convergence
for a manufactured smooth solution."""

import logging
import math

import numpy as np
import pytest
from skfem import (
    Basis,
    ElementTriP1,
    ElementTriP2,
    ElementVector,
    Functional,
    LinearForm,
    MeshTri,
    asm,
    condense,
    solve,
)

from rodimpact.solvers.fem_axi.axisym import (
    axis_dofs,
    axisym_load,
    axisym_mass,
    axisym_stiffness,
    component_dofs,
    cross_section_mean_uz,
    strain,
)

from helpers.paper import STEEL

E, NU, RHO = STEEL.youngs_modulus_pa, STEEL.poisson_ratio, STEEL.density_kg_m3  # 2.1e11, 0.30, 7800.0
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
A, L = 0.01, 0.03  # cylinder radius and length, m
log = logging.getLogger(__name__)
ELEMENTS = {"P1": ElementTriP1, "P2": ElementTriP2}


def cylinder(element: str, nr: int = 5, nz: int = 6) -> Basis:
    """Graded mesh of 0 <= r <= A, 0 <= z <= L (boundaries left = axis, right, bottom, top)."""
    r = np.r_[0.0, A * np.geomspace(0.08, 1.0, nr)]
    z = L * np.r_[0.0, np.geomspace(0.05, 1.0, nz)]
    mesh = MeshTri.init_tensor(r, z).with_defaults()
    return Basis(mesh, ElementVector(ELEMENTS[element]()))


def nodal(basis: Basis, ur, uz) -> np.ndarray:
    """Lagrange interpolant of (u_r, u_z)(r, z) (exact for fields in the FE space)."""
    u = np.zeros(basis.N)
    for comp, fun in ((0, ur), (1, uz)):
        idx = component_dofs(basis, comp)
        u[idx] = fun(basis.doflocs[0, idx], basis.doflocs[1, idx])
    return u


def solve_dirichlet(K, f, D, x=None) -> np.ndarray:
    return solve(*condense(K, f, x=x, D=D))


def axial_state(element: str, s: float = 1.0e8):
    """Test 1's problem: u_z = 0 on z = 0 (frictionless), sigma_zz = s on z = L."""
    basis = cylinder(element)
    K = axisym_stiffness(basis, E, NU)
    f = axisym_load(basis, lambda r, z: (0.0, s), "top")
    bottom_z = component_dofs(basis, 1, "bottom")
    D = np.union1d(axis_dofs(basis), bottom_z)
    return basis, K, f, solve_dirichlet(K, f, D), bottom_z


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_uniaxial_stress_is_exact(element):
    s = 1.0e8
    basis, K, f, u, bottom_z = axial_state(element, s)
    exact = nodal(basis, lambda r, z: -NU * s * r / E, lambda r, z: s * z / E)
    assert np.max(np.abs(u - exact)) < 1e-10 * np.max(np.abs(exact))
    # the load and the reaction are the 3D forces divided by 2 pi
    top_z = component_dofs(basis, 1, "top")
    assert 2 * math.pi * f[top_z].sum() == pytest.approx(s * math.pi * A**2, rel=1e-12)
    reaction = (K @ u - f)[bottom_z]
    assert 2 * math.pi * reaction.sum() == pytest.approx(-s * math.pi * A**2, rel=1e-10)
    # post-processing through strain(): uniform strains at the quadrature points
    err, ezz, ett, grz = strain(basis.interpolate(u), np.asarray(basis.global_coordinates())[0])
    np.testing.assert_allclose(ezz, s / E, rtol=1e-9)
    np.testing.assert_allclose(err, -NU * s / E, rtol=1e-9)
    np.testing.assert_allclose(ett, -NU * s / E, rtol=1e-9)
    assert np.max(np.abs(grz)) < 1e-9 * s / E


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_uniform_radial_expansion_energy(element):
    """u_r = c r, u_z = 0: e_rr = e_tt = c, sigma_rr = sigma_tt = 2 c (lam + mu),
    sigma_zz = 2 lam c; W = 2 c^2 (lam + mu); 3D energy W pi a^2 L."""
    c = 1.0e-4
    basis = cylinder(element)
    K = axisym_stiffness(basis, E, NU)
    f = axisym_load(basis, lambda r, z: (2 * c * (LAM + MU), 0.0), "right") + axisym_load(
        basis, lambda r, z: (0.0, 2 * LAM * c), "top"
    )
    D = np.union1d(axis_dofs(basis), component_dofs(basis, 1, "bottom"))
    u = solve_dirichlet(K, f, D)
    exact = nodal(basis, lambda r, z: c * r, lambda r, z: 0.0 * z)
    assert np.max(np.abs(u - exact)) < 1e-10 * np.max(np.abs(exact))
    energy = 2 * math.pi * 0.5 * u @ (K @ u)
    analytic = 2 * c**2 * (LAM + MU) * math.pi * A**2 * L
    assert energy == pytest.approx(analytic, rel=1e-10)
    assert 2 * math.pi * 0.5 * f @ u == pytest.approx(analytic, rel=1e-10)  # Clapeyron


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_mass_of_rigid_translations(element):
    basis = cylinder(element)
    M = axisym_mass(basis, RHO)
    for comp in (0, 1):
        ones = np.zeros(basis.N)
        ones[component_dofs(basis, comp)] = 1.0
        assert 2 * math.pi * ones @ (M @ ones) == pytest.approx(RHO * math.pi * A**2 * L, rel=1e-12)
    # with intorder 2p + 1 the mass is exact: u_z = z^p is in the Pp space and
    # 2 pi int rho z^(2p) r dr dz = rho pi a^2 L^(2p+1) / (2p + 1)
    p = basis.elem.maxdeg
    hi = Basis(basis.mesh, basis.elem, intorder=2 * p + 1)
    uz = nodal(hi, lambda r, z: 0 * r, lambda r, z: z if p == 1 else z**2)
    moment = RHO * math.pi * A**2 * (L**3 / 3 if p == 1 else L**5 / 5)
    assert 2 * math.pi * uz @ (axisym_mass(hi, RHO) @ uz) == pytest.approx(moment, rel=1e-12)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_null_space_is_the_axial_translation(element):
    basis = cylinder(element, nr=3, nz=3)
    K = axisym_stiffness(basis, E, NU)
    scale = abs(K).max()
    ones_z = nodal(basis, lambda r, z: 0 * r, lambda r, z: 1 + 0 * z)
    ones_r = nodal(basis, lambda r, z: 1 + 0 * r, lambda r, z: 0 * z)
    assert np.max(np.abs(K @ ones_z)) < 1e-12 * scale
    # a radial translation stretches the hoops (e_tt = 1 / r): not a rigid motion
    assert np.max(np.abs(K @ ones_r)) > 1e-2 * scale
    assert ones_r @ (K @ ones_r) > 0.0
    # one zero eigenvalue only (no torsion, no radial rigid motion), even without the axis
    # condition; its eigenvector is the axial translation
    w, v = np.linalg.eigh(K.toarray())
    assert np.sum(np.abs(w) < 1e-10 * w.max()) == 1
    assert np.sum(w[1:] > 1e-10 * w.max()) == basis.N - 1
    cosine = abs(v[:, 0] @ ones_z) / np.linalg.norm(ones_z)
    assert cosine == pytest.approx(1.0, abs=1e-10)


# --- manufactured solution on 0 <= r <= 1, 0 <= z <= 1 (E = 1, nu = 0.3) -------------------
# u_r = a(r) sin z, a = r - r^3;   u_z = b(r) cos z, b = cos(r^2)
# e_rr = a' sin z, e_tt = (1 - r^2) sin z, e_zz = -b sin z, gamma = a cos z + b' cos z
LAM1, MU1 = NU / ((1 + NU) * (1 - 2 * NU)), 1 / (2 * (1 + NU))


def mms_u(r, z):
    return (r - r**3) * np.sin(z), np.cos(r**2) * np.cos(z)


def mms_strain(r, z):
    """(e_rr, e_zz, e_tt, gamma_rz) of the manufactured field."""
    s, c = np.sin(z), np.cos(z)
    b, db = np.cos(r**2), -2 * r * np.sin(r**2)
    return (1 - 3 * r**2) * s, -b * s, (1 - r**2) * s, (r - r**3) * c + db * c


def mms_stress(r, z):
    """(s_rr, s_zz, s_tt, s_rz), E = 1."""
    err, ezz, ett, grz = mms_strain(r, z)
    tr = err + ezz + ett
    return (LAM1 * tr + 2 * MU1 * err, LAM1 * tr + 2 * MU1 * ezz, LAM1 * tr + 2 * MU1 * ett, MU1 * grz)


def mms_body_force(r, z):
    """f from the axisymmetric equilibrium equations, differentiated by hand:

        d(s_rr)/dr + d(s_rz)/dz + (s_rr - s_tt)/r + f_r = 0,
        d(s_rz)/dr + d(s_zz)/dz + s_rz/r + f_z = 0,

    with tr e = (1 - 3r^2) s - b s + (1 - r^2) s = (2 - 4r^2 - b) s (s = sin z, c = cos z),
    s_rr - s_tt = 2 mu (e_rr - e_tt) = -4 mu r^2 s and s_rz / r = mu ((1 - r^2) c + (b'/r) c)
    with b'/r = -2 sin(r^2): no term is singular on the axis.
    """
    s, c = np.sin(z), np.cos(z)
    b = np.cos(r**2)
    db = -2 * r * np.sin(r**2)
    d2b = -2 * np.sin(r**2) - 4 * r**2 * np.cos(r**2)
    dtr_dr = (-8 * r - db) * s
    dtr_dz = (2 - 4 * r**2 - b) * c
    ds_rr_dr = LAM1 * dtr_dr + 2 * MU1 * (-6 * r) * s
    ds_rz_dz = MU1 * (-(r - r**3) - db) * s
    hoop_over_r = -4 * MU1 * r * s
    f_r = -(ds_rr_dr + ds_rz_dz + hoop_over_r)
    ds_rz_dr = MU1 * ((1 - 3 * r**2) + d2b) * c
    ds_zz_dz = LAM1 * dtr_dz + 2 * MU1 * (-b * c)
    s_rz_over_r = MU1 * ((1 - r**2) - 2 * np.sin(r**2)) * c
    f_z = -(ds_rz_dr + ds_zz_dz + s_rz_over_r)
    return f_r, f_z


def test_body_force_satisfies_equilibrium_by_finite_differences():
    rng = np.random.default_rng(1)
    r, z = rng.uniform(0.1, 1.0, 20), rng.uniform(0.0, 1.0, 20)
    h = 1e-5
    s_rr, _, s_tt, s_rz = mms_stress(r, z)
    d_dr = [(p - m) / (2 * h) for p, m in zip(mms_stress(r + h, z), mms_stress(r - h, z))]
    d_dz = [(p - m) / (2 * h) for p, m in zip(mms_stress(r, z + h), mms_stress(r, z - h))]
    f_r, f_z = mms_body_force(r, z)
    np.testing.assert_allclose(-(d_dr[0] + d_dz[3] + (s_rr - s_tt) / r), f_r, rtol=1e-7, atol=1e-8)
    np.testing.assert_allclose(-(d_dr[3] + d_dz[1] + s_rz / r), f_z, rtol=1e-7, atol=1e-8)
    # and the strains are those of the displacement
    d_ur_dr = (mms_u(r + h, z)[0] - mms_u(r - h, z)[0]) / (2 * h)
    d_uz_dr = (mms_u(r + h, z)[1] - mms_u(r - h, z)[1]) / (2 * h)
    d_ur_dz = (mms_u(r, z + h)[0] - mms_u(r, z - h)[0]) / (2 * h)
    d_uz_dz = (mms_u(r, z + h)[1] - mms_u(r, z - h)[1]) / (2 * h)
    err, ezz, ett, grz = mms_strain(r, z)
    np.testing.assert_allclose(err, d_ur_dr, atol=1e-9)
    np.testing.assert_allclose(ezz, d_uz_dz, atol=1e-9)
    np.testing.assert_allclose(ett, mms_u(r, z)[0] / r, atol=1e-12)
    np.testing.assert_allclose(grz, d_ur_dz + d_uz_dr, atol=1e-9)


def mms_errors(element: str, n: int) -> tuple[float, float]:
    """L2 and energy-norm errors (r-weighted, per radian) on an n x n mesh of the unit square."""
    mesh = MeshTri.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1)).with_defaults()
    basis = Basis(mesh, ElementVector(ELEMENTS[element]()))
    K = axisym_stiffness(basis, 1.0, NU)

    @LinearForm
    def body(v, w):
        f_r, f_z = mms_body_force(w.x[0], w.x[1])
        return (f_r * v[0] + f_z * v[1]) * w.x[0]

    f = asm(body, basis)
    D = np.unique(np.concatenate([axis_dofs(basis), basis.get_dofs({"right", "bottom", "top"}).all()]))
    u = solve_dirichlet(K, f, D, x=nodal(basis, lambda r, z: mms_u(r, z)[0], lambda r, z: mms_u(r, z)[1]))
    hi = Basis(mesh, basis.elem, intorder=2 * basis.elem.maxdeg + 4)

    @Functional
    def l2(w):
        ur, uz = mms_u(w.x[0], w.x[1])
        return ((w.uh[0] - ur) ** 2 + (w.uh[1] - uz) ** 2) * w.x[0]

    @Functional
    def energy(w):
        d = [a - b for a, b in zip(strain(w.uh, w.x[0]), mms_strain(w.x[0], w.x[1]))]
        tr = d[0] + d[1] + d[2]
        return (LAM1 * tr**2 + 2 * MU1 * (d[0] ** 2 + d[1] ** 2 + d[2] ** 2) + MU1 * d[3] ** 2) * w.x[0]

    uh = hi.interpolate(u)
    return math.sqrt(l2.assemble(hi, uh=uh)), math.sqrt(energy.assemble(hi, uh=uh))


@pytest.mark.parametrize(
    "element, sizes, l2_order, energy_order",
    [
        ("P1", (4, 8, 16, 32), (1.8, 2.3), (0.9, 1.2)),
        ("P2", (2, 4, 8, 16), (2.7, 3.4), (1.8, 2.3)),
    ],
)
def test_manufactured_solution_convergence(element, sizes, l2_order, energy_order):
    errors = np.array([mms_errors(element, n) for n in sizes])
    h = 1.0 / np.asarray(sizes, float)
    p_l2 = np.polyfit(np.log(h), np.log(errors[:, 0]), 1)[0]
    p_en = np.polyfit(np.log(h), np.log(errors[:, 1]), 1)[0]
    log.info(
        "%s: L2 errors %s, order %.3f; energy errors %s, order %.3f", element, errors[:, 0], p_l2, errors[:, 1], p_en
    )
    assert l2_order[0] <= p_l2 <= l2_order[1]
    assert energy_order[0] <= p_en <= energy_order[1]
    assert np.all(np.diff(errors, axis=0) < 0)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_cross_section_mean(element):
    s = 1.0e8
    basis, _, _, u, _ = axial_state(element, s)
    for z in (0.0, 0.37 * L, 0.5 * L, L):
        row = cross_section_mean_uz(basis, z, A)
        assert row.shape == (1, basis.N)
        assert (row @ u)[0] == pytest.approx(s * z / E, rel=1e-10, abs=1e-10 * s * L / E)
    if element == "P2":  # u_z = r^2 is in P2: mean over a disc of radius R is R^2 / 2
        uz = nodal(basis, lambda r, z: 0 * r, lambda r, z: r**2)
        for radius in (0.3 * A, A):
            row = cross_section_mean_uz(basis, 0.41 * L, radius, n=8)
            assert (row @ uz)[0] == pytest.approx(radius**2 / 2, rel=1e-12)


def test_bad_input_names_the_argument():
    basis = cylinder("P1", nr=2, nz=2)
    with pytest.raises(ValueError, match="youngs_modulus_pa"):
        axisym_stiffness(basis, -1.0, NU)
    with pytest.raises(ValueError, match="poisson_ratio"):
        axisym_stiffness(basis, E, 0.5)
    with pytest.raises(ValueError, match="density_kg_m3"):
        axisym_mass(basis, 0.0)
    with pytest.raises(ValueError, match="basis"):
        axisym_mass(Basis(basis.mesh, ElementTriP1()), RHO)
    with pytest.raises(ValueError, match="component"):
        component_dofs(basis, 2, "top")
    with pytest.raises(ValueError, match="dofs"):
        component_dofs(basis, 0, "nowhere")
    with pytest.raises(ValueError, match="facets"):
        axisym_load(basis, lambda r, z: (0.0, 1.0), "nowhere")
    with pytest.raises(ValueError, match="radius"):
        cross_section_mean_uz(basis, 0.5 * L, 2 * A)
    with pytest.raises(ValueError, match="z must"):
        cross_section_mean_uz(basis, 2 * L, A)
    with pytest.raises(ValueError, match="n must"):
        cross_section_mean_uz(basis, L, A, n=0)
    with pytest.raises(ValueError, match="tol"):
        axis_dofs(basis, tol=-1.0)
