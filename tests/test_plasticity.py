"""J2 plasticity's return mapping (rodimpact.solvers.fem_axi.plasticity) against closed forms:
a uniaxial-strain path, a uniaxial-stress path (the lateral strains found by Newton on the
consistent tangent, which converges quadratically), a pure shear through the engineering shear
component, elastic unloading, and the tangent against finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.solvers.fem_axi.plasticity import J2Material, J2State, return_map

E, NU, Y = 7.0e10, 0.33, 2.8e8
MATERIALS = {"perfect": J2Material(E, NU, Y), "hardening": J2Material(E, NU, Y, 7.0e9)}


def _path(material: J2Material, strains: np.ndarray) -> tuple[np.ndarray, J2State]:
    """The stresses along a path of total strains (m, 4), one step each, from a virgin state."""
    state, stresses = J2State.virgin(1), []
    for eps in strains:
        update = return_map(material, eps[None], state)
        state = update.state
        stresses.append(update.stress[0])
    return np.asarray(stresses), state


@pytest.mark.parametrize("name", MATERIALS)
def test_uniaxial_strain_against_its_closed_form(name: str) -> None:
    """e_zz = eps, the other strains zero (a confined layer): elastic to eps_y = Y / (2 mu),
    then q = Y + H alpha with alpha = (2 mu eps - Y) / (3 mu + H), the mean stress K eps."""
    material = MATERIALS[name]
    mu, bulk, h = material.mu, material.bulk, material.hardening_modulus_pa
    levels = np.linspace(0.0, -12.0 * Y / (2.0 * mu), 37)[1:]  # compression, past yield
    strains = np.zeros((len(levels), 4))
    strains[:, 1] = levels
    stresses, state = _path(material, strains)
    for eps, sigma in zip(levels, stresses):
        strain = abs(eps)
        alpha = max((2.0 * mu * strain - Y) / (3.0 * mu + h), 0.0)
        q = 2.0 * mu * strain if alpha == 0.0 else Y + h * alpha
        expected_zz = bulk * eps - 2.0 / 3.0 * q  # compression: the axial stress is the larger in size
        expected_lateral = bulk * eps + 1.0 / 3.0 * q
        assert sigma[1] == pytest.approx(expected_zz, rel=1e-10)
        assert sigma[0] == pytest.approx(expected_lateral, rel=1e-10) and sigma[2] == pytest.approx(sigma[0], rel=1e-12)
        assert sigma[3] == 0.0
    assert state.equivalent_plastic_strain[0] == pytest.approx(
        (2.0 * mu * abs(levels[-1]) - Y) / (3.0 * mu + h), rel=1e-10
    )


def _uniaxial_stress(material: J2Material, axial: float, state: J2State) -> tuple[np.ndarray, J2State, list[float]]:
    """e_zz = axial, the lateral strains (rr = tt) found by Newton so that s_rr = s_tt = 0,
    with the consistent tangent: the stress, the state and the residuals of the iterations."""
    lateral, residuals = -NU * axial, []
    for _ in range(30):
        eps = np.array([[lateral, axial, lateral, 0.0]])
        update = return_map(material, eps, state)
        residual = update.stress[0, 0]
        residuals.append(abs(residual))
        if abs(residual) <= 1e-13 * Y:
            return update.stress[0], update.state, residuals
        slope = update.tangent[0, 0, 0] + update.tangent[0, 0, 2]  # d s_rr / d lateral (rr and tt move together)
        lateral -= residual / slope
    raise AssertionError(f"Newton did not converge: {residuals}")


@pytest.mark.parametrize("name", MATERIALS)
def test_uniaxial_stress_against_its_closed_form(name: str) -> None:
    """s_zz = E eps to yield, then Y + E_t (eps - Y / E) with E_t = E H / (E + H); unloading is
    elastic and leaves the plastic strain eps - s / E."""
    material = MATERIALS[name]
    h = material.hardening_modulus_pa
    tangent_modulus = E * h / (E + h)
    state = J2State.virgin(1)
    peak = 6.0 * Y / E
    for axial in np.linspace(0.0, peak, 25)[1:]:
        sigma, state, residuals = _uniaxial_stress(material, float(axial), state)
        expected = E * axial if axial <= Y / E else Y + tangent_modulus * (axial - Y / E)
        assert sigma[1] == pytest.approx(expected, rel=1e-10)
        if len(residuals) >= 4 and residuals[1] > 1e-6 * Y:  # a plastic step: quadratic convergence
            assert residuals[2] <= 10.0 * residuals[1] ** 2 / residuals[0] + 1e-12 * Y
    top = Y + tangent_modulus * (peak - Y / E)
    plastic = peak - top / E  # the plastic strain the peak leaves
    assert state.equivalent_plastic_strain[0] == pytest.approx(plastic, rel=1e-10)
    # unloading to zero stress is elastic: the axial strain is the plastic strain
    sigma, state, _ = _uniaxial_stress(material, plastic, state)
    assert abs(sigma[1]) <= 1e-9 * Y
    assert state.plastic_strain[0, 1] == pytest.approx(plastic, rel=1e-10)
    assert state.plastic_strain[0, 0] == pytest.approx(-0.5 * plastic, rel=1e-10)  # isochoric


def test_pure_shear_yields_at_y_over_root_3() -> None:
    """gamma_rz alone: s_rz = mu gamma up to Y / sqrt(3), then flat (perfectly plastic); the
    engineering shear is carried with its factor 2 in the plastic strain."""
    material = MATERIALS["perfect"]
    gammas = np.linspace(0.0, 8.0 * Y / (math.sqrt(3.0) * material.mu), 33)[1:]
    strains = np.zeros((len(gammas), 4))
    strains[:, 3] = gammas
    stresses, state = _path(material, strains)
    expected = np.minimum(material.mu * gammas, Y / math.sqrt(3.0))
    np.testing.assert_allclose(stresses[:, 3], expected, rtol=1e-10)
    np.testing.assert_allclose(stresses[:, :3], 0.0, atol=1e-6)
    # the elastic shear left is s / mu: the rest of gamma is plastic
    assert state.plastic_strain[0, 3] == pytest.approx(gammas[-1] - Y / (math.sqrt(3.0) * material.mu), rel=1e-10)


@pytest.mark.parametrize("name", MATERIALS)
def test_the_tangent_is_the_derivative_of_the_update(name: str) -> None:
    material = MATERIALS[name]
    rng = np.random.default_rng(7)
    start = J2State(rng.normal(scale=1e-3, size=(6, 4)), np.abs(rng.normal(scale=1e-3, size=6)))
    strain = start.plastic_strain + rng.normal(scale=4.0 * Y / E, size=(6, 4))
    update = return_map(material, strain, start)
    assert update.yielded.sum() >= 3
    h = 1e-7 * Y / E
    for j in range(4):
        step = np.zeros(4)
        step[j] = h
        numeric = (
            return_map(material, strain + step, start).stress - return_map(material, strain - step, start).stress
        ) / (2.0 * h)
        np.testing.assert_allclose(update.tangent[:, :, j], numeric, rtol=1e-5, atol=1e-6 * E)


def test_an_elastic_step_is_hookes_law_and_costs_nothing_plastic() -> None:
    material = MATERIALS["hardening"]
    strain = np.array([[1e-4, -3e-4, 1e-4, 2e-4]])
    update = return_map(material, strain, J2State.virgin(1))
    assert not update.yielded.any() and update.plastic_work[0] == 0.0
    hooke = material.elastic_tangent @ strain[0]
    np.testing.assert_allclose(update.stress[0], hooke, rtol=1e-13, atol=1e-13 * np.abs(hooke).max())
    with pytest.raises(ValueError, match="hardening_modulus_pa"):
        J2Material(E, NU, Y, 2.0 * E)
    with pytest.raises(ValueError, match="yield_stress_pa"):
        J2Material(E, NU, 0.0)
