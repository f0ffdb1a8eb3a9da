"""A set read several ways (its variants, such as the paper's readings of the rod): each reading's
table of contact times and errors (the paper's Table 2 for the paper's set), and the errors per
reading and method.

Each table is declared here once, its columns beside its frame (:mod:`rodimpact.present.table`).
Errors against the measurements follow the paper (docs/paper-notes.md, "Table 2"): |model -
measured| / measured, in % (:func:`rodimpact.analysis.errors.relative_error_pct`, its absolute
value); the summary's mean signed error keeps the sign.
"""

from __future__ import annotations

import logging
import math
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.errors import relative_error_pct
from rodimpact.contact.laws import DEFAULT_LAW
from rodimpact.contact.stack import Stack
from rodimpact.present.columns import method_error, method_header, method_time, shared
from rodimpact.present.inputs import load_records
from rodimpact.present.table import Column, Table, TableArtifact, latex_escape, latex_title, panels
from rodimpact.present.words import reading_words
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.runs import RunRecord

__all__ = [
    "METHOD_ORDER",
    "by_variant",
    "make_readings_summary",
    "make_readings_table",
    "methods_of",
    "reading_of",
    "reading_table",
    "readings_frame",
    "readings_summary_table",
    "table2_frame",
    "table2_panels",
    "variants_summary",
]

log = logging.getLogger(__name__)

#: Column order of our methods in every table: the registry's.
METHOD_ORDER = tuple(METHODS)

#: The columns of a reading's table that hold the published results its cases declare.
PUBLISHED_COLUMNS = (
    "published_fem_us",
    "published_sem_us",
    "published_fem_error_pct",
    "published_sem_error_pct",
    "sem_vs_published_sem_pct",
)
#: A reading's columns other than the shared ones and those made per method.
_VERSUS_PAPER = Column("sem_vs_published_sem_pct", "SEM vs paper SEM", "%")
_ERROR = " error"


def methods_of(records: Sequence[RunRecord]) -> list[str]:
    """The methods of ``records``, the registry's first in its order, then any other by name."""
    present = {r.method for r in records}
    return [m for m in METHOD_ORDER if m in present] + sorted(present - set(METHOD_ORDER))


def _published(config: Mapping[str, Any], family: str, key: str) -> float:
    block = (config.get("published") or {}).get(family) or {}
    value = block.get(key)
    return math.nan if value is None else float(value)


def _paper_error_pct(model: float, measured: float | None) -> float:
    """|model - measured| / measured, %: the paper's error; NaN without a measurement."""
    if measured is None or not math.isfinite(model):
        return math.nan
    return abs(relative_error_pct(model, measured))


def table2_frame(records: Sequence[RunRecord]) -> pd.DataFrame:
    """One row per case (ball), sorted by mass: measured, published and our contact times.

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of the cases of one geometry variant, any methods (several per case).

    Returns
    -------
    DataFrame
        Columns ``case_id, row, variant, diameter_mm, mass_g, measured_us,
        published_fem_us, published_sem_us, published_fem_error_pct,
        published_sem_error_pct`` (the published columns only when a case declares
        ``published``), then ``{method}_us, {method}_error_pct`` for each method present, and
        ``sem_vs_published_sem_pct`` when ``sem`` is present (and published).
    """
    by_case: dict[str, dict[str, RunRecord]] = {}
    for rec in records:
        by_case.setdefault(rec.case_id, {})[rec.method] = rec
    methods = methods_of(records)
    rows = []
    for case_id, runs in by_case.items():
        config = next(iter(runs.values())).config
        measured = (config.get("measured") or {}).get("contact_time_us")
        row: dict[str, Any] = {
            "case_id": case_id,
            "row": config.get("row", case_id),
            "variant": config.get("variant"),
            "diameter_mm": 2000.0 * config["impactor"]["radius_m"],
            "mass_g": 1000.0 * config["impactor"]["mass_kg"],
            "measured_us": math.nan if measured is None else float(measured),
            "published_fem_us": _published(config, "fem", "contact_time_us"),
            "published_sem_us": _published(config, "sem", "contact_time_us"),
            "published_fem_error_pct": _published(config, "fem", "error_pct"),
            "published_sem_error_pct": _published(config, "sem", "error_pct"),
        }
        for method in methods:
            rec = runs.get(method)
            ours = math.nan if rec is None else 1e6 * float(rec.summary["contact_time_s"])
            row[f"{method}_us"] = ours
            row[f"{method}_error_pct"] = _paper_error_pct(ours, measured)
        if "sem" in methods:
            row["sem_vs_published_sem_pct"] = relative_error_pct(row["sem_us"], row["published_sem_us"])
        rows.append(row)
    frame = pd.DataFrame(rows)
    if not any(rec.config.get("published") for rec in records):  # no case declares the paper's results
        frame = frame.drop(columns=[c for c in frame.columns if "published" in c])
    return frame.sort_values("mass_g", kind="stable").reset_index(drop=True)


