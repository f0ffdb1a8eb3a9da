"""The rod as a 1D bar in scikit-fem: mesh, mass and stiffness, end and station probes."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.linalg import cholesky_banded, get_lapack_funcs
from scipy.sparse.csgraph import reverse_cuthill_mckee
from skfem import Basis, BilinearForm, ElementLineP1, ElementLineP2, MeshLine, asm

from rodimpact.model.responses import Rod

__all__ = ["BarModel", "ELEMENTS", "banded_solver", "bar_model", "row_blocks"]

ELEMENTS = {"P1": ElementLineP1, "P2": ElementLineP2}


@dataclass(frozen=True)
class BarModel:
    """Assembled bar on its free degrees of freedom (the fixed far end eliminated).

    Attributes
    ----------
    mass, stiffness : scipy.sparse.csc_matrix, shape (d, d)
        rho S int u v dx and E S int u' v' dx on the free DOFs, kg and N/m.
    end : int
        Index (among the free DOFs) of the struck end's node, x = 0.
    station_probes : scipy.sparse.csr_matrix, shape (k, d)
        Displacement at the stations.
    strain_probes : scipy.sparse.csr_matrix, shape (k, d)
        Axial strain du/dx at the stations (central difference inside the elements, the
        mean of the two sides at a node).
    dof_spacing_m : float
        Element length / element order.
    n_elements : int
    field_probes : scipy.sparse.csr_matrix, shape (f, d)
        Axial strain at the cross-sections of the strain field, as ``strain_probes``.
    gauge_probes : scipy.sparse.csr_matrix, shape (g, d)
        Mean axial strain over each gauge: (u(x + g/2) - u(x - g/2)) / g, the displacement
        probed at both ends of the gauge; a point gauge (g = 0) as ``strain_probes``.
    far_probe : scipy.sparse.csr_matrix, shape (1, d), or None
        The far end's value (x = l) of a nodal field (its velocity from the velocities); a
        zero row when the far end is fixed (its DOF eliminated).
    """

    mass: sp.csc_matrix
    stiffness: sp.csc_matrix
    end: int
    station_probes: sp.csr_matrix
    strain_probes: sp.csr_matrix
    dof_spacing_m: float
    n_elements: int
    field_probes: sp.csr_matrix | None = None
    gauge_probes: sp.csr_matrix | None = None
    far_probe: sp.csr_matrix | None = None


def bar_model(
    rod: Rod,
    element: Literal["P1", "P2"],
    n_elements: int,
    stations_m: Sequence[float] = (),
    field_m: Sequence[float] = (),
    gauges_m: Sequence[tuple[float, float]] = (),
    far_end: bool = False,
) -> BarModel:
    """Assemble the bar 0 <= x <= l struck at x = 0 (the far end fixed or free).

    Parameters
    ----------
    rod : Rod
        The rod (finite length).
    element : {"P1", "P2"}
        Lagrange elements of order 1 or 2.
    n_elements : int
        Number of equal elements (>= 1).
    stations_m : sequence of float
        Positions of the probes, m from the struck end.
    field_m : sequence of float
        Cross-sections of the strain field (:attr:`BarModel.field_probes`), m from the struck end.
    gauges_m : sequence of (float, float)
        The gauges' centres and lengths (:attr:`BarModel.gauge_probes`), m.
    far_end : bool
        Build the far end's probe (:attr:`BarModel.far_probe`).
    """
    if element not in ELEMENTS:
        raise ValueError(f"element must be one of {sorted(ELEMENTS)}, got {element!r}")
    if int(n_elements) != n_elements or n_elements < 1:
        raise ValueError(f"n_elements must be a positive integer, got {n_elements!r}")
    length = rod.length_m
    if not np.isfinite(length):
        raise ValueError("fem1d needs a rod of finite length")
    mesh = MeshLine(np.linspace(0.0, length, int(n_elements) + 1))
    basis = Basis(mesh, ELEMENTS[element]())
    e_s = rod.material.youngs_modulus_pa * rod.area_m2
    rho_s = rod.material.density_kg_m3 * rod.area_m2

    @BilinearForm
    def mass_form(u, v, w):
        return rho_s * u * v

    @BilinearForm
    def stiffness_form(u, v, w):
        return e_s * u.grad[0] * v.grad[0]

    mass = asm(mass_form, basis)
    stiffness = asm(stiffness_form, basis)
    free = np.arange(basis.N)
    if rod.far_end == "fixed":
        fixed = basis.get_dofs(lambda x: np.isclose(x[0], length)).all()
        free = np.setdiff1d(free, fixed)
    end_global = int(basis.get_dofs(lambda x: np.isclose(x[0], 0.0)).all()[0])
    end = int(np.flatnonzero(free == end_global)[0])

    stations = np.asarray(list(stations_m), dtype=float)
    h_e = length / n_elements
    if len(stations):
        values = basis.probes(stations[None, :])
    else:
        values = sp.csr_matrix((0, basis.N))
    return BarModel(
        mass=mass[free][:, free].tocsc(),
        stiffness=stiffness[free][:, free].tocsc(),
        end=end,
        station_probes=sp.csr_matrix(values)[:, free],
        strain_probes=_strain_probes(basis, stations, length, h_e)[:, free],
        dof_spacing_m=h_e / (1 if element == "P1" else 2),
        n_elements=int(n_elements),
        field_probes=_strain_probes(basis, np.asarray(list(field_m), dtype=float), length, h_e)[:, free],
        gauge_probes=_gauge_probes(basis, gauges_m, length, h_e)[:, free] if len(gauges_m) else None,
        far_probe=sp.csr_matrix(basis.probes(np.array([[length]])))[:, free] if far_end else None,
    )


def _gauge_probes(basis: Basis, gauges_m: Sequence[tuple[float, float]], length: float, h_e: float) -> sp.csr_matrix:
    """The mean strain over each gauge (centre x, length g, m), shape (k, N): the difference
    of the displacement at its ends over g; a point gauge's du/dx as :func:`_strain_probes`."""
    rows = []
    for x, g in gauges_m:
        if g > 0.0:
            ends = np.array([[x - 0.5 * g, x + 0.5 * g]])
            values = sp.csr_matrix(basis.probes(ends))
            rows.append((values[1] - values[0]) / g)
        else:
            rows.append(_strain_probes(basis, np.array([x]), length, h_e))
    return sp.csr_matrix(sp.vstack(rows))


