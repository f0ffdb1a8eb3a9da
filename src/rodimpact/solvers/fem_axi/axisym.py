"""Axisymmetric linear elasticity (no torsion) in scikit-fem, per radian.

The body of revolution is meshed in the half-plane (r, z) with ``MeshTri`` (x[0] = r >= 0,
x[1] = z) and a vector basis ``Basis(mesh, ElementVector(ElementTriP1()))`` (or P2); the
displacement is (u_r, u_z). The strains are

    e_rr = du_r/dr,   e_zz = du_z/dz,   e_tt = u_r / r (hoop),   gamma_rz = du_r/dz + du_z/dr,

and every integral carries the weight r: the forms are *per radian*, the 3D quantity is
2 pi times the per-radian one (a total force is 2 pi times the sum of the nodal
reactions; a rigid body coupled to the rod carries m / (2 pi) in the per-radian equations).

On the axis, u_r = 0 must be imposed (:func:`axis_dofs`); u_z needs nothing there (the
weight r makes the axis a natural boundary). The hoop term u_r v_r / r is not polynomial on
elements with a single vertex on the axis, so the quadrature of the basis matters there; the
default of scikit-fem (order 2p) converges at the optimal rate. Exact integration of the
mass of a Pp basis needs ``Basis(mesh, elem, intorder=2 * p + 1)``.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from skfem import Basis, BilinearForm, ElementVector, FacetBasis, LinearForm, MeshTri, asm
from skfem.assembly.dofs import DofsView
from skfem.element import DiscreteField

__all__ = [
    "strain",
    "axisym_stiffness",
    "axisym_mass",
    "axisym_load",
    "axis_dofs",
    "component_dofs",
    "cross_section_mean_uz",
]

log = logging.getLogger(__name__)

Traction = Callable[[NDArray[np.float64], NDArray[np.float64]], Sequence[Any]]


def _check_basis(basis: Any) -> None:
    """Raise ValueError unless ``basis`` is a 2-component vector basis on a MeshTri in r >= 0."""
    if not isinstance(basis, Basis):
        raise ValueError(f"basis must be a skfem Basis, got {type(basis).__name__}")
    if not isinstance(basis.mesh, MeshTri):
        raise ValueError(f"basis must live on a MeshTri in the (r, z) half-plane, got {type(basis.mesh).__name__}")
    if not isinstance(basis.elem, ElementVector) or basis.elem.dim != 2:
        raise ValueError("basis must use ElementVector(...) of a triangle element (two components u_r, u_z)")
    r = basis.mesh.p[0]
    if r.min() < -1e-12 * max(float(np.ptp(r)), np.finfo(float).tiny):
        raise ValueError(f"basis: the mesh must lie in r >= 0, min r = {r.min():g} m")


def _lame(youngs_modulus_pa: float, poisson_ratio: float) -> tuple[float, float]:
    """Lamé's lambda and mu, Pa, with the arguments checked."""
    if not np.isfinite(youngs_modulus_pa) or youngs_modulus_pa <= 0.0:
        raise ValueError(f"youngs_modulus_pa must be positive, got {youngs_modulus_pa!r}")
    if not np.isfinite(poisson_ratio) or not -1.0 < poisson_ratio < 0.5:
        raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {poisson_ratio!r}")
    e, nu = float(youngs_modulus_pa), float(poisson_ratio)
    return e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))