def _reading_columns(methods: Sequence[str]) -> tuple[Column, ...]:
    """The columns of :func:`table2_frame` (of a reading of these methods)."""
    return (
        *shared(["case_id", "row", "variant", "diameter_mm", "mass_g", "measured_us", *PUBLISHED_COLUMNS[:4]]),
        *(c for m in methods for c in (method_time(m), method_error(m))),
        _VERSUS_PAPER,
    )


def _setting(records: Sequence[RunRecord], frame: pd.DataFrame, variant: str, of: str) -> str:
    """The LaTeX caption's first sentence: what the balls are, how they strike, the reading."""
    config = records[0].config if records else {}
    if not config:
        return f"Contact time of the balls of {of}, rod reading \\texttt{{{latex_escape(variant)}}}."
    speed = float(config["impactor"]["velocity_m_s"])
    ball = str(config["impactor"]["material"].get("name", "")).split("_")[0]
    rod = str(config["rod"]["material"].get("name", "")).split("_")[0]
    return (
        f"Contact time of the {len(frame)} {ball} balls of {of} striking the {rod} rod at {speed:g}~m/s; rod "
        f"reading \\texttt{{{latex_escape(variant)}}}: {latex_escape(reading_words(config))}."
    )


def reading_table(records: Sequence[RunRecord], variant: str, title: str = "Table 2", reference: str = "") -> Table:
    """One reading of a set: its contact times and errors (:func:`table2_frame`), for people in
    two panels, the contact times, then the errors against the measurements, with the published
    results where its cases declare them.

    Parameters
    ----------
    records : sequence of RunRecord
        The reading's runs.
    variant : str
        The reading (the LaTeX labels are ``tab:{title}-{variant}-times`` and ``-errors``, the
        title's letters and digits in lower case, ``-`` for ``_``).
    title, reference : str
        The set in captions (e.g. ``Table 2``), and the work its measurements come from.
    """
    frame = table2_frame(records)
    methods = [m for m in METHOD_ORDER if f"{m}_us" in frame.columns]  # the registry's, shown
    caption = (
        f"{title}, rod reading {variant}: {reading_words(records[0].config) if records else ''}. Contact times in "
        "µs; errors |model − measured| / measured in %."
    )
    table = Table(frame, _reading_columns(methods_of(records)), caption)
    slug = f"{re.sub(r'[^a-z0-9]', '', title.lower())}-{variant.replace('_', '-')}"
    published = [c for c in PUBLISHED_COLUMNS if c in frame.columns and frame[c].notna().any()]
    ours = ", ".join(f"{method_header(m)} ({METHODS[m].label})" for m in methods)
    ours_tex = latex_escape(ours).replace(". (", ".\\ (")  # an abbreviation's point ends no sentence
    of = latex_title(title) + (f" of {latex_escape(reference)}" if reference else "")
    printed = ", printed by the paper (its FEM and SEM)," if published else ","
    key = ["diameter_mm", "mass_g"]
    times = panels(
        table,
        f"Contact time: measured{', printed by the paper' if published else ''}, and ours",
        key,
        ["measured_us", *(c for c in published if c.endswith("_us")), *(f"{m}_us" for m in methods)],
        label=f"tab:{slug}-times",
        latex_caption=(
            f"{_setting(records, frame, variant, of)} Measured{printed} and computed by our methods: {ours_tex}."
        ),
    )
    errors = panels(
        table,
        "Error against the measurement, |model − measured| / measured",
        key,
        [
            *(c for c in published if c.endswith("_error_pct")),
            *(f"{m}_error_pct" for m in methods),
            *(c for c in published if c.endswith("_vs_published_sem_pct")),
        ],
        label=f"tab:{slug}-errors",
        drop=_ERROR,
        latex_caption=(
            f"Error of the contact times of Table~\\ref{{{times[0].label}}} against the "
            r"measured time $t_\mathrm{m}$, $|t - t_\mathrm{m}|/t_\mathrm{m}$ in per cent: "
            + (
                r"the paper's as printed, and ours. SEM vs paper SEM: our SEM's time over the "
                r"paper's, $t_\mathrm{SEM}/t_\mathrm{paper} - 1$, in per cent."
                if published
                else "ours."
            )
        ),
    )
    return table.showing([*times, *errors])


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


def by_variant(runs: Sequence[str | Path], variants: Sequence[str]) -> tuple[list[RunRecord], dict[str, pd.DataFrame]]:
    """The runs read, and :func:`table2_frame` of each variant that has runs."""
    records = load_records(runs)
    grouped = {v: [r for r in records if r.config.get("variant") == v] for v in variants}
    return records, {v: table2_frame(recs) for v, recs in grouped.items() if recs}


