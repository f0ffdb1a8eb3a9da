"""The continuum's fast paths against the plain computations they replace: the axisymmetric
stiffness against scikit-fem's ``asm`` of the same bilinear form (bit for bit), and
``spd_inverse_rows`` (rows K^-1 rows^T from the factor's elimination-tree block) against
full solves."""

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTriP1, ElementTriP2, ElementVector, MeshTri, asm

from rodimpact.solvers.fem_axi.axibody import spd_inverse_rows
from rodimpact.solvers.fem_axi.axisym import axis_dofs, axisym_stiffness, strain

E, NU = 2.1e11, 0.3


def _asm_stiffness(basis: Basis) -> sp.csr_matrix:
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))

    @BilinearForm
    def form(u, v, w):
        r = w.x[0]
        urr, uzz, utt, urz = strain(u, r)
        vrr, vzz, vtt, vrz = strain(v, r)
        return (
            lam * (urr + uzz + utt) * (vrr + vzz + vtt)
            + 2.0 * mu * (urr * vrr + uzz * vzz + utt * vtt)
            + mu * urz * vrz
        ) * r

    return asm(form, basis).tocsr()


def _basis(element, part: bool) -> Basis:
    mesh = MeshTri.init_tensor(np.geomspace(1e-3, 1e-2, 6) - 1e-3, np.linspace(0.0, 0.02, 7))
    elements = np.arange(0, mesh.t.shape[1], 2) if part else None
    elem = ElementVector(element())
    return Basis(mesh, elem) if elements is None else Basis(mesh, elem, elements=elements)


@pytest.mark.parametrize("element", [ElementTriP1, ElementTriP2])
@pytest.mark.parametrize("part", [False, True])
def test_stiffness_is_asm_of_the_form_bit_for_bit(element, part):
    basis = _basis(element, part)
    fast, plain = axisym_stiffness(basis, E, NU), _asm_stiffness(basis)
    assert np.array_equal(fast.indptr, plain.indptr) and np.array_equal(fast.indices, plain.indices)
    assert np.array_equal(fast.data, plain.data)


def test_spd_inverse_rows_matches_full_solves():
    basis = _basis(ElementTriP2, False)
    K = axisym_stiffness(basis, E, NU)
    bottom = np.flatnonzero(basis.doflocs[1] == 0.0)
    held = np.union1d(axis_dofs(basis), bottom)  # u_r on the axis, the bottom clamped: K is SPD
    free = np.setdiff1d(np.arange(basis.N), held)
    K = sp.csc_matrix(K[free][:, free])
    top = np.flatnonzero(basis.doflocs[1, free] == basis.doflocs[1].max())
    rng = np.random.default_rng(1)
    rows = sp.random(len(top), len(free), density=0.0, format="lil")
    for i, j in enumerate(top):  # a pick and a neighbour's weight, as the contact's rows are
        rows[i, j] = 1.0
        rows[i, top[(i + 1) % len(top)]] = rng.uniform(-0.5, 0.5)
    rows = sp.csr_matrix(rows)
    inverse_rows, solve = spd_inverse_rows(K, rows)
    dense = rows @ np.linalg.solve(K.toarray(), rows.T.toarray())
    assert np.allclose(inverse_rows, dense, rtol=1e-11, atol=1e-11 * np.abs(dense).max())
    assert np.allclose(inverse_rows, inverse_rows.T, rtol=0, atol=0)
    b = rng.standard_normal(len(free))
    assert np.allclose(K @ solve(b), b, atol=1e-9 * np.abs(b).max())
