"""The tables of the sensor film, from stored runs, band files and curve files only:

- :func:`film_table`: Table 2 on one rod without and with the film and the sensor as built, by
  every method, with the calibrated law, the prediction bands and the model-form error;
- :func:`film_band_table`: the prediction band of every case of the film readings;
- :func:`film_indentation_table`: the continuum's indentation curves against the analytic laws.

Each table is declared here once, its columns beside its frame (:mod:`rodimpact.present.table`).
Errors against the measurements follow the paper: |model - measured| / measured, in %.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.errors import relative_error_pct
from rodimpact.contact.stack import Stack
from rodimpact.present.columns import method_error, method_time, shared
from rodimpact.present.inputs import cases_in, load_records
from rodimpact.present.readings import METHOD_ORDER, table2_frame
from rodimpact.present.table import Column, Table, TableArtifact, panels
from rodimpact.storage.bands import CaseBand, read_band
from rodimpact.storage.curves import ContactCurve, read_contact_curve
from rodimpact.storage.runs import RunRecord

__all__ = [
    "FILM_ROLES",
    "INDENTATION_COLUMNS",
    "film_band_frame",
    "film_band_table",
    "film_indentation_frame",
    "film_indentation_table",
    "film_table",
    "film_table_frame",
    "make_film_band_table",
    "make_film_indentation_table",
    "make_film_table",
]

log = logging.getLogger(__name__)

#: The columns of the film's band table, in order (all of them shared).
_BAND = shared(
    [
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
)
#: The readings :func:`film_table_frame` compares, by role: the column suffix of each.
FILM_ROLES = ("no_film", "film", "film_calibrated", "no_film_calibrated", "sensor", "sensor_calibrated")
_ERROR = " error"


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
        frame[column.removesuffix("_us") + "_error_pct"] = np.abs(relative_error_pct(frame[column], measured))
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
            frame[name] = relative_error_pct(frame[calibrated], frame[continuum])
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
    columns = [column.name for column in _BAND]
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


#: The film table's own columns (its bands, the contact radius, the model-form errors).
_FILM_COLUMNS = (
    Column("sensor_band_min_us", "Sensor band min (continuum)", "µs"),
    Column("sensor_band_max_us", "Sensor band max (continuum)", "µs"),
    Column("thin_layer_band_min_us", "Thin-layer band min (approximation)", "µs"),
    Column("thin_layer_band_max_us", "Thin-layer band max (approximation)", "µs"),
    Column("radius_to_thickness", "Contact radius / film thickness"),
    Column("model_form_pct", "Model-form error", "%"),
    Column("sensor_model_form_pct", "Model-form error, sensor", "%"),
)

FILM_TABLE_CAPTION = (
    "Table 2 on the rod of the text, without the sensor, with the film alone and with the sensor as built "
    "(electrodes, film and bond line, each from its source): measured and published contact times, ours by "
    "every method (no film: Hertz; film and sensor: the layers bonded in the continuum, the thin-layer law "
    "for the 1-D methods, an approximation; calibrated: the law of the continuum's static indentation), "
    "the sensor's prediction band from the continuum (calibrated SEM over the stack's sourced ranges), the "
    "film's band with the thin-layer law (approximation), each model's |model - measured| / measured, the "
    "contact radius over the film thickness (thin-layer law, SEM), and the model-form error of the "
    "quasi-static contact: (calibrated SEM - continuum) / continuum, with the film and with the sensor."
)


def film_table(
    records: Sequence[RunRecord],
    variants: Mapping[str, str],
    bands: Sequence[CaseBand] = (),
    *,
    sensor_bands: Sequence[CaseBand] = (),
) -> Table:
    """Table 2 on one rod without and with the film and the sensor as built
    (:func:`film_table_frame`): for people, the times without the film, with the sensor as built
    and its band, with the film alone and its band, then the errors of each."""
    frame = film_table_frame(records, variants, bands, sensor_bands=sensor_bands)
    methods = [m for m in METHOD_ORDER] + sorted({r.method for r in records} - set(METHOD_ORDER))
    columns = (
        *shared(["row", "mass_g", "diameter_mm", "measured_us", "published_fem_us", "published_sem_us"]),
        *shared(["published_fem_error_pct", "published_sem_error_pct"]),
        *(c for m in methods for role in FILM_ROLES for c in (method_time(m, role), method_error(m, role))),
        *_FILM_COLUMNS,
    )
    table = Table(frame, columns, FILM_TABLE_CAPTION)

    def per(role: str, suffix: str) -> list[str]:
        return [f"{m}_{role}{suffix}" for m in METHOD_ORDER if f"{m}_{role}{suffix}" in frame.columns]

    key = ["mass_g"]
    views = [
        (
            "Contact time without the film",
            [
                "measured_us",
                "published_fem_us",
                "published_sem_us",
                *per("no_film", "_us"),
                *per("no_film_calibrated", "_us"),
            ],
            "",
        ),
        (
            "Contact time with the sensor as built, and its prediction band from the continuum",
            [
                "measured_us",
                *per("sensor", "_us"),
                *per("sensor_calibrated", "_us"),
                "sensor_band_min_us",
                "sensor_band_max_us",
            ],
            "",
        ),
        (
            "Contact time with the film alone (the thin-layer law is an approximation)",
            [
                "measured_us",
                *per("film", "_us"),
                *per("film_calibrated", "_us"),
                "thin_layer_band_min_us",
                "thin_layer_band_max_us",
            ],
            "",
        ),
        (
            "Error against the measurement without the film",
            [
                "published_fem_error_pct",
                "published_sem_error_pct",
                *per("no_film", "_error_pct"),
                *per("no_film_calibrated", "_error_pct"),
            ],
            _ERROR,
        ),
        (
            "Error against the measurement with the sensor as built, and the quasi-static contact's",
            [*per("sensor", "_error_pct"), *per("sensor_calibrated", "_error_pct"), "sensor_model_form_pct"],
            _ERROR,
        ),
        (
            "Error against the measurement with the film alone, and the quasi-static contact's",
            [
                *per("film", "_error_pct"),
                *per("film_calibrated", "_error_pct"),
                "model_form_pct",
                "radius_to_thickness",
            ],
            _ERROR,
        ),
    ]
    return table.showing(p for title, values, drop in views for p in panels(table, title, key, values, drop=drop))


def film_band_table(bands: Mapping[str, Sequence[CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> Table:
    """The film's prediction band of every case (:func:`film_band_frame`), a panel per reading."""
    frame = film_band_frame(bands, cases)
    monotone = (
        "Monotone: whether the time is monotone along each range (then the corners bound it)."
        if "monotone" in frame.columns
        else "That the time is monotone along each range, so that the corners bound it, is the table "
        "film_band_axes (make film-axes)."
    )
    table = Table(
        frame,
        _BAND,
        "The sensor film's prediction band per Table 2 row and film reading: the SEM's contact time at the "
        "film's nominal constants and its min and max over the corners of the box of their ranges (µs), and "
        f"whether the measurement lies inside. {monotone}",
    )
    return table.showing(
        panels(
            table,
            "The film's prediction band of the SEM's contact time",
            ["row"],
            ["measured_us", "nominal_us", "band_min_us", "band_max_us", "measured_in_band", "monotone"],
            by="variant",
        )
    )


