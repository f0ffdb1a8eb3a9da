"""Tables of the sensor film, built from stored runs, band files and curve files only.

- :func:`readings_frame`: what each reading of Table 2 is (its rod, whether it has the film,
  its contact law);
- :func:`film_table_frame`: Table 2 on one rod without and with the film, by every method,
  with the calibrated law, the film's prediction band and the model-form error;
- :func:`film_band_frame`: the prediction band of every case of the film readings;
- :func:`film_indentation_frame`: the continuum's indentation curves against the analytic laws.

Errors against the measurements follow the paper: |model - measured| / measured, in %.
"""

from __future__ import annotations

import json
import logging
import math
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.contact.laws import DEFAULT_LAW
from rodimpact.contact.stack import Stack
from rodimpact.present.tables import METHOD_ORDER, table2_frame
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.bands import CaseBand
from rodimpact.storage.curves import ContactCurve
from rodimpact.storage.provenance import file_sha256
from rodimpact.storage.runs import RunRecord
from rodimpact.storage.sidecar import provenance_record

__all__ = [
    "FILM_ROLES",
    "INDENTATION_COLUMNS",
    "film_band_frame",
    "film_indentation_frame",
    "film_table_frame",
    "reading_of",
    "readings_frame",
    "table2_panels",
    "write_provenance_with_files",
]

log = logging.getLogger(__name__)

#: The readings :func:`film_table_frame` compares, by role: the column suffix of each.
FILM_ROLES = ("no_film", "film", "film_calibrated", "no_film_calibrated", "sensor", "sensor_calibrated")


def reading_of(config: Mapping[str, Any]) -> dict[str, Any]:
    """What a run's case reads the experiment as: rod (mm), film (bool: a film or a stack of
    layers on the struck end), contact law, film modulus (a one-layer film's)."""
    contact = config.get("contact") or {}
    film = contact.get("film")
    material = (film or {}).get("material") or {}
    return {
        "rod_radius_mm": 1000.0 * float(config["rod"]["radius_m"]) if "radius_m" in config["rod"] else math.nan,
        "rod_length_mm": 1000.0 * float(config["rod"]["length_m"]),
        "film": Stack.of(contact) is not None,
        "contact_law": str(contact.get("law", DEFAULT_LAW)),
        "film_modulus_pa": float(material.get("youngs_modulus_pa", math.nan)),
    }


def readings_frame(records: Sequence[RunRecord]) -> pd.DataFrame:
    """One row per variant (in the order first met): ``variant, rod_radius_mm, rod_length_mm,
    film, contact_law, film_modulus_pa`` (NaN without a film).

    Raises
    ------
    ValueError
        Two runs of one variant read the experiment differently.
    """
    rows: dict[str, dict[str, Any]] = {}
    for rec in records:
        variant = rec.config.get("variant")
        reading = reading_of(rec.config)
        known = rows.setdefault(variant, {"variant": variant, **reading})
        if (known["film"], known["contact_law"]) != (reading["film"], reading["contact_law"]):
            raise ValueError(
                f"variant {variant!r}: its runs have different contact laws or films "
                f"({known['contact_law']}, film {known['film']} and {reading['contact_law']}, "
                f"film {reading['film']})"
            )
    columns = ["variant", "rod_radius_mm", "rod_length_mm", "film", "contact_law", "film_modulus_pa"]
    return pd.DataFrame(list(rows.values()), columns=columns)


def table2_panels(readings: pd.DataFrame, film_variants: Sequence[str] = ()) -> dict[str, list[str]]:
    """The panels of the Table 2 figure: each reading without a film and with the default law
    (one per rod), with the readings of ``film_variants`` on the same rod drawn on it.

    A reading that is neither (a calibrated law) is not drawn; nor is a film reading whose rod
    has no reading without the film (both are logged). With no such base reading at all, every
    reading is its own panel.
    """

    def rod(reading: Any) -> tuple[float, float]:
        return (round(float(reading.rod_radius_mm), 9), round(float(reading.rod_length_mm), 9))

    base = [r for r in readings.itertuples() if not r.film and r.contact_law == DEFAULT_LAW]
    if not base:
        return {v: [] for v in readings["variant"]}
    panels: dict[str, list[str]] = {r.variant: [] for r in base}
    home = {rod(r): r.variant for r in base}
    for reading in readings.itertuples():
        if reading.variant in panels:
            continue
        if reading.variant in film_variants and rod(reading) in home:
            panels[home[rod(reading)]].append(reading.variant)
        else:
            log.info(
                "the Table 2 figure does not draw the reading %r (%s law, film: %s)",
                reading.variant,
                reading.contact_law,
                reading.film,
            )
    return panels


