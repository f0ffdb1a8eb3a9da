"""One elastic body of the axisymmetric model, reduced to its free coordinates.

A body is a scikit-fem vector basis (u_r, u_z) on a MeshTri in the (r, z) half-plane with
per-radian mass and stiffness (:mod:`.axisym`), reduced by a sparse map ``T`` from free
coordinates q to the full DOF vector, u = T q:

* u_r = 0 on the axis (and wherever the body is clamped);
* a clamped set of DOFs (the rod's fixed far end) is removed;
* a rigid rear part (the impactor's back face): its nodes move only along the axis, all
  with one coordinate W, which carries the rear part's mass m_rigid / (2 pi) per radian;
* a far bar (the rod beyond z_c, :mod:`.farbar`): the u_z DOFs of the section z = z_c all
  move with the bar's first node, and the bar's other nodes are further coordinates.

Newmark's average-acceleration rule is factorised once: K_eff = K + (4 / h^2) M (LDL^T). The state
carries its images K q, M v, M a and the next step's right-hand side y = M (4/h^2 q + 4/h v +
a), so that a step costs one back-substitution and one product K q: with f the generalised
load of the step (B^T lambda of the contact), K_eff q_new = y + f gives 4/h^2 M q_new =
y + f - K q_new, the equation of motion M a_new = f - K q_new, and M v follows Newmark's
velocity update.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
import qdldl
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.linalg import spsolve_triangular
from skfem import Basis

from rodimpact.solvers.fem_axi.axisym import cross_section_mean_uz
from rodimpact.solvers.fem_axi.farbar import FarBar

__all__ = ["AxiBody", "spd_inverse_rows", "spd_solver"]


def _solver_of(factor: qdldl.Solver) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """b (shape (n,) or (n, k)) -> the solution of the same shape, by ``factor``'s back-substitutions."""

    def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
        b = np.asarray(b, dtype=float)
        if b.ndim == 1:
            return factor.solve(b)
        return np.column_stack([factor.solve(np.ascontiguousarray(column)) for column in b.T])

    return solve


def spd_solver(matrix: sp.spmatrix) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """Solver of a sparse symmetric positive definite system, factorised once (LDL^T).

    QDLDL's LDL^T factor in an approximate-minimum-degree order (the ``qdldl`` package):
    its back-substitutions, the bulk of a run, take about 0.6 of SuperLU's with a symmetric
    ordering on the same matrices (measured on both bodies of ``model``), which stores L and
    U where an LDL^T factor stores L once.

    Parameters
    ----------
    matrix : sparse matrix, shape (n, n)
        Symmetric positive definite (only its upper triangle is read).

    Returns
    -------
    callable
        b (shape (n,) or (n, k)) -> the solution of the same shape.
    """
    return _solver_of(qdldl.Solver(sp.triu(matrix, format="csc")))