#: The indentation table's own columns.
_INDENTATION = (
    Column("point", "Point", fmt=""),
    Column("force_N", "Force", "N", ".4g"),
    Column("continuum_approach_um", "Continuum approach", "µm", ".4f"),
    Column("law_approach_um", "Law approach", "µm", ".4f"),
    Column("law", "Law", fmt=""),
    Column("law_error_pct", "Law error", "%"),
    Column("contact_radius_um", "Contact radius", "µm", ".1f"),
    Column("film_thickness_um", "Film thickness", "µm", ".1f"),
    Column("radius_to_film_thickness", "Contact radius / film thickness"),
    Column("interpolation_error_half", "Interpolation error", fmt=".1e"),
)


def film_indentation_table(curves: Sequence[ContactCurve]) -> Table:
    """Every point of every indentation curve against its analytic law (:func:`film_indentation_frame`)."""
    table = Table(
        film_indentation_frame(curves),
        (*shared(["case_id", "variant", "row"]), *_INDENTATION),
        "The continuum's static indentation (the calibrated contact laws) against the analytic law at the "
        "same force (hertz_film with the film, hertz without): approaches (µm), the law's error "
        "(law − continuum) / continuum (%), the contact radius (µm) and its ratio to the film thickness, and "
        "the tabulated law's interpolation error (every other point).",
    )
    return table.showing(
        panels(
            table,
            "Static indentation: the continuum against the analytic law",
            ["row"],
            [
                "force_N",
                "continuum_approach_um",
                "law_approach_um",
                "law_error_pct",
                "contact_radius_um",
                "radius_to_film_thickness",
            ],
            by="variant",
        )
    )


def make_film_table(
    runs: Sequence[str | Path],
    variants: Mapping[str, str],
    band: str | Path,
    sensor_bands: Sequence[str | Path] = (),
) -> TableArtifact:
    """Table 2 on one rod without and with the film and the sensor as built (:func:`film_table`),
    from the runs and the band files.

    Raises
    ------
    ValueError
        ``band`` is not the band of the film reading.
    """
    records = load_records(runs)
    band_variant, bands = read_band(band)
    if band_variant != variants.get("film"):
        raise ValueError(f"{band}: the band of {band_variant!r}, not of the film reading {variants.get('film')!r}")
    sensor = [b for p in sensor_bands for b in read_band(p)[1]]
    table = film_table(records, variants, bands, sensor_bands=sensor)
    log.info("table 2 with the film: %d rows from %d runs", len(table.frame), len(records))
    return TableArtifact(table, records, {"band": [band], "sensor band": sensor_bands})


def make_film_band_table(bands: Sequence[str | Path], case_files: Sequence[str | Path]) -> TableArtifact:
    """Every case of every band file (:func:`film_band_table`); rows and masses from the case files."""
    table = film_band_table(dict(read_band(p) for p in bands), cases_in(case_files))
    frame = table.frame
    log.info("film bands: %d cases of %d readings, %d inside", len(frame), len(bands), frame["measured_in_band"].sum())
    return TableArtifact(table, (), {"band": bands, "case file": case_files})


def make_film_indentation_table(curves: Sequence[str | Path]) -> TableArtifact:
    """Every point of every indentation curve against its analytic law (:func:`film_indentation_table`)."""
    return TableArtifact(film_indentation_table([read_contact_curve(p) for p in curves]), (), {"contact curve": curves})