def strain(u: Any, r: ArrayLike) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Axisymmetric strains of a displacement field (u_r, u_z).

    Parameters
    ----------
    u : skfem DiscreteField (or any object with ``value`` and ``grad``)
        The displacement at points: ``u.value`` shape (2, ...), m; ``u.grad`` shape
        (2, 2, ...), ``u.grad[i, j]`` = d u_i / d x_j (x_0 = r, x_1 = z), dimensionless.
        Inside a form this is the trial or test function; after a solve,
        ``basis.interpolate(x)``.
    r : array_like
        Radius at the same points, m, broadcastable to one component of ``u`` (in a form:
        ``w.x[0]``). Must be nonzero (quadrature points are interior to the elements).

    Returns
    -------
    eps_rr, eps_zz, eps_tt, gamma_rz : ndarray, shape of one component of ``u``
        du_r/dr, du_z/dz, u_r / r, du_r/dz + du_z/dr (engineering shear strain).
    """
    if isinstance(u, DiscreteField):
        value, grad = u.get(0), u.grad  # u.value is deprecated in scikit-fem 12
    else:
        value, grad = getattr(u, "value", None), getattr(u, "grad", None)
    if value is None or grad is None:
        raise ValueError("u must be a DiscreteField or have 'value' (2, ...) and 'grad' (2, 2, ...)")
    if np.shape(value)[:1] != (2,) or np.shape(grad)[:2] != (2, 2):
        raise ValueError(f"u must have two components: value shape {np.shape(value)}, grad shape {np.shape(grad)}")
    return grad[0, 0], grad[1, 1], value[0] / r, grad[0, 1] + grad[1, 0]


def axisym_stiffness(basis: Basis, youngs_modulus_pa: float, poisson_ratio: float) -> sp.csr_matrix:
    """Per-radian stiffness matrix of an isotropic linear elastic body of revolution.

    K_ij = integral of [lam tr e(phi_j) tr e(phi_i) + 2 mu (e_rr e_rr + e_zz e_zz + e_tt e_tt)
    + mu gamma_rz gamma_rz] r dr dz, so 0.5 u^T K u is the strain energy per radian, J.

    Parameters
    ----------
    basis : skfem.Basis
        ``Basis(MeshTri, ElementVector(ElementTriP1() or ElementTriP2()))`` in r >= 0, m.
    youngs_modulus_pa : float
        Young's modulus E > 0, Pa.
    poisson_ratio : float
        Poisson's ratio, -1 < nu < 0.5.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (basis.N, basis.N)
        N/m (per radian).
    """
    _check_basis(basis)
    lam, mu = _lame(youngs_modulus_pa, poisson_ratio)
    stiffness = _stiffness_matrix(basis, lam, mu)
    log.debug("axisymmetric stiffness: %d DOFs, %d nonzeros", basis.N, stiffness.nnz)
    return stiffness


def _stiffness_matrix(basis: Basis, lam: float, mu: float) -> sp.csr_matrix:
    """:func:`axisym_stiffness`'s matrix: what ``asm`` of its bilinear form gives, bit for bit
    (the same products and sums, in the same order, into the same COO layout), with each
    local function's strains computed once and a trial function's column of the element
    matrices at a time (scikit-fem calls the form once per pair of local functions)."""
    r = basis.default_parameters()["x"][0]  # w.x[0] of the form, shape (elements, points)
    dx = basis.dx
    test = np.array([strain(phi[0], r) for phi in basis.basis])  # (local, 4, elements, points)
    vrr, vzz, vtt, vrz = test[:, 0], test[:, 1], test[:, 2], test[:, 3]
    trace_v = vrr + vzz + vtt
    nb, nt = len(basis.basis), basis.nelems
    data = np.empty((nb, nb, nt))
    for j in range(nb):  # the trial function u = phi_j, every test function v = phi_i at once
        urr, uzz, utt, urz = test[j]
        values = (
            lam * (urr + uzz + utt) * trace_v + 2.0 * mu * (urr * vrr + uzz * vzz + utt * vtt) + mu * urz * vrz
        ) * r
        data[j] = np.sum(values * dx, axis=-1)
    dofs = basis.element_dofs  # (local, elements)
    rows = np.tile(dofs, (nb, 1)).ravel()  # entry (j, i, e): row dofs[i, e], column dofs[j, e]
    cols = np.repeat(dofs, nb, axis=0).ravel()
    matrix = sp.coo_matrix((data.ravel(), (rows, cols)), shape=(basis.N, basis.N))
    matrix.eliminate_zeros()
    return matrix.tocsr()


def axisym_mass(basis: Basis, density_kg_m3: float) -> sp.csr_matrix:
    """Per-radian consistent mass matrix, integral of rho (u_r v_r + u_z v_z) r dr dz.

    Parameters
    ----------
    basis : skfem.Basis
        As in :func:`axisym_stiffness`; exact for a Pp basis built with intorder >= 2p + 1.
    density_kg_m3 : float
        Density rho > 0, kg/m^3.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (basis.N, basis.N)
        kg (per radian): 0.5 v^T M v is the kinetic energy per radian, J.
    """
    _check_basis(basis)
    if not np.isfinite(density_kg_m3) or density_kg_m3 <= 0.0:
        raise ValueError(f"density_kg_m3 must be positive, got {density_kg_m3!r}")
    rho = float(density_kg_m3)

    @BilinearForm
    def form(u, v, w):
        return rho * (u[0] * v[0] + u[1] * v[1]) * w.x[0]

    return asm(form, basis).tocsr()


def _facets(basis: Basis, facets: Any) -> NDArray[np.int64]:
    """Facet indices from a boundary name, a predicate on facet midpoints or an index array."""
    mesh = basis.mesh
    if isinstance(facets, str):
        boundaries = mesh.boundaries or {}
        if facets not in boundaries:
            raise ValueError(f"facets: no boundary named {facets!r} (have {sorted(boundaries)})")
        idx = np.asarray(boundaries[facets])
    elif callable(facets):
        idx = mesh.facets_satisfying(facets)
    else:
        idx = np.asarray(facets)
        if idx.ndim != 1 or (idx.size and not np.issubdtype(idx.dtype, np.integer)):
            raise ValueError("facets must be a boundary name, a predicate or a 1D integer array")
        if idx.size and (idx.min() < 0 or idx.max() >= mesh.facets.shape[1]):
            raise ValueError(f"facets: indices out of range [0, {mesh.facets.shape[1]})")
    if idx.size == 0:
        raise ValueError("facets: the selection is empty")
    return idx.astype(np.int64)


def axisym_load(basis: Basis, traction: Traction, facets: Any, intorder: int | None = None) -> NDArray[np.float64]:
    """Per-radian consistent nodal loads of a surface traction, integral of t.v r ds.

    Parameters
    ----------
    basis : skfem.Basis
        As in :func:`axisym_stiffness`.
    traction : callable
        ``traction(r, z) -> (t_r, t_z)``, Pa; r and z are arrays of the facet quadrature
        points, m, and each component is an array broadcastable to their shape (or a scalar).
    facets : str, callable or ndarray of int
        A boundary name of the mesh, a predicate on facet midpoints ``x -> bool array``
        (x shape (2, n)), or facet indices.
    intorder : int, optional
        Quadrature order on the facets; default 2p + 1 for Pp elements (exact for a traction
        linear along the facet).

    Returns
    -------
    ndarray, shape (basis.N,)
        N per radian; 2 pi times the sum of the z components is the total axial force.
    """
    _check_basis(basis)
    if not callable(traction):
        raise ValueError("traction must be a callable (r, z) -> (t_r, t_z)")
    idx = _facets(basis, facets)
    if intorder is None:
        intorder = 2 * int(basis.elem.maxdeg) + 1
    fbasis = FacetBasis(basis.mesh, basis.elem, facets=idx, intorder=intorder)

    @LinearForm
    def form(v, w):
        r, z = w.x[0], w.x[1]
        t = traction(r, z)
        if len(t) != 2:
            raise ValueError("traction must return two components (t_r, t_z)")
        return (np.broadcast_to(t[0], r.shape) * v[0] + np.broadcast_to(t[1], r.shape) * v[1]) * r

    return np.asarray(asm(form, fbasis), dtype=float)


def axis_dofs(basis: Basis, tol: float = 1e-12) -> NDArray[np.int64]:
    """The u_r DOFs on the axis r = 0 (where u_r = 0 must be imposed).

    Parameters
    ----------
    basis : skfem.Basis
        As in :func:`axisym_stiffness`.
    tol : float
        A DOF is on the axis if its location has r <= tol times the radial extent of the mesh.

    Returns
    -------
    ndarray of int, shape (k,)
        Sorted DOF indices (vertex and, for P2, edge-midpoint DOFs).
    """
    _check_basis(basis)
    if not np.isfinite(tol) or tol < 0.0:
        raise ValueError(f"tol must be non-negative, got {tol!r}")
    r = basis.mesh.p[0]
    scale = max(float(np.ptp(r)), np.finfo(float).tiny)
    radial = basis.split_indices()[0]
    on_axis = np.abs(basis.doflocs[0, radial]) <= tol * scale
    return np.sort(radial[on_axis]).astype(np.int64)


def component_dofs(basis: Basis, component: int, dofs: Any = None) -> NDArray[np.int64]:
    """The u_r (component 0) or u_z (component 1) DOFs of a selection.

    Parameters
    ----------
    basis : skfem.Basis
        As in :func:`axisym_stiffness`.
    component : {0, 1}
        0 for u_r, 1 for u_z.
    dofs : DofsView, str, callable, array of int or None
        A ``basis.get_dofs(...)`` result; a boundary name or a facet predicate (passed to
        ``basis.get_dofs``); an array of DOF indices (filtered to the component); None for
        every DOF of the basis.

    Returns
    -------
    ndarray of int, shape (k,)
        Sorted DOF indices.
    """
    _check_basis(basis)
    if component not in (0, 1):
        raise ValueError(f"component must be 0 (u_r) or 1 (u_z), got {component!r}")
    comp = basis.split_indices()[component]
    if dofs is None:
        out = comp
    elif isinstance(dofs, DofsView):
        out = dofs.all(basis.elem.dofnames[component])
    elif isinstance(dofs, str) or callable(dofs):
        if isinstance(dofs, str) and dofs not in (basis.mesh.boundaries or {}):
            raise ValueError(f"dofs: no boundary named {dofs!r}")
        out = basis.get_dofs(dofs).all(basis.elem.dofnames[component])
    else:
        arr = np.asarray(dofs)
        if arr.ndim != 1 or (arr.size and not np.issubdtype(arr.dtype, np.integer)):
            raise ValueError("dofs must be a DofsView, a boundary name, a predicate, a 1D integer array or None")
        out = arr[np.isin(arr, comp)]
    return np.unique(np.asarray(out, dtype=np.int64))


def cross_section_mean_uz(basis: Basis, z: float, radius: float, n: int = 64) -> sp.csr_matrix:
    """Row that maps the DOFs to the area-weighted mean of u_z over a disc.

    mean = 2 pi int_0^R u_z(r, z) r dr / (pi R^2) = (2 / R^2) int_0^R u_z r dr, evaluated with
    an n-point Gauss-Legendre rule in r on [0, R] (exact for u_z polynomial of degree
    <= 2n - 2 in r along the section; across element boundaries it is a quadrature).

    Parameters
    ----------
    basis : skfem.Basis
        As in :func:`axisym_stiffness`.
    z : float
        Height of the section, m (inside the mesh).
    radius : float
        Radius R of the disc, m, 0 < R <= the largest r of the mesh.
    n : int
        Number of Gauss points (>= 1).

    Returns
    -------
    scipy.sparse.csr_matrix, shape (1, basis.N)
        The mean axial displacement, m, is ``row @ u``.
    """
    _check_basis(basis)
    p = basis.mesh.p
    if int(n) != n or n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    r_max = float(p[0].max())
    if not np.isfinite(radius) or radius <= 0.0 or radius > r_max * (1.0 + 1e-12):
        raise ValueError(f"radius must lie in (0, {r_max:g}] m, got {radius!r}")
    z_lo, z_hi = float(p[1].min()), float(p[1].max())
    if not np.isfinite(z) or not z_lo <= z <= z_hi:
        raise ValueError(f"z must lie in [{z_lo:g}, {z_hi:g}] m, got {z!r}")
    xi, wts = np.polynomial.legendre.leggauss(int(n))
    r = 0.5 * radius * (xi + 1.0)
    weights = 0.5 * radius * wts * r * 2.0 / radius**2
    points = np.vstack([r, np.full(int(n), float(z))])
    probes = sp.csr_matrix(basis.probes(points))  # rows: n values of u_r, then n of u_z
    row = sp.csr_matrix(weights[None, :]) @ probes[int(n) :]
    return sp.csr_matrix(row)
