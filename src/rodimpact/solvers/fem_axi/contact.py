"""The contact of ``fem_axi``'s two bodies: candidate gaps, their Delassus operator and the LCP.

With both bodies' Newmark operators factorised, G = K_eff^-1 B^T (one column per candidate
gap) maps multipliers to displacements, and A = B_rod G_rod + B_imp G_imp (symmetric positive
definite, c x c) maps multipliers to the opening of the gaps. A step's free prediction has
the gaps g; the multipliers solve the linear complementarity problem

    lambda >= 0,   w = g + A lambda >= 0,   lambda . w = 0,

which has exactly one solution (A is positive definite), computed as non-negative least
squares on the Cholesky factor C of A (|C^T lambda + C^-1 g|^2 = lambda.A lambda + 2 g.lambda
+ const).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.linalg import cholesky, solve_triangular
from scipy.optimize import nnls

from rodimpact.solvers.fem_axi.axibody import AxiBody

__all__ = ["ContactOperator"]


@dataclass
class ContactOperator:
    """The candidate gaps of the two bodies, factorised for the step.

    Attributes
    ----------
    B_rod, B_imp : scipy.sparse.csr_matrix, shape (c, n_rod) and (c, n_imp)
        The closing of each gap from each body's free coordinates.
    gap0 : ndarray, shape (c,)
        Initial gaps, m.
    GT_rod, GT_imp : ndarray, shape (c, n_rod) and (c, n_imp)
        G^T, one row per candidate (C-ordered: a contact reads only its active rows).
    delassus : ndarray, shape (c, c)
        A = B G, m per (N per radian).
    """

    B_rod: sp.csr_matrix
    B_imp: sp.csr_matrix
    gap0: NDArray[np.float64]
    GT_rod: NDArray[np.float64]
    GT_imp: NDArray[np.float64]
    delassus: NDArray[np.float64]
    _Bt: tuple[sp.csr_matrix, sp.csr_matrix] = field(init=False, repr=False)
    _chol: NDArray[np.float64] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._Bt = (sp.csr_matrix(self.B_rod.T), sp.csr_matrix(self.B_imp.T))
        self._chol = cholesky(self.delassus, lower=True)

    @classmethod
    def of(
        cls, rod: AxiBody, impactor: AxiBody, B_rod: sp.spmatrix, B_imp: sp.spmatrix, gap0: NDArray[np.float64]
    ) -> ContactOperator:
        """G and A for bodies factorised for their step (one solve with c right-hand sides each)."""
        B_rod, B_imp = sp.csr_matrix(B_rod), sp.csr_matrix(B_imp)
        GT_rod = np.ascontiguousarray(rod.solve(np.asfortranarray(B_rod.T.toarray())).T)
        GT_imp = np.ascontiguousarray(impactor.solve(np.asfortranarray(B_imp.T.toarray())).T)
        delassus = B_rod @ GT_rod.T + B_imp @ GT_imp.T
        return cls(B_rod, B_imp, np.asarray(gap0, dtype=float), GT_rod, GT_imp, 0.5 * (delassus + delassus.T))

    def gaps(self, q_rod: NDArray[np.float64], q_imp: NDArray[np.float64]) -> NDArray[np.float64]:
        """The gaps of displacements of both bodies, m, shape (c,)."""
        return self.gap0 + self.B_rod @ q_rod + self.B_imp @ q_imp

    def multipliers(self, gap: NDArray[np.float64]) -> NDArray[np.float64]:
        """The LCP's solution for the free gaps ``gap`` (m), N per radian, shape (c,)."""
        lam, _ = nnls(self._chol.T, -solve_triangular(self._chol, gap, lower=True), maxiter=50 * len(gap))
        return lam

    def corrections(
        self, lam: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """G lambda and the loads B^T lambda of the rod and of the impactor (multipliers ``lam``,
        nonzero on at least one candidate)."""
        nonzero = np.flatnonzero(lam)
        lo, hi = nonzero[0], nonzero[-1] + 1
        return (lam[lo:hi] @ self.GT_rod[lo:hi], lam[lo:hi] @ self.GT_imp[lo:hi], self._Bt[0] @ lam, self._Bt[1] @ lam)