def spd_inverse_rows(
    matrix: sp.spmatrix, rows: sp.spmatrix
) -> tuple[NDArray[np.float64], Callable[[NDArray[np.float64]], NDArray[np.float64]]]:
    """``rows matrix^-1 rows^T`` of a sparse SPD matrix and sparse rows, from one LDL^T factor.

    With the factor P (I + L) D (I + L)^T P^T of :func:`spd_solver`, the product is Y^T D^-1 Y
    for Y = (I + L)^-1 P^T rows^T. The columns of Y are nonzero only on the rows the rows'
    DOFs reach in the factor's elimination tree (their paths to its root: a few per cent of the
    DOFs for a surface's nodes), so the forward substitution runs on that block of L alone:
    the c back-substitutions of c full solves are not needed.

    Parameters
    ----------
    matrix : sparse matrix, shape (n, n)
        Symmetric positive definite (only its upper triangle is read).
    rows : sparse matrix, shape (c, n)

    Returns
    -------
    inverse_rows : ndarray, shape (c, c)
        ``rows matrix^-1 rows^T`` (symmetric).
    solve : callable
        The factor's solver, as :func:`spd_solver` returns it.

    Raises
    ------
    numpy.linalg.LinAlgError
        A pivot of the factor is not positive: the matrix is not positive definite.
    """
    factor = qdldl.Solver(sp.triu(matrix, format="csc"))
    lower, diagonal, order = factor.factors()
    if not np.all(diagonal > 0.0):
        raise np.linalg.LinAlgError(
            f"the matrix is not positive definite: {int(np.sum(~(diagonal > 0.0)))} pivots of its LDL^T not positive"
        )
    lower = sp.csc_matrix(lower)
    lower.sort_indices()
    n = lower.shape[0]
    # the elimination tree: the parent of column j is its first row below the diagonal
    parent = np.full(n, -1, dtype=np.int64)
    filled = np.diff(lower.indptr) > 0
    parent[filled] = lower.indices[lower.indptr[:-1][filled]]
    position = np.empty(n, dtype=np.int64)
    position[order] = np.arange(n)
    rows_p = sp.csc_matrix(rows)[:, order]  # columns in the factor's order
    reached = np.zeros(n, dtype=bool)
    for j in np.flatnonzero(np.diff(rows_p.indptr) > 0):
        while j != -1 and not reached[j]:
            reached[j] = True
            j = parent[j]
    reach = np.flatnonzero(reached)
    block = (sp.eye(len(reach), format="csr") + lower[reach][:, reach]).tocsr()
    Y = spsolve_triangular(block, rows_p[:, reach].T.toarray(), lower=True, unit_diagonal=True)
    Y = np.asarray(Y).reshape(len(reach), -1)
    inverse_rows = (Y / diagonal[reach][:, None]).T @ Y

    return 0.5 * (inverse_rows + inverse_rows.T), _solver_of(factor)