def variants_summary(
    frames: dict[str, pd.DataFrame], readings: Mapping[str, Mapping[str, Any]] | None = None
) -> pd.DataFrame:
    """Per variant and method: mean, max and mean signed error against the measurements,
    next to the paper's own errors for the same family of method (SEM or FEM) when a case
    declares them (else no ``paper_*`` columns).

    Parameters
    ----------
    frames : dict
        Variant name -> :func:`table2_frame` of that variant.
    readings : mapping, optional
        Variant -> ``{"film": bool, "contact_law": str}``: given, the columns ``film`` and
        ``contact_law`` follow ``variant``.
    """
    rows = []
    for variant, frame in frames.items():
        reading = (
            {}
            if readings is None
            else {"film": bool(readings[variant]["film"]), "contact_law": str(readings[variant]["contact_law"])}
        )
        measured = frame["measured_us"].to_numpy(float)
        for column in frame.columns:
            if not column.endswith("_us") or column.startswith(("measured", "published")):
                continue
            method = column[: -len("_us")]
            family = METHODS[method].family if method in METHODS else None
            signed = relative_error_pct(frame[column].to_numpy(float), measured)
            published = f"published_{family}_error_pct"
            paper = frame[published].to_numpy(float) if family and published in frame else np.array([np.nan])
            rows.append(
                {
                    "variant": variant,
                    **reading,
                    "method": method,
                    "n_cases": int(np.sum(np.isfinite(signed))),
                    "mean_error_pct": float(np.nanmean(np.abs(signed))),
                    "max_error_pct": float(np.nanmax(np.abs(signed))),
                    "mean_signed_error_pct": float(np.nanmean(signed)),
                    "paper_method": family or "",
                    "paper_mean_error_pct": float(np.nanmean(paper)),
                    "paper_max_error_pct": float(np.nanmax(paper)),
                }
            )
    summary = pd.DataFrame(rows)
    if not any("published_fem_us" in frame for frame in frames.values()):
        summary = summary.drop(columns=[c for c in summary.columns if c.startswith("paper_")])
    return summary


#: The summary's own columns.
_SUMMARY_COLUMNS = (
    Column("mean_error_pct", "Mean error", "%"),
    Column("max_error_pct", "Largest error", "%"),
    Column("mean_signed_error_pct", "Mean signed error", "%"),
    Column("paper_method", "Paper's method", fmt="", words={"sem": "the paper's SEM", "fem": "the paper's FEM"}),
    Column("paper_mean_error_pct", "Paper's mean error", "%"),
    Column("paper_max_error_pct", "Paper's largest error", "%"),
)


def readings_summary_table(frames: dict[str, pd.DataFrame], readings: Mapping[str, Mapping[str, Any]]) -> Table:
    """The errors per reading and method (:func:`variants_summary`), next to the paper's mean
    error of the same family."""
    frame = variants_summary(frames, readings)
    table = Table(
        frame,
        (*shared(["variant", "film", "contact_law", "method", "n_cases"]), *_SUMMARY_COLUMNS),
        "Error against the measured contact times, per rod geometry reading (with or without the sensor "
        "film, and its contact law) and method, next to the paper's own errors (%).",
    )
    return table.showing(
        panels(
            table,
            "Error against the measurements, per reading and method",
            ["variant", "contact_law", "method"],
            ["mean_error_pct", "max_error_pct", "mean_signed_error_pct", "paper_mean_error_pct"],
        )
    )


def make_readings_table(runs: Sequence[str | Path], variant: str, title: str, reference: str = "") -> TableArtifact:
    """One reading of a set with variants, from its runs (:func:`reading_table`; for the paper's
    set, ``title`` "Table 2": Table 2 for one reading of the rod).

    Raises
    ------
    ValueError
        A run is of another variant.
    """
    records = load_records(runs)
    wrong = sorted({r.case_id for r in records if r.config.get("variant") != variant})
    if wrong:
        raise ValueError(f"runs: cases {wrong} do not belong to variant {variant!r}")
    table = reading_table(records, variant, title, reference)
    log.info("%s (%s): %d rows from %d runs", title, variant, len(table.frame), len(records))
    return TableArtifact(table, records)


def make_readings_summary(runs: Sequence[str | Path], variants: Sequence[str]) -> TableArtifact:
    """Per variant and method, the mean and max error against the measurements, from the runs
    (:func:`readings_summary_table`)."""
    records, frames = by_variant(runs, variants)
    readings = readings_frame(records).set_index("variant").to_dict("index")
    return TableArtifact(readings_summary_table(frames, readings), records)
