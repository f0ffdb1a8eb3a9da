"""The far rod as a one-dimensional bar, joined to the continuum at a plane section.

Beyond a few diameters from the struck end the near field of the contact has decayed (Saint-
Venant) and the waves that run along the rod have wavelengths of the order of a t_c, far
longer than the rod's diameter, so they are one-dimensional: plane sections stay plane under
uniaxial stress. The rod is therefore a continuum over 0 <= z <= z_c and a bar of linear
(P1) elements over z_c <= z <= L. At the joint the axial displacement of every point of the
continuum's section z = z_c equals the bar's first node (one shared coordinate); the radial
displacement there stays free (the bar is in uniaxial stress, so its section may expand).
The joint is a kinematic constraint: the coupled model is the continuum model with those
DOFs tied, which stays symmetric and conserves the same energy.

The rule for where the continuum ends (:func:`continuum_length`): z_c = n 2a with n =
``continuum_diameters`` (default 5) for a rod of radius a, and a bar only on a rod at least
:data:`MIN_ROD_TO_CONTINUUM` times z_c long; otherwise the whole rod is a continuum. On a
shorter rod the waves cross the joint many times during a contact, each crossing adds the 3-D
dispersion the bar leaves out, and the bar saves little: on the 1 mm rods of 30.1 mm (Table 2)
a bar of 20 mm moved the heaviest ball's contact time by 0.16 % for 7 % of the run time.
A run with strain gauges (:mod:`.gauges`) extends the continuum to cover them: z_c is at least
the ``cover`` its gauges ask for (one diameter beyond the last gauge's far end), and a bar that
would be left shorter than :data:`MIN_BAR_DIAMETERS` diameters is none (the whole rod is then a
continuum); without gauges nothing changes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:  # the cost model reads this module: scipy only where the bar is built
    import scipy.sparse as sp

__all__ = ["BAR_ELEMENTS_PER_RADIUS", "MIN_BAR_DIAMETERS", "MIN_ROD_TO_CONTINUUM", "FarBar", "continuum_length"]

#: A bar only on a rod at least this many continuum lengths long (L >= 10 z_c).
MIN_ROD_TO_CONTINUUM = 10.0
#: Bar elements per rod radius a: P1 elements a/4 long (the continuum's coarse cells are a/2
#: long with P2 elements, the same spacing of nodes along the axis).
BAR_ELEMENTS_PER_RADIUS = 4
#: A continuum extended to cover gauges leaves a bar only when it is at least this many rod
#: diameters long.
MIN_BAR_DIAMETERS = 1.0


def continuum_length(radius_m: float, length_m: float, diameters: float | None, cover_m: float = 0.0) -> float | None:
    """Where the continuum ends and the bar begins, m, or None when the whole rod is a continuum.

    Parameters
    ----------
    radius_m, length_m : float
        The rod's radius a and length L, m.
    diameters : float or None
        The continuum's length in rod diameters; None: no bar.
    cover_m : float
        The continuum reaches at least this far from the struck end, m (the gauges',
        :func:`~.gauges.continuum_cover_m`); 0 (default): no such need.

    Returns
    -------
    float or None
        z_c = 2 a ``diameters`` when L >= :data:`MIN_ROD_TO_CONTINUUM` z_c, else None; then
        ``cover_m`` when it is further, or None when that leaves a bar shorter than
        :data:`MIN_BAR_DIAMETERS` diameters.
    """
    if diameters is None:
        return None
    z_c = 2.0 * radius_m * diameters
    if length_m < MIN_ROD_TO_CONTINUUM * z_c:
        return None
    if cover_m > z_c:
        if cover_m > length_m - MIN_BAR_DIAMETERS * 2.0 * radius_m:
            return None
        z_c = cover_m
    return z_c


@dataclass(frozen=True)
class FarBar:
    """The bar z_c <= z <= L of a rod of radius a, per radian, with its nodes.

    Attributes
    ----------
    start_m, length_m : float
        z_c and L, m.
    radius_m : float
        The rod's radius a, m.
    youngs_modulus_pa, density_kg_m3 : float
        The rod's material.
    fixed : bool
        The node z = L is held (a fixed far end).
    """

    start_m: float
    length_m: float
    radius_m: float
    youngs_modulus_pa: float
    density_kg_m3: float
    fixed: bool

    @property
    def elements(self) -> int:
        """Number of P1 elements: the bar's length over a / BAR_ELEMENTS_PER_RADIUS, rounded up."""
        return max(1, math.ceil((self.length_m - self.start_m) * BAR_ELEMENTS_PER_RADIUS / self.radius_m - 1e-9))

    @property
    def nodes(self) -> NDArray[np.float64]:
        """The nodes' heights z, m, shape (elements + 1,): node 0 is the joint."""
        return np.linspace(self.start_m, self.length_m, self.elements + 1)

    @property
    def coordinates(self) -> int:
        """Coordinates the bar adds beyond the joint's: its nodes 1.. (less the held far node)."""
        return self.elements - (1 if self.fixed else 0)

    def matrices(self) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """Per-radian stiffness (N/m) and consistent mass (kg) on the nodes, shape (e + 1, e + 1).

        EA / (2 pi ell) [[1, -1], [-1, 1]] and rho A ell / (2 pi) [[1/3, 1/6], [1/6, 1/3]] per
        element of length ell, A = pi a^2: the bar's share of the per-radian forms of the
        continuum (whose energies are 2 pi times the quadratic forms).
        """
        import scipy.sparse as sp

        e = self.elements
        ell = (self.length_m - self.start_m) / e
        area = math.pi * self.radius_m**2
        k = self.youngs_modulus_pa * area / (2.0 * math.pi * ell)
        m = self.density_kg_m3 * area * ell / (2.0 * math.pi)
        main_k = np.full(e + 1, 2.0 * k)
        main_k[[0, -1]] = k
        main_m = np.full(e + 1, 2.0 * m / 3.0)
        main_m[[0, -1]] = m / 3.0
        stiffness = sp.diags([np.full(e, -k), main_k, np.full(e, -k)], [-1, 0, 1], format="csr")
        mass = sp.diags([np.full(e, m / 6.0), main_m, np.full(e, m / 6.0)], [-1, 0, 1], format="csr")
        return stiffness, mass

    def interpolation_row(self, z: float) -> sp.csr_matrix:
        """Row that maps the bar's nodal displacements to u_z at height ``z`` (m), shape (1, e + 1)."""
        import scipy.sparse as sp

        z_nodes = self.nodes
        if not z_nodes[0] <= z <= z_nodes[-1]:
            raise ValueError(f"z must lie in the bar [{z_nodes[0]:g}, {z_nodes[-1]:g}] m, got {z!r}")
        j = min(int(np.searchsorted(z_nodes, z, side="right")) - 1, len(z_nodes) - 2)
        s = (z - z_nodes[j]) / (z_nodes[j + 1] - z_nodes[j])
        return sp.csr_matrix(([1.0 - s, s], ([0, 0], [j, j + 1])), shape=(1, len(z_nodes)))
