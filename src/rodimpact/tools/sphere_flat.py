"""The continuum's elastic-plastic sphere on a rigid flat against the published finite-element fits.

A hemisphere of an elastic-perfectly-plastic steel (E = 200 GPa, nu = 0.32, S_y = 0.9115 GPa,
R = 1 mm; the rigid back of ``fem_axi``'s ``cap`` is the hemisphere's base) is pressed on a
rod 1000 times stiffer (a rigid flat, to 1e-3 of E') by :func:`~rodimpact.solvers.fem_axi.
indentation.static_indentation`, along a geometric path of interferences (each 5 % above the
last) to omega* = 24, on three meshes (8, 12 and 18 elements across the estimated contact
radius: a constant ratio 1.5). At omega* = 1, 1.9, 4, 8, 16 and 24 the force over P_c is written
beside Jackson and Green's (2005) and Kogut and Etsion's (2002) fits
(:mod:`rodimpact.contact.sphere_flat`), with the grid convergence index of the finest mesh
(:func:`rodimpact.analysis.convergence.numerical_uncertainty`) and the change on the coarsest
mesh when every increment is halved (2.5 %).

``python -m rodimpact.tools.sphere_flat --out results/verification`` (``make sphere-flat``)
writes ``sphere_flat.csv`` and ``sphere_flat.{pdf,png}``; about 11 minutes on the machine
``docs/setup.md`` names (``--figure-only`` redraws the figure from the CSV).
"""

from __future__ import annotations

import argparse
import logging
import math
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from rodimpact.analysis.convergence import numerical_uncertainty
from rodimpact.contact.sphere_flat import (
    critical_force,
    jackson_green_critical_interference,
    jackson_green_force,
    kogut_etsion_critical_interference,
    kogut_etsion_force,
)
from rodimpact.model.materials import Material
from rodimpact.solvers.fem_axi.indentation import static_indentation
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.sidecar import write_provenance

__all__ = ["LEVELS", "RATIOS", "sphere_flat_problem", "sphere_flat_path", "sphere_flat_study", "main"]

log = logging.getLogger(__name__)

#: Elements across the estimated contact radius of the three meshes (constant ratio 1.5).
LEVELS = (8, 12, 18)
#: The interferences reported, over Jackson and Green's omega_c.
RATIOS = (1.0, 1.9, 4.0, 8.0, 16.0, 24.0)
#: The sphere: a bearing steel as in Jackson and Green's and Kogut and Etsion's studies.
SPHERE = Material(200e9, 0.32, 7850.0, name="elastic-perfectly-plastic steel", yield_stress_pa=0.9115e9)
RADIUS_M = 1e-3
#: The flat: the same steel, elastic and 1000 times stiffer.
STIFFNESS_RATIO = 1000.0
#: Each interference of the path over the last.
GROWTH = 1.05


def contact_modulus() -> float:
    """E' of the sphere on the flat, Pa."""
    one = (1.0 - SPHERE.poisson_ratio**2) / SPHERE.youngs_modulus_pa
    return 1.0 / (one * (1.0 + 1.0 / STIFFNESS_RATIO))


def critical_interference() -> float:
    """Jackson and Green's omega_c of the sphere, m."""
    return jackson_green_critical_interference(
        RADIUS_M, contact_modulus(), SPHERE.yield_stress_pa, SPHERE.poisson_ratio
    )


def sphere_flat_problem(largest_ratio: float) -> AxiImpact:
    """The hemisphere and the flat, with an impact whose Hertz approach is the path's largest
    interference (it sizes the mesh: the continuum's contact radius estimate)."""
    flat = Material(SPHERE.youngs_modulus_pa * STIFFNESS_RATIO, SPHERE.poisson_ratio, 7850.0, name="flat")
    k = 4.0 / 3.0 * contact_modulus() * math.sqrt(RADIUS_M)
    largest = largest_ratio * critical_interference()
    mass = 0.01
    velocity = math.sqrt(4.0 * k * largest**2.5 / (5.0 * mass))
    return AxiImpact(
        mass_kg=mass,
        velocity_m_s=velocity,
        sphere_radius_m=RADIUS_M,
        impactor_material=SPHERE,
        body="cap",
        rod_radius_m=20 * RADIUS_M,
        rod_length_m=40 * RADIUS_M,
        rod_material=flat,
        far_end="fixed",
    )


