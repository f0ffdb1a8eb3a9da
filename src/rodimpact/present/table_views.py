"""Which columns of each table a reader sees, in which panels, under which captions.

Each function takes a table's frame (the CSV's columns, see :mod:`.tables` and
:mod:`.film_tables`) and returns its :class:`~rodimpact.present.table_formats.Panel` list, at
most :data:`~rodimpact.present.table_formats.MAX_COLUMNS` columns each: the report shows them
as HTML, and a reading's table (Table 2's) is also written as LaTeX from them. The CSV keeps every column.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import Any

import pandas as pd

from rodimpact.contact.laws import UnknownLaw, law_of
from rodimpact.present.columns import method_header
from rodimpact.present.table_formats import Panel, latex_escape, panels
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.runs import RunRecord

__all__ = [
    "comparison_views",
    "film_band_views",
    "film_indentation_views",
    "film_table_views",
    "orders_views",
    "latex_title",
    "reading_views",
    "reading_words",
    "stability_views",
    "sweep_views",
    "variants_views",
]

_ERROR = " error"


def _methods(frame: pd.DataFrame, pattern: str) -> list[str]:
    """The registry's methods (in its order) whose column ``pattern.format(m)`` the frame has."""
    return [m for m in METHODS if pattern.format(m) in frame.columns]


def reading_words(config: Mapping[str, Any]) -> str:
    """How a run's case reads the experiment, in words: its rod, its film, its contact law."""
    rod = config["rod"]
    words = [
        f"rod radius {1000 * float(rod['radius_m']):g} mm"
        if "radius_m" in rod
        else f"rod cross-section {float(rod['area_m2']):g} m²",
        f"length {1000 * float(rod['length_m']):g} mm",
    ]
    contact = config.get("contact") or {}
    film = contact.get("film")
    if film:
        name = str((film.get("material") or {}).get("name", "")).upper()
        words.append(f"with the {1e6 * float(film['thickness_m']):g} µm {name} film".replace("  ", " "))
    else:
        words.append("without the film")
    try:
        words.append(law_of(contact).reading)
    except UnknownLaw as unknown:  # a stored run of a law this code does not have
        words.append(f"contact law {unknown.name}")
    return ", ".join(words)


#: The columns of a reading's table that hold the published results its cases declare.
PUBLISHED_COLUMNS = (
    "published_fem_us",
    "published_sem_us",
    "published_fem_error_pct",
    "published_sem_error_pct",
    "sem_vs_published_sem_pct",
)


def latex_title(title: str) -> str:
    """A set's title in LaTeX: escaped, with a tie before a number (``Table 2`` -> ``Table~2``)."""
    return re.sub(r" (?=\d)", "~", latex_escape(title))