def _error_pct(model: np.ndarray, measured: np.ndarray) -> np.ndarray:
    return np.abs(np.asarray(model, float) - measured) / measured * 100.0


def _row_of(case_id: str, variant: str, rows: Mapping[str, str]) -> str:
    """The Table 2 row of a case id: from its runs, else the id without ``-{variant}``."""
    if case_id in rows:
        return rows[case_id]
    suffix = f"-{variant}"
    return case_id[: -len(suffix)] if case_id.endswith(suffix) else case_id


def film_table_frame(
    records: Sequence[RunRecord],
    variants: Mapping[str, str],
    bands: Sequence[CaseBand] = (),
    *,
    calibrated_method: str = "sem",
    continuum_method: str = "fem_axi",
    radius_method: str = "sem",
    sensor_bands: Sequence[CaseBand] = (),
) -> pd.DataFrame:
    """Table 2 on one rod, without and with the film and the sensor as built, one row per Table 2 row (by mass).

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of the variants of ``variants``, any methods.
    variants : mapping
        Role (one of :data:`FILM_ROLES`) -> variant: ``no_film`` (Hertz), ``film`` (the
        thin-layer law; the continuum's bonded film), ``film_calibrated`` (the law calibrated
        by the continuum, with the film), ``no_film_calibrated`` (calibrated, no film),
        ``sensor`` (the sensor as built: the continuum's bonded layers; the stack's thin-layer
        law for the 1-D methods), ``sensor_calibrated`` (the law calibrated on the stack).
    bands : sequence of CaseBand
        The thin-layer law's prediction bands of the ``film`` variant's cases (``read_band``):
        ``thin_layer_band_min_us``, ``thin_layer_band_max_us``.
    calibrated_method, continuum_method : str
        ``model_form_pct`` = (``{calibrated}_film_calibrated_us`` - ``{continuum}_film_us``) /
        ``{continuum}_film_us`` x 100: the error of the quasi-static contact law;
        ``sensor_model_form_pct`` the same for the sensor.
    sensor_bands : sequence of CaseBand
        The bands from the continuum of the ``sensor_calibrated`` variant's cases:
        ``sensor_band_min_us``, ``sensor_band_max_us``.
    radius_method : str
        The method of the ``film`` run whose ``film_radius_to_thickness`` is reported.

    Returns
    -------
    DataFrame
        ``row, mass_g, diameter_mm, measured_us, published_fem_us, published_sem_us``, then
        ``{method}_{role}_us`` per role and method present, ``sensor_band_min_us,
        sensor_band_max_us, thin_layer_band_min_us, thin_layer_band_max_us``,
        ``published_fem_error_pct, published_sem_error_pct``, ``{method}_{role}_error_pct``,
        ``radius_to_thickness``, ``model_form_pct``, ``sensor_model_form_pct``.

    Raises
    ------
    ValueError
        A role is unknown, or a run belongs to none of the variants.
    """
    unknown = sorted(set(variants) - set(FILM_ROLES))
    if unknown:
        raise ValueError(f"variants: unknown roles {unknown}; known: {list(FILM_ROLES)}")
    role_of = {variant: role for role, variant in variants.items()}
    stray = sorted({r.case_id for r in records if r.config.get("variant") not in role_of})
    if stray:
        raise ValueError(f"runs: cases {stray} belong to none of the variants {sorted(role_of)}")
    base = [
        "row",
        "mass_g",
        "diameter_mm",
        "measured_us",
        "published_fem_us",
        "published_sem_us",
        "published_fem_error_pct",
        "published_sem_error_pct",
    ]
    parts, model_columns = [], []
    for role in FILM_ROLES:
        recs = [r for r in records if role in variants and r.config.get("variant") == variants[role]]
        if not recs:
            if role in variants:
                log.warning("no runs of the %s reading %r", role, variants[role])
            continue
        present = {r.method for r in recs}
        methods = [m for m in METHOD_ORDER if m in present] + sorted(present - set(METHOD_ORDER))
        part = table2_frame(recs).rename(columns={f"{m}_us": f"{m}_{role}_us" for m in methods})
        parts.append(part)
        model_columns += [f"{m}_{role}_us" for m in methods]
    if not parts:
        raise ValueError("records: no run of any of the variants")
    base = [c for c in base if all(c in part for part in parts)]  # the published results, where declared
    frame = pd.concat([part[base] for part in parts]).drop_duplicates("row").reset_index(drop=True)
    for part in parts:
        frame = frame.merge(part[["row", *(c for c in part.columns if c in model_columns)]], on="row", how="left")
    measured = frame["measured_us"].to_numpy(float)
    by_case = {r.case_id: r.config.get("row", r.case_id) for r in records}
    band_columns = []
    for prefix, role, case_bands in (("sensor", "sensor_calibrated", sensor_bands), ("thin_layer", "film", bands)):
        variant = variants.get(role, "")
        band_by_row = {_row_of(b.case_id, variant, by_case): b for b in case_bands}
        for end in ("min", "max"):
            frame[f"{prefix}_band_{end}_us"] = [
                getattr(band_by_row[r], f"band_{end}_us") if r in band_by_row else math.nan for r in frame["row"]
            ]
            band_columns.append(f"{prefix}_band_{end}_us")
    for column in model_columns:
        frame[column.removesuffix("_us") + "_error_pct"] = _error_pct(frame[column], measured)
    film_variant = variants.get("film", "")
    ratio = {
        rec.config.get("row"): float(rec.summary.get("film_radius_to_thickness", math.nan))
        for rec in records
        if rec.method == radius_method and rec.config.get("variant") == film_variant
    }
    frame["radius_to_thickness"] = [ratio.get(r, math.nan) for r in frame["row"]]
    for name, calibrated, continuum in (
        ("model_form_pct", f"{calibrated_method}_film_calibrated_us", f"{continuum_method}_film_us"),
        ("sensor_model_form_pct", f"{calibrated_method}_sensor_calibrated_us", f"{continuum_method}_sensor_us"),
    ):
        if calibrated in frame and continuum in frame:
            frame[name] = (frame[calibrated] - frame[continuum]) / frame[continuum] * 100.0
        else:
            frame[name] = math.nan
    head = base[:6] + model_columns + band_columns + base[6:]
    frame = frame[head + [c for c in frame.columns if c not in head]]
    return frame.sort_values("mass_g", kind="stable").reset_index(drop=True)