def sphere_flat_path(ratios: Sequence[float], growth: float) -> np.ndarray:
    """Interferences over omega_c from 0.5 to the largest ratio, each at most ``growth`` times the
    last, the reported ``ratios`` among them."""
    top = max(ratios)
    steps = math.ceil(math.log(top / 0.5) / math.log(growth))
    return np.unique(np.concatenate([np.geomspace(0.5, top, steps + 1), np.asarray(ratios, float)]))


def _forces(elements_across: int, growth: float) -> dict[float, float]:
    """P / P_c at each reported ratio on one mesh and path."""
    omega_c = critical_interference()
    p_c = critical_force(RADIUS_M, contact_modulus(), omega_c)
    path = sphere_flat_path(RATIOS, growth)
    options = FEMAxiOptions(
        elements_across=elements_across, contact_extent=2.5, plastic_extent=3.0, continuum_diameters=None
    )
    result = static_indentation(sphere_flat_problem(max(RATIOS)), path * omega_c, options)
    if not result.success:
        raise RuntimeError(f"sphere on a flat, {elements_across} elements across: {result.message}")
    log.info("%d elements across: %d Newton iterations", elements_across, result.newton_iterations)
    return {ratio: float(result.force_N[np.argmin(np.abs(path - ratio))] / p_c) for ratio in RATIOS}


def sphere_flat_study(levels: Sequence[int] = LEVELS) -> pd.DataFrame:
    """One row per reported ratio: the finite-element P / P_c on each mesh, its uncertainty, the fits.

    Columns: ``ratio`` (omega / omega_c, Jackson and Green's), ``fe_level{k}`` (P / P_c on mesh k),
    ``fe`` (the finest), ``gci`` (its uncertainty, a fraction), ``fe_half_increment`` (the
    coarsest mesh with every increment halved), ``jackson_green``, ``kogut_etsion`` (their
    P / P_c at the same interference, each over its own omega_c and P_c expressed in
    Jackson and Green's), ``diff_jackson_green_pct``, ``diff_kogut_etsion_pct`` (the finest
    against each, %) and ``fits_diff_pct`` (the two fits against each other, %).
    """
    if len(levels) != 3:
        raise ValueError(f"levels: three meshes are needed for a grid convergence index, got {len(levels)}")
    ratio = levels[1] / levels[0]
    if not math.isclose(levels[2] / levels[1], ratio, rel_tol=1e-9):
        raise ValueError(f"levels: the refinement ratio must be constant, got {levels}")
    runs = [_forces(level, GROWTH) for level in levels]
    halved = _forces(levels[0], math.sqrt(GROWTH))
    e_prime, nu, s_y = contact_modulus(), SPHERE.poisson_ratio, SPHERE.yield_stress_pa
    omega_jg = critical_interference()
    omega_ke = kogut_etsion_critical_interference(RADIUS_M, e_prime, s_y, nu)
    p_jg = critical_force(RADIUS_M, e_prime, omega_jg)
    p_ke = critical_force(RADIUS_M, e_prime, omega_ke)
    rows = []
    for w in RATIOS:
        coarse, medium, fine = (run[w] for run in runs)
        uncertainty = numerical_uncertainty(fine, medium, coarse, ratio)
        jg = float(jackson_green_force(w, RADIUS_M, e_prime, s_y, nu))
        ke = float(kogut_etsion_force(w * omega_jg / omega_ke)) * p_ke / p_jg
        rows.append(
            {
                "ratio": w,
                **{f"fe_level{k}": run[w] for k, run in enumerate(runs)},
                "fe": fine,
                "gci": uncertainty.value,
                "fe_half_increment": halved[w],
                "jackson_green": jg,
                "kogut_etsion": ke,
                "diff_jackson_green_pct": 100.0 * (fine / jg - 1.0),
                "diff_kogut_etsion_pct": 100.0 * (fine / ke - 1.0),
                "fits_diff_pct": 100.0 * (jg / ke - 1.0),
            }
        )
    return pd.DataFrame(rows)