@dataclass
class AxiBody:
    """A reduced elastic body with its Newmark state.

    Parameters
    ----------
    basis : Basis
        Vector basis (u_r, u_z) on the body's mesh.
    stiffness, mass : sparse matrix, shape (N, N)
        Per-radian stiffness (N/m) and mass (kg) on the full DOFs.
    removed : array of int
        Full DOFs held at zero (axis u_r, clamped DOFs, the rigid part's u_r).
    rigid : array of int
        Full u_z DOFs of the rigid rear part (empty: none); they all move with one
        coordinate W, the last free coordinate.
    rigid_mass_kg : float
        Mass of the rigid rear part (total, not per radian).
    bar : FarBar, optional
        The rod beyond the mesh as a 1-D bar (:mod:`.farbar`), joined at ``joint``.
    joint : array of int
        Full u_z DOFs of the mesh's last section z = z_c; they all move with the bar's first node.
    """

    basis: Basis
    stiffness: sp.spmatrix
    mass: sp.spmatrix
    removed: NDArray[np.int64]
    rigid: NDArray[np.int64] = field(default_factory=lambda: np.empty(0, dtype=np.int64))
    rigid_mass_kg: float = 0.0

    bar: FarBar | None = None
    joint: NDArray[np.int64] = field(default_factory=lambda: np.empty(0, dtype=np.int64))

    def __post_init__(self) -> None:
        n = self.basis.N
        gone = np.union1d(np.union1d(self.removed, self.rigid), self.joint).astype(np.int64)
        free = np.setdiff1d(np.arange(n), gone)
        rows, cols = [free], [np.arange(len(free))]
        n_q = len(free)
        #: the rigid part's coordinate W (None: no rigid part)
        self.rigid_index: int | None = None
        if len(self.rigid):
            self.rigid_index = n_q
            rows.append(self.rigid)
            cols.append(np.full(len(self.rigid), n_q))
            n_q += 1
        #: the bar's nodes' coordinates: the joint's, then its own (less a held far node)
        self.bar_indices = np.empty(0, dtype=np.int64)
        if self.bar is not None:
            if not len(self.joint):
                raise ValueError("a far bar needs the joint's u_z DOFs (joint is empty)")
            rows.append(self.joint)
            cols.append(np.full(len(self.joint), n_q))
            self.bar_indices = np.concatenate([[n_q], n_q + 1 + np.arange(self.bar.coordinates)]).astype(np.int64)
            n_q += 1 + self.bar.coordinates
        self.n = n_q
        rows_all, cols_all = np.concatenate(rows), np.concatenate(cols)
        self.T = sp.csr_matrix((np.ones(len(rows_all)), (rows_all, cols_all)), shape=(n, n_q))
        K = self.T.T @ self.stiffness @ self.T
        M = self.T.T @ self.mass @ self.T
        if self.rigid_index is not None:
            if not self.rigid_mass_kg >= 0:
                raise ValueError(f"rigid_mass_kg must be >= 0, got {self.rigid_mass_kg!r}")
            M = M + sp.csr_matrix(
                ([self.rigid_mass_kg / (2 * math.pi)], ([self.rigid_index], [self.rigid_index])), shape=(n_q, n_q)
            )
        if self.bar is not None:
            nodes = self.bar.elements + 1
            kept = len(self.bar_indices)
            #: bar nodes -> coordinates, shape (n, nodes); a held far node has an empty column
            self._bar_map = sp.csr_matrix((np.ones(kept), (self.bar_indices, np.arange(kept))), shape=(n_q, nodes))
            K_bar, M_bar = self.bar.matrices()
            K = K + self._bar_map @ K_bar @ self._bar_map.T
            M = M + self._bar_map @ M_bar @ self._bar_map.T
        self.K = sp.csc_matrix(K)
        self.M = sp.csc_matrix(M)
        ones_z = self.uniform_axial(1.0)
        #: axial momentum p_z = 2 pi * momentum_weights @ v (uniform axial motion: the mass)
        self.momentum_weights = self.M @ ones_z
        self.total_mass_kg = 2 * math.pi * float(ones_z @ self.momentum_weights)

    # -- time stepping -----------------------------------------------------------------
    def factorise(self, h: float) -> None:
        """Factorise K_eff = K + (4/h^2) M for the step h (s)."""
        self.h = h
        self._K_rows = self.K.tocsr()
        self._M_rows = self.M.tocsr()
        self.solve = spd_solver(self.K + (4.0 / h**2) * self.M)

    def start(self, velocity_z: float) -> None:
        """At rest, or moving as a whole along the axis at ``velocity_z`` (m/s)."""
        self.q = np.zeros(self.n)
        self.v = self.uniform_axial(velocity_z)
        self.a = np.zeros(self.n)
        #: images of the state: K q, M a, M v; and the next prediction's right-hand side
        #: y = M (4/h^2 q + 4/h v + a)
        self.Kq, self.Ma = np.zeros(self.n), np.zeros(self.n)
        self.Mv = self.M @ self.v
        self.rhs = (4.0 / self.h) * self.Mv
        self._predicted = False

    def uniform_axial(self, value: float) -> NDArray[np.float64]:
        """Free coordinates of a uniform axial field (every u_z, and W, equal to ``value``)."""
        full = np.zeros(self.basis.N)
        full[self._uz_dofs()] = value
        q = np.zeros(self.n)
        keep = self.T.T @ full
        counts = np.asarray(self.T.sum(axis=0)).ravel()
        q[counts > 0] = keep[counts > 0] / counts[counts > 0]
        q[self.bar_indices] = value
        return q

    def _uz_dofs(self) -> NDArray[np.int64]:
        dofs = self.basis.nodal_dofs[1]
        if self.basis.facet_dofs.size:
            dofs = np.concatenate([dofs, self.basis.facet_dofs[1]])
        return dofs

    def predict(self) -> NDArray[np.float64]:
        """Displacement at the new step without loads: K_eff^-1 y, y = M (4/h^2 q + 4/h v + a)."""
        self._predicted = True
        return self.solve(self.rhs)

    def advance(self, q_new: NDArray[np.float64], load: NDArray[np.float64] | float | None = None) -> None:
        """Accept the new displacement; update the velocity, the acceleration and the images (Newmark).

        Parameters
        ----------
        q_new : ndarray, shape (n,)
            The new displacement, m.
        load : ndarray, shape (n,), or 0.0, or None
            The generalised load f of the step (N per radian), when ``q_new`` is
            K_eff^-1 (y + f) for the right-hand side y of the last :meth:`predict` (0.0: no
            load, q_new is the prediction): 4/h^2 M q_new = y + f - K q_new and M a_new = f -
            K q_new. None: q_new may be anything; M q_new is computed (one product more) and
            M a_new = 4/h^2 M q_new - y (Newmark's acceleration).
        """
        h = self.h
        Kq = self._K_rows @ q_new
        if load is None or not self._predicted:
            Mq4 = (4.0 / h**2) * (self._M_rows @ q_new)
            Ma = Mq4 - self.rhs
        else:
            Ma = load - Kq
            Mq4 = self.rhs + Ma
        # Newmark: v_new = v + h/2 (a + a_new) and a_new = 4/h^2 (q_new - q) - 4/h v - a, i.e.
        # v_new = 2/h (q_new - q) - v and a_new = 2/h (v_new - v) - a; M v likewise
        self.Mv += (0.5 * h) * (self.Ma + Ma)
        Mq4 += (4.0 / h) * self.Mv
        Mq4 += Ma
        v = q_new - self.q
        v *= 2.0 / h
        v -= self.v
        self.a = (2.0 / h) * (v - self.v) - self.a
        self.q, self.v, self.Kq, self.Ma, self.rhs = q_new, v, Kq, Ma, Mq4
        self._predicted = False

    @property
    def Mq(self) -> NDArray[np.float64]:
        """M q, from the next prediction's right-hand side."""
        h = self.h
        return (h * h / 4.0) * (self.rhs - (4.0 / h) * self.Mv - self.Ma)

    # -- measures ------------------------------------------------------------------------
    def kinetic_energy(self) -> float:
        """Total (3D) kinetic energy, J."""
        return math.pi * float(self.v @ self.Mv)

    def strain_energy(self) -> float:
        """Total (3D) strain energy, J."""
        return math.pi * float(self.q @ self.Kq)

    def reduce_rows(self, rows: sp.spmatrix) -> sp.csr_matrix:
        """Rows acting on full DOFs (e.g. probes), expressed on the free coordinates."""
        return sp.csr_matrix(rows @ self.T)

    def section_mean_uz_row(self, z: float, radius: float) -> sp.csr_matrix:
        """The cross-section mean of u_z at height ``z`` (m) on the free coordinates, shape (1, n):
        over the disc of ``radius`` (m) in the continuum, the bar's interpolated u_z beyond z_c."""
        if self.bar is not None and z >= self.bar.start_m:
            return sp.csr_matrix(self.bar.interpolation_row(z) @ self._bar_map.T)
        return self.reduce_rows(cross_section_mean_uz(self.basis, z, radius))

    def uz_probe_rows(self, points: NDArray[np.float64]) -> sp.csr_matrix:
        """u_z at points (shape (2, k)) on the free coordinates, shape (k, n)."""
        probes = sp.csr_matrix(self.basis.probes(points))
        k = points.shape[1]
        return self.reduce_rows(probes[k:])


def dofs_of(basis: Basis, facets: Sequence[int] | NDArray[np.int64], component: int) -> NDArray[np.int64]:
    """Full DOF indices of one component (0: u_r, 1: u_z) on the given boundary facets."""
    view = basis.get_dofs(np.asarray(facets, dtype=np.int64))
    key = f"u^{component + 1}"
    parts = [view.nodal.get(key, np.empty(0, dtype=np.int64)), view.facet.get(key, np.empty(0, dtype=np.int64))]
    return np.unique(np.concatenate(parts)).astype(np.int64)