def reading_views(
    frame: pd.DataFrame, variant: str, records: Sequence[RunRecord], title: str, reference: str = ""
) -> list[Panel]:
    """One reading of a set: the contact times, then the errors against the measurements; the
    published results where its cases declare them.

    Parameters
    ----------
    frame : DataFrame
        :func:`rodimpact.present.tables.table2_frame` of the reading's runs.
    variant : str
        The reading (the LaTeX labels are ``tab:{title}-{variant}-times`` and ``-errors``, the
        title's letters and digits in lower case, ``-`` for ``_``).
    records : sequence of RunRecord
        The runs: the caption's materials, speed and reading.
    title, reference : str
        The set in captions (e.g. ``Table 2``), and the work its measurements come from.
    """
    config = records[0].config if records else {}
    slug = f"{re.sub(r'[^a-z0-9]', '', title.lower())}-{variant.replace('_', '-')}"
    published = [c for c in PUBLISHED_COLUMNS if c in frame.columns and frame[c].notna().any()]
    methods = _methods(frame, "{}_us")
    key = ["diameter_mm", "mass_g"]
    ours = ", ".join(f"{method_header(m)} ({METHODS[m].label})" for m in methods)
    ours_tex = latex_escape(ours).replace(". (", ".\\ (")  # an abbreviation's point ends no sentence
    of = latex_title(title) + (f" of {latex_escape(reference)}" if reference else "")
    if config:
        speed = float(config["impactor"]["velocity_m_s"])
        ball = str(config["impactor"]["material"].get("name", "")).split("_")[0]
        rod = str(config["rod"]["material"].get("name", "")).split("_")[0]
        setting = (
            f"Contact time of the {len(frame)} {ball} balls of {of} "
            f"striking the {rod} rod at "
            f"{speed:g}~m/s; rod reading \\texttt{{{latex_escape(variant)}}}: "
            f"{latex_escape(reading_words(config))}."
        )
    else:
        setting = f"Contact time of the balls of {of}, rod reading \\texttt{{{latex_escape(variant)}}}."
    printed = ", printed by the paper (its FEM and SEM)," if published else ","
    times = panels(
        frame,
        f"Contact time: measured{', printed by the paper' if published else ''}, and ours",
        key,
        ["measured_us", *(c for c in published if c.endswith("_us")), *(f"{m}_us" for m in methods)],
        label=f"tab:{slug}-times",
        latex_caption=(f"{setting} Measured{printed} and computed by our methods: {ours_tex}."),
    )
    errors = panels(
        frame,
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
    return [*times, *errors]


def variants_views(frame: pd.DataFrame) -> list[Panel]:
    """The errors per reading and method, next to the paper's mean error of the same family."""
    return panels(
        frame,
        "Error against the measurements, per reading and method",
        ["variant", "contact_law", "method"],
        ["mean_error_pct", "max_error_pct", "mean_signed_error_pct", "paper_mean_error_pct"],
    )


def comparison_views(frame: pd.DataFrame) -> list[Panel]:
    """Fig. 2's numbers: contact time and force maxima per method, and their differences."""
    maxima = sorted((c for c in frame.columns if c.startswith("max_")), key=lambda c: int(c.split("_")[1]))
    versus = [c for c in frame.columns if c.endswith("_pct") and "_vs_" in c and not c.startswith("paper_")]
    return panels(
        frame, "Fig. 2 in numbers: the first contact per method", ["method"], ["contact_time_us", *maxima, *versus]
    )


def film_table_views(frame: pd.DataFrame) -> list[Panel]:
    """Table 2 on the text's rod: times without and with the film, then the errors of each."""

    def per(role: str, suffix: str) -> list[str]:
        return [f"{m}_{role}{suffix}" for m in _methods(frame, "{}_" + role + suffix)]

    key = ["mass_g"]
    return [
        *panels(
            frame,
            "Contact time without the film",
            key,
            [
                "measured_us",
                "published_fem_us",
                "published_sem_us",
                *per("no_film", "_us"),
                *per("no_film_calibrated", "_us"),
            ],
        ),
        *panels(
            frame,
            "Contact time with the sensor as built, and its prediction band from the continuum",
            key,
            [
                "measured_us",
                *per("sensor", "_us"),
                *per("sensor_calibrated", "_us"),
                "sensor_band_min_us",
                "sensor_band_max_us",
            ],
        ),
        *panels(
            frame,
            "Contact time with the film alone (the thin-layer law is an approximation)",
            key,
            [
                "measured_us",
                *per("film", "_us"),
                *per("film_calibrated", "_us"),
                "thin_layer_band_min_us",
                "thin_layer_band_max_us",
            ],
        ),
        *panels(
            frame,
            "Error against the measurement without the film",
            key,
            [
                "published_fem_error_pct",
                "published_sem_error_pct",
                *per("no_film", "_error_pct"),
                *per("no_film_calibrated", "_error_pct"),
            ],
            drop=_ERROR,
        ),
        *panels(
            frame,
            "Error against the measurement with the sensor as built, and the quasi-static contact's",
            key,
            [*per("sensor", "_error_pct"), *per("sensor_calibrated", "_error_pct"), "sensor_model_form_pct"],
            drop=_ERROR,
        ),
        *panels(
            frame,
            "Error against the measurement with the film alone, and the quasi-static contact's",
            key,
            [
                *per("film", "_error_pct"),
                *per("film_calibrated", "_error_pct"),
                "model_form_pct",
                "radius_to_thickness",
            ],
            drop=_ERROR,
        ),
    ]


def film_band_views(frame: pd.DataFrame) -> list[Panel]:
    """The film's prediction band per reading and ball."""
    return panels(
        frame,
        "The film's prediction band of the SEM's contact time",
        ["row"],
        ["measured_us", "nominal_us", "band_min_us", "band_max_us", "measured_in_band", "monotone"],
        by="variant",
    )


def film_indentation_views(frame: pd.DataFrame) -> list[Panel]:
    """The continuum's indentation against the analytic law, every point."""
    return panels(
        frame,
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


def sweep_views(frame: pd.DataFrame) -> list[Panel]:
    """Every sweep point: the swept values (other than the ball's diameter, shown in mm), the ball,
    the contact time, the largest force and the number of contacts; each row named by its
    reading (by its sweep when a reading has several) and by its method when there are several."""
    fixed = {
        "sweep",
        "row",
        "variant",
        "method",
        "mass_g",
        "diameter_mm",
        "velocity_m_s",
        "rod_length_mm",
        "contact_time_us",
        "first_peak_force_N",
        "max_force_N",
        "n_contacts",
        "ball_diameter_m",
    }
    swept = [c for c in frame.columns if c not in fixed and frame[c].notna().any()]
    one_per_reading = frame.empty or frame.groupby("variant")["sweep"].nunique().max() == 1
    key = ["variant" if one_per_reading else "sweep", *(["method"] if frame["method"].nunique() > 1 else [])]
    return panels(
        frame,
        "Every sweep point",
        key,
        [*swept, "diameter_mm", "mass_g", "contact_time_us", "max_force_N", "n_contacts"],
    )


def orders_views(frame: pd.DataFrame) -> list[Panel]:
    """Per case, the orders of convergence (expected, observed with its standard error, the
    levels fitted, monotone, sign change), then the verdict and the three-level uncertainty."""
    return panels(
        frame,
        "Orders of convergence",
        ["case_id", "method", "quantity"],
        [
            "expected_order",
            "observed_order",
            "order_stderr",
            "fitted_levels",
            "monotone",
            "sign_change",
            "within_expected",
            "asymptotic",
            "gci_order",
            "gci_pct",
            "oscillatory",
            "u_osc_pct",
        ],
        by="case_id",
    )


def stability_views(frame: pd.DataFrame) -> list[Panel]:
    """Every stress run's verdict, its number of contacts, its errors (the tolerances are the
    method's, in the caption) and its wall time."""
    return panels(
        frame,
        "Every stress run, checked",
        ["case_id", "method"],
        ["verdict", "n_contacts", "contact_time_error", "energy_error", "wall_time_s"],
    )