def _strain_probes(basis: Basis, positions: NDArray[np.float64], length: float, h_e: float) -> sp.csr_matrix:
    """du/dx at ``positions`` (m), shape (k, N): a central difference over 2e-3 element lengths
    (one-sided at the ends), inside an element its exact strain, at a node the mean of both sides."""
    if not len(positions):
        return sp.csr_matrix((0, basis.N))
    delta = 1e-3 * h_e
    lo = np.clip(positions - delta, 0.0, length)
    hi = np.clip(positions + delta, 0.0, length)
    return sp.csr_matrix((basis.probes(hi[None, :]) - basis.probes(lo[None, :])).multiply(1.0 / (hi - lo)[:, None]))


def end_vector(model: BarModel) -> NDArray[np.float64]:
    """Unit load at the struck end, shape (d,)."""
    e0 = np.zeros(model.mass.shape[0])
    e0[model.end] = 1.0
    return e0


def banded_solver(matrix: sp.spmatrix) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """x = A^-1 b for a symmetric positive definite bar matrix, by a banded Cholesky factor.

    The bar's DOFs (P2: the vertices first, then the element midpoints) are renumbered by
    reverse Cuthill-McKee, which makes a 1-D mesh's matrix banded (half-bandwidth 1 for P1,
    2 for P2); the factor then costs O(n) to apply, with no fill-in.

    Parameters
    ----------
    matrix : scipy.sparse matrix, shape (d, d)
        Symmetric positive definite.

    Returns
    -------
    callable
        b (shape (d,)) -> A^-1 b (shape (d,)).
    """
    csr = sp.csr_matrix(matrix)
    order = reverse_cuthill_mckee(csr, symmetric_mode=True)
    permuted = sp.csr_matrix(csr[order][:, order])
    rows, cols = permuted.nonzero()
    width = int(np.max(np.abs(rows - cols), initial=0))
    bands = np.zeros((width + 1, csr.shape[0]))
    lower = rows >= cols
    bands[rows[lower] - cols[lower], cols[lower]] = np.asarray(permuted[rows[lower], cols[lower]]).ravel()
    factor = cholesky_banded(bands, lower=True)
    inverse = np.empty_like(order)
    inverse[order] = np.arange(len(order))
    # LAPACK's back-substitution itself, which cho_solve_banded calls after its checks of the
    # arguments: the same numbers, without a few microseconds of checks at every step
    (pbtrs,) = get_lapack_funcs(("pbtrs",), (factor,))

    def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
        x, info = pbtrs(factor, b[order], lower=1)
        if info != 0:
            raise ValueError(f"banded_solver: LAPACK pbtrs refused argument {-info}")
        return x[inverse]

    return solve


def row_blocks(*blocks: sp.spmatrix | None) -> tuple[sp.csr_matrix, list[slice | None]]:
    """Sparse matrices acting on one vector, stacked into one: a step's products in one call.

    Each row's sum runs over its columns in ascending order, as in the block's own product
    (CSR with sorted indices, and CSC, both accumulate a row that way), so every product is the
    same number to the last bit (``tests/test_fem1d.py``); the step pays scipy's dispatch once
    instead of once per block.

    Parameters
    ----------
    *blocks : sparse matrix, shape (k_i, d), or None
        The blocks, all on vectors of length d; None: a product not taken.

    Returns
    -------
    stacked : scipy.sparse.csr_matrix, shape (sum k_i, d)
    rows : list of slice or None
        Each block's rows in ``stacked @ x`` (None for a None block).
    """
    present = [block for block in blocks if block is not None]
    stacked = sp.csr_matrix(sp.vstack(present, format="csr"))
    stacked.sort_indices()
    rows: list[slice | None] = []
    start = 0
    for block in blocks:
        if block is None:
            rows.append(None)
            continue
        rows.append(slice(start, start + block.shape[0]))
        start += block.shape[0]
    return stacked, rows