def sphere_flat_figure(frame: pd.DataFrame, stem: Path, levels: Sequence[int] = LEVELS) -> None:
    """Three panels, written to ``stem``.pdf and ``stem``.png: the force against the interference
    (the finest mesh with its uncertainty, both fits, Hertz); the finite element's difference
    from each fit; and the mesh convergence, each mesh's force against the finest's."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    e_prime, nu, s_y = contact_modulus(), SPHERE.poisson_ratio, SPHERE.yield_stress_pa
    omega_jg = critical_interference()
    omega_ke = kogut_etsion_critical_interference(RADIUS_M, e_prime, s_y, nu)
    p_ke_over_jg = critical_force(RADIUS_M, e_prime, omega_ke) / critical_force(RADIUS_M, e_prime, omega_jg)
    w = np.geomspace(0.5, frame["ratio"].max() * 1.1, 200)
    fig, (top, middle, bottom) = plt.subplots(3, 1, figsize=(5.5, 8.0), height_ratios=(2, 1.2, 1.2))
    top.loglog(w, w**1.5, ":", color="0.5", label="Hertz")
    top.loglog(w, jackson_green_force(w, RADIUS_M, e_prime, s_y, nu), "-", label="Jackson and Green (2005)")
    ke_w = w[w * omega_jg / omega_ke >= 1.0]
    top.loglog(
        ke_w, kogut_etsion_force(ke_w * omega_jg / omega_ke) * p_ke_over_jg, "--", label="Kogut and Etsion (2002)"
    )
    top.errorbar(
        frame["ratio"],
        frame["fe"],
        yerr=frame["gci"] * frame["fe"],
        fmt="o",
        color="k",
        ms=4,
        capsize=3,
        label="Axisymmetric FE, J2 (finest mesh)",
    )
    top.set_ylim(0.3, 1.5 * float(frame["fe"].max()))
    top.set_xlabel(r"Interference over critical interference, $\omega/\omega_c$")
    top.set_ylabel(r"Force over critical force, $P/P_c$")
    top.legend(fontsize=8, loc="upper left")
    for column, label, marker in (
        ("diff_jackson_green_pct", "against Jackson and Green", "o"),
        ("diff_kogut_etsion_pct", "against Kogut and Etsion", "s"),
    ):
        middle.errorbar(
            frame["ratio"], frame[column], yerr=100.0 * frame["gci"], fmt=marker, ms=4, capsize=3, label=label
        )
    middle.plot(frame["ratio"], frame["fits_diff_pct"], "x", color="0.4", label="the two fits' own difference")
    middle.axhline(0.0, color="0.5", lw=0.8)
    middle.set_xscale("log")
    middle.set_xlabel(r"Interference over critical interference, $\omega/\omega_c$")
    middle.set_ylabel("Difference, %")
    middle.legend(fontsize=7, ncol=1)
    for _, row in frame.iterrows():
        values = np.array([row[f"fe_level{k}"] for k in range(len(levels))])
        bottom.plot(levels, 100.0 * (values / row["fe"] - 1.0), "o-", ms=4, label=f"{row['ratio']:g}")
    bottom.axhline(0.0, color="0.5", lw=0.8)
    bottom.set_xscale("log")
    bottom.set_xticks(list(levels), [str(level) for level in levels])
    bottom.minorticks_off()
    bottom.set_xlabel("Elements across the estimated contact radius")
    bottom.set_ylabel("Force against finest mesh, %")
    bottom.legend(title=r"$\omega/\omega_c$", fontsize=7, title_fontsize=7, ncol=3)
    fig.tight_layout()
    for suffix in (".pdf", ".png"):
        fig.savefig(stem.with_suffix(suffix), dpi=150)
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the study and write ``sphere_flat.csv`` and the figure under ``--out``."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("results/verification"))
    parser.add_argument("--levels", type=int, nargs=3, default=list(LEVELS))
    parser.add_argument("--figure-only", action="store_true", help="draw the figure from an existing sphere_flat.csv")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    logging.getLogger("skfem").setLevel(logging.WARNING)
    written = [args.out / f"sphere_flat.{ext}" for ext in ("csv", "pdf", "png")]
    if args.figure_only:
        sphere_flat_figure(pd.read_csv(args.out / "sphere_flat.csv"), args.out / "sphere_flat", args.levels)
        write_provenance(args.out / "sphere_flat.provenance.json", [], written)
        return 0
    frame = sphere_flat_study(args.levels)
    args.out.mkdir(parents=True, exist_ok=True)
    with atomic_output(args.out / "sphere_flat.csv") as tmp:
        frame.to_csv(tmp, index=False, float_format="%.6g")
    sphere_flat_figure(frame, args.out / "sphere_flat", args.levels)
    # what made them: the code version (the study's configuration is this module's constants)
    write_provenance(args.out / "sphere_flat.provenance.json", [], written)
    sys.stdout.write(frame.to_string(index=False, float_format=lambda x: f"{x:.4g}") + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