def film_band_frame(bands: Mapping[str, Sequence[CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """Every case of every band file: its band and whether the measurement lies inside it.

    Parameters
    ----------
    bands : mapping
        Variant -> the bands of its cases (``read_band``).
    cases : mapping
        Case id -> its resolved case (a case file's ``case``, or a run's config): row and mass.

    Returns
    -------
    DataFrame
        ``variant, row, case_id, mass_g, measured_us, nominal_us, band_min_us, band_max_us,
        measured_in_band`` (False when nothing was measured), and ``monotone`` where some band
        has its axes; by variant (in the order given), then mass.
    """
    rows = []
    for order, (variant, case_bands) in enumerate(bands.items()):
        for band in case_bands:
            case = cases.get(band.case_id) or {}
            mass = 1000.0 * float(case["impactor"]["mass_kg"]) if case else math.nan
            measured = band.measured_us
            rows.append(
                {
                    "variant": variant,
                    "row": case.get("row", _row_of(band.case_id, variant, {})),
                    "case_id": band.case_id,
                    "mass_g": mass,
                    "measured_us": measured,
                    "nominal_us": band.nominal_us,
                    "band_min_us": band.band_min_us,
                    "band_max_us": band.band_max_us,
                    "measured_in_band": bool(
                        math.isfinite(measured) and band.band_min_us <= measured <= band.band_max_us
                    ),
                    "monotone": band.monotone,
                    "_order": order,
                }
            )
    columns = [
        "variant",
        "row",
        "case_id",
        "mass_g",
        "measured_us",
        "nominal_us",
        "band_min_us",
        "band_max_us",
        "measured_in_band",
        "monotone",
    ]
    if all(band.monotone is None for group in bands.values() for band in group):
        columns.remove("monotone")
    frame = pd.DataFrame(rows, columns=[*columns, "_order"])
    frame = frame.sort_values(["_order", "mass_g"], kind="stable").reset_index(drop=True)
    return frame[columns]


#: The columns of :func:`film_indentation_frame`, in order.
INDENTATION_COLUMNS = (
    "case_id",
    "variant",
    "row",
    "point",
    "force_N",
    "continuum_approach_um",
    "law_approach_um",
    "law",
    "law_error_pct",
    "contact_radius_um",
    "film_thickness_um",
    "radius_to_film_thickness",
    "interpolation_error_half",
)


def film_indentation_frame(curves: Sequence[ContactCurve]) -> pd.DataFrame:
    """Every point of every indentation curve: the continuum's approach against the analytic law's.

    Returns
    -------
    DataFrame
        ``case_id, variant, row, point, force_N, continuum_approach_um, law_approach_um, law,
        law_error_pct`` (= (law - continuum) / continuum x 100), ``contact_radius_um``,
        ``film_thickness_um`` and ``radius_to_film_thickness`` (NaN without a film),
        ``interpolation_error_half`` (the curve's); by case, then force
        (:data:`INDENTATION_COLUMNS`; with no curve, these columns and no row).
    """
    rows = []
    for curve in curves:
        config, data = curve.config, curve.data
        stack = Stack.of(config.get("contact"))
        thickness = stack.thickness_m if stack is not None else math.nan
        approach, force = data["approach_m"], data["force_N"]
        law_approach = data.get("law_approach_m", np.full_like(force, math.nan))
        radius = data["contact_radius_m"]
        for i in range(len(force)):
            rows.append(
                {
                    "case_id": curve.case_id,
                    "variant": config.get("variant"),
                    "row": config.get("row"),
                    "point": i,
                    "force_N": float(force[i]),
                    "continuum_approach_um": 1e6 * float(approach[i]),
                    "law_approach_um": 1e6 * float(law_approach[i]),
                    "law": str(curve.summary.get("analytic_law", "")),
                    "law_error_pct": (float(law_approach[i]) - float(approach[i])) / float(approach[i]) * 100.0,
                    "contact_radius_um": 1e6 * float(radius[i]),
                    "film_thickness_um": 1e6 * thickness,
                    "radius_to_film_thickness": float(radius[i]) / thickness,
                    "interpolation_error_half": float(curve.summary.get("interpolation_error_half", math.nan)),
                }
            )
    # no curve (no calibrated case): the header alone
    frame = pd.DataFrame(rows, columns=list(INDENTATION_COLUMNS))
    return frame.sort_values(["case_id", "force_N"], kind="stable").reset_index(drop=True)


def write_provenance_with_files(
    path: str | Path,
    records: Sequence[RunRecord],
    artifacts: Iterable[str | Path],
    files: Mapping[str, Iterable[str | Path]],
) -> None:
    """A provenance sidecar (as :func:`rodimpact.storage.sidecar.write_provenance`) that also names
    the inputs that are not runs (band files, curve files, case files) with their SHA-256:
    ``input_files``, a list of ``{path, kind, sha256}`` (``files``: kind -> paths)."""
    artifacts = [str(a) for a in artifacts]
    record = provenance_record(records, artifacts)
    record["input_files"] = [
        {"path": str(p), "kind": kind, "sha256": file_sha256(p)} for kind, paths in files.items() for p in paths
    ]
    record["sha256"] = {a: file_sha256(a) for a in artifacts}
    with atomic_output(path) as tmp:
        tmp.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
