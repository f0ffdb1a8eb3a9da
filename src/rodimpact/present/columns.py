"""What every column of every table means to a reader: a label in words, a unit, a format.

The tables' frames keep machine names (``measured_us``, ``sem_error_pct``: the CSV's header,
the unit in the suffix); every table written for people (HTML, LaTeX, Markdown) takes its
headers and its rounding from here, through :func:`column`. Three kinds of name are known:

- the fixed columns of :data:`COLUMNS`;
- the columns made per method, ``{method}_us`` and ``{method}_error_pct``, and per method and
  reading of the sensor film, ``{method}_{role}_us`` and ``{method}_{role}_error_pct``, labelled
  with each method's ``header`` in the registry and :data:`ROLE_WORDS`;
- numbered columns (``max_{i}_kN``) and comparisons with a method (``*_vs_{method}_pct``).

Anything else is read from its suffix (:data:`SUFFIX_UNITS`), its words capitalised.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rodimpact.contact.laws import LAWS
from rodimpact.solvers.registry import METHODS

__all__ = [
    "COLUMNS",
    "Column",
    "LATEX_UNITS",
    "ROLE_WORDS",
    "SUFFIX_UNITS",
    "column",
    "headers_with_units",
    "method_header",
    "words_only",
]


@dataclass(frozen=True)
class Column:
    """How one column is shown.

    Attributes
    ----------
    label : str
        The header in words, without the unit ("Measured", "SEM error").
    unit : str
        The unit as printed ("µs", "%", "g"); empty for a pure number or a text.
    fmt : str
        A format spec for a number (``".2f"``: two decimals); empty for a text, a flag or an
        integer, shown as they are (a flag as yes or no).
    words : mapping, optional
        An id -> its words, for a column of ids (a method, a contact law): a table for people
        shows the words; an id not in it is shown as it is.
    """

    label: str
    unit: str = ""
    fmt: str = ".2f"
    words: Mapping[str, str] | None = field(default=None, compare=False, hash=False)

    @property
    def header(self) -> str:
        """The label and its unit in parentheses: ``Measured (µs)``."""
        return f"{self.label} ({self.unit})" if self.unit else self.label

    def text(self, value: Any) -> str:
        """A cell: the number in this column's format, an en dash for a missing value, yes or no
        for a flag, a text as it is."""
        if value is None or (isinstance(value, (float, np.floating)) and math.isnan(value)):
            return "–"
        if isinstance(value, (bool, np.bool_)):
            return "yes" if value else "no"
        if self.words and isinstance(value, str):
            return self.words.get(value, value)
        if self.fmt and isinstance(value, (int, float, np.integer, np.floating)):
            return format(float(value), self.fmt)
        return str(value)


#: Units as printed (HTML, Markdown) -> LaTeX (plain, no siunitx).
LATEX_UNITS = {"µs": r"$\mu$s", "µm": r"$\mu$m", "%": r"\%", "kg/s": "kg/s", "m/s": "m/s"}

#: Suffix of a machine name -> unit, longest first (``_kg_s`` before ``_s``).
SUFFIX_UNITS = {
    "_kg_s": "kg/s",
    "_m_s": "m/s",
    "_us": "µs",
    "_um": "µm",
    "_mm": "mm",
    "_kN": "kN",
    "_pct": "%",
    "_MiB": "MiB",
    "_pa": "Pa",
    "_kg": "kg",
    "_g": "g",
    "_N": "N",
    "_m": "m",
    "_s": "s",
}

#: The readings of Table 2 with and without the sensor film (``film_tables.FILM_ROLES``), in words.
ROLE_WORDS = {
    "no_film": "no film",
    "film": "film",
    "film_calibrated": "film, calibrated",
    "no_film_calibrated": "calibrated, no film",
    "sensor": "sensor as built",
    "sensor_calibrated": "sensor as built, calibrated",
}

_TEXT = ""
_ORDINALS = ("1st", "2nd", "3rd")

#: Columns that name in words what another column names by its id: a table for people shows the
#: words only (:func:`words_only`), under the id's header; the CSV keeps both.
WORDS_FOR = {"method": "method_label", "quantity": "quantity_words", "case_id": "case_words"}
#: Columns another column already says in words: the case id (its ball and its reading have
#: their own columns), the contact law's id (the method's words name the law).
SAID_BY = {"case_id": ("row",), "contact_law": ("method_label",)}

#: The error quantities of the error-against-run-time study, in words (a table's ``quantity``).
STUDY_QUANTITY_WORDS = {
    "contact_time": "contact time",
    "history_l2": "force history, L2 norm",
    "history_max": "force history, max norm",
    **{
        f"max_{k}": f"{ordinal} force maximum"
        for k, ordinal in enumerate(
            ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth"), start=1
        )
    },
}

#: The fixed columns.
COLUMNS: dict[str, Column] = {
    # what a row is
    "case_id": Column("Case", fmt=_TEXT),
    "case_words": Column("Case", fmt=_TEXT),
    "row": Column("Ball", fmt=_TEXT),
    "variant": Column("Reading", fmt=_TEXT),
    "method": Column("Method", fmt=_TEXT, words={name: spec.label for name, spec in METHODS.items()}),
    "sweep": Column("Sweep", fmt=_TEXT),
    "point": Column("Point", fmt=_TEXT),
    "quantity": Column("Quantity", fmt=_TEXT, words=STUDY_QUANTITY_WORDS),
    # the same in words (the CSV keeps both; a table for people shows these, under the same header)
    "method_label": Column("Method", fmt=_TEXT),
    "quantity_words": Column("Quantity", fmt=_TEXT),
    "warning": Column("Warning", fmt=_TEXT),
    "film": Column("Film", fmt=_TEXT),
    "contact_law": Column("Contact law", fmt=_TEXT, words={name: law.label for name, law in LAWS.items()}),
    "law": Column("Law", fmt=_TEXT),
    "paper_method": Column("Paper's method", fmt=_TEXT, words={"sem": "the paper's SEM", "fem": "the paper's FEM"}),
    "n_cases": Column("Cases", fmt=_TEXT),
    # a comparison's measured and computed values, each in its row's unit (column "unit")
    "measured": Column("Measured", fmt=".5g"),
    "computed": Column("Computed", fmt=".5g"),
    # the balls and the rod
    "diameter_mm": Column("Diameter", "mm"),
    "mass_g": Column("Mass", "g", ".3g"),
    "ball_diameter_m": Column("Ball diameter", "m", ".5f"),
    "velocity_m_s": Column("Velocity", "m/s", ".4f"),
    "rod_length_mm": Column("Rod length", "mm", ".1f"),
    "film_modulus_pa": Column("Film modulus", "Pa", ".3g"),
    # Table 2: measured, printed by the paper, ours
    "measured_us": Column("Measured", "µs"),
    "published_fem_us": Column("Paper FEM", "µs"),
    "published_sem_us": Column("Paper SEM", "µs"),
    "published_fem_error_pct": Column("Paper FEM error", "%"),
    "published_sem_error_pct": Column("Paper SEM error", "%"),
    "sem_vs_published_sem_pct": Column("SEM vs paper SEM", "%"),
    # the errors per reading
    "mean_error_pct": Column("Mean error", "%"),
    "max_error_pct": Column("Largest error", "%"),
    "mean_signed_error_pct": Column("Mean signed error", "%"),
    "paper_mean_error_pct": Column("Paper's mean error", "%"),
    "paper_max_error_pct": Column("Paper's largest error", "%"),
    # the sensor film
    "nominal_us": Column("Nominal", "µs"),
    "band_min_us": Column("Band min", "µs"),
    "band_max_us": Column("Band max", "µs"),
    "measured_in_band": Column("Measured in band", fmt=_TEXT),
    "monotone": Column("Monotone", fmt=_TEXT),
    "radius_to_thickness": Column("Contact radius / film thickness"),
    "model_form_pct": Column("Model-form error", "%"),
    "sensor_model_form_pct": Column("Model-form error, sensor", "%"),
    "sensor_band_min_us": Column("Sensor band min (continuum)", "µs"),
    "sensor_band_max_us": Column("Sensor band max (continuum)", "µs"),
    "thin_layer_band_min_us": Column("Thin-layer band min (approximation)", "µs"),
    "thin_layer_band_max_us": Column("Thin-layer band max (approximation)", "µs"),
    "nominal_error_pct": Column("Nominal error", "%"),
    "constants": Column("Constants", fmt=_TEXT),
    "constant": Column("Constant", fmt=_TEXT),
    "low_us": Column("At the low end", "µs"),
    "high_us": Column("At the high end", "µs"),
    "continuum_lengthens_at": Column("Continuum lengthens at", fmt=_TEXT),
    "lengthens_at": Column("Lengthens at", fmt=_TEXT),
    "law_lengthens_at": Column("Analytic law lengthens at", fmt=_TEXT),
    "agree": Column("Same end", fmt=_TEXT),
    "role": Column("Role", fmt=_TEXT),
    "fitted_us": Column("Fitted stack", "µs"),
    "held_out_us": Column("Held out", "µs"),
    "fitted_error_pct": Column("Fitted stack error", "%"),
    "held_out_error_pct": Column("Held-out error", "%"),
    "force_N": Column("Force", "N", ".4g"),
    # a calibration (docs/calibration.md): its constants, and each measurement fitted
    "parameter": Column("Constant", fmt=_TEXT),
    "low": Column("Least", fmt=".4g"),
    "high": Column("Largest", fmt=".4g"),
    "start": Column("Start", fmt=".4g"),
    "value": Column("Fitted", fmt=".5g"),
    "standard_error": Column("Standard error", fmt=".2g"),
    "relative_standard_error_pct": Column("Standard error", "%", ".2g"),
    "correlation": Column("Correlation with the others", fmt=_TEXT),
    "at_bound": Column("At a bound", fmt=_TEXT),
    "start_predicted": Column("Model at the start", fmt=".5g"),
    "start_error_pct": Column("Model at the start, error", "%", ".3g"),
    "fitted": Column("Fitted model", fmt=".5g"),
    "fitted_standard_error": Column("Fitted model's standard error", fmt=".2g"),
    "residual_pct": Column("Fitted model's error", "%", ".3g"),
    "held_out_predicted": Column("Predicted held out", fmt=".5g"),
    "held_out_status": Column("Held-out fit", fmt=_TEXT),
    "continuum_approach_um": Column("Continuum approach", "µm", ".4f"),
    "law_approach_um": Column("Law approach", "µm", ".4f"),
    "law_error_pct": Column("Law error", "%"),
    "contact_radius_um": Column("Contact radius", "µm", ".1f"),
    "film_thickness_um": Column("Film thickness", "µm", ".1f"),
    "radius_to_film_thickness": Column("Contact radius / film thickness"),
    "interpolation_error_half": Column("Interpolation error", fmt=".1e"),
    # Fig. 2 and the sweeps
    "contact_time_us": Column("Contact time", "µs", ".3f"),
    "n_maxima": Column("Maxima", fmt=_TEXT),
    "maxima_vs_sem_pct": Column("Maxima vs SEM", "%", ".3f"),
    "paper_fem_vs_sem_contact_time_pct": Column("Paper FEM vs SEM, contact time", "%", ".0f"),
    "paper_fem_vs_sem_extrema_pct": Column("Paper FEM vs SEM, extrema", "%", ".0f"),
    "first_peak_force_N": Column("First force maximum", "N", ".4g"),
    "max_force_N": Column("Largest force maximum", "N", ".4g"),
    "n_contacts": Column("Contacts", fmt=_TEXT),
    # the orders of convergence
    "observed_order": Column("Observed order"),
    "theoretical_order": Column("Theoretical order", fmt=".0f"),
    "fitted_levels": Column("Fitted levels", fmt=_TEXT),
    "expected_order": Column("Expected order", fmt=".3g"),
    "order_stderr": Column("Standard error", fmt=".2f"),
    "sign_change": Column("Sign change", fmt=_TEXT),
    "within_expected": Column("Within 0.3 of expected", fmt=_TEXT),
    "asymptotic": Column("Asymptotic", fmt=_TEXT),
    "arrival_offset": Column("Offset from a wave arrival (of 2L/c)", fmt=".3f"),
    "gci_order": Column("GCI order"),
    "gci_pct": Column("GCI", "%", ".3f"),
    "oscillatory": Column("Oscillatory", fmt=_TEXT),
    "u_osc_pct": Column("Oscillatory half range", "%", ".3f"),
    # the stress cases
    "status": Column("Status", fmt=_TEXT),
    "success": Column("Success", fmt=_TEXT),
    "finite": Column("Finite", fmt=_TEXT),
    "min_force_N": Column("Smallest force", "N", ".3g"),
    "energy_error": Column("Energy error", fmt=".1e"),
    "energy_tolerance": Column("Energy tolerance", fmt=".0e"),
    "contact_time_s": Column("Contact time", "s", ".4e"),
    "reference_contact_time_s": Column("Reference contact time", "s", ".4e"),
    "contact_time_error": Column("Contact-time error", fmt=".1e"),
    "contact_time_tolerance": Column("Contact-time tolerance", fmt=".0e"),
    "contact_intervals_us": Column("Contact intervals", "µs", _TEXT),
    "wall_time_s": Column("Wall time", "s", ".3f"),
    "message": Column("Message", fmt=_TEXT),
    "verdict": Column("Verdict", fmt=_TEXT),
}


def method_header(method: str) -> str:
    """A method's name in a table header: its registry ``header``, else its label, else its name."""
    if method not in METHODS:
        return method
    return METHODS[method].header or METHODS[method].label


def _per_method(name: str) -> Column | None:
    """``{method}_us``, ``{method}_error_pct``, ``{method}_{role}_us``, ``{method}_{role}_error_pct``."""
    for suffix, unit, what in (("_error_pct", "%", " error"), ("_us", "µs", "")):
        if not name.endswith(suffix):
            continue
        stem = name[: -len(suffix)]
        for method in sorted(METHODS, key=len, reverse=True):
            if stem == method:
                return Column(method_header(method) + what, unit)
            for role, words in ROLE_WORDS.items():
                if stem == f"{method}_{role}":
                    return Column(f"{method_header(method)}, {words}{what}", unit)
    return None


def column(name: str) -> Column:
    """How the column ``name`` is shown: its label, unit and format.

    Parameters
    ----------
    name : str
        A column of a table's frame (the CSV's header).
    """
    if name in COLUMNS:
        return COLUMNS[name]
    per_method = _per_method(name)
    if per_method is not None:
        return per_method
    maximum = re.fullmatch(r"max_(\d+)_kN", name)
    if maximum:
        i = int(maximum.group(1))
        return Column(f"{_ORDINALS[i - 1] if i <= len(_ORDINALS) else f'{i}th'} maximum", "kN", ".3f")
    versus = re.fullmatch(r"(.+)_vs_(.+)_pct", name)
    if versus:
        what, method = versus.groups()
        return Column(f"{column(what).label} vs {method_header(method)}", "%", ".3f")
    for suffix, unit in SUFFIX_UNITS.items():
        if name.endswith(suffix) and len(name) > len(suffix):
            words = name[: -len(suffix)].replace("_", " ")
            return Column(words[:1].upper() + words[1:], unit)
    words = name.replace("_", " ")
    return Column(words[:1].upper() + words[1:], fmt=_TEXT)


def headers_with_units(columns: Iterable[str]) -> dict[str, str]:
    """Column -> its header in words with its unit: ``measured_us`` -> ``Measured (µs)``."""
    return {name: column(name).header for name in columns}


def words_only(names: Iterable[str], empty: Iterable[str] = ()) -> list[str]:
    """The columns a table for people shows, of ``names``: each thing once, in words.

    An id with a column of its words (:data:`WORDS_FOR`) gives way to that column, an id that
    another column already says (:data:`SAID_BY`) is left out, and so is a column in
    ``empty`` (no value in any row). The order of ``names`` is kept.
    """
    names = list(names)
    present, blank = set(names), set(empty)
    dropped = {n for n, words in WORDS_FOR.items() if words in present}
    dropped |= {n for n, others in SAID_BY.items() if any(o in present for o in others)}
    return [n for n in names if n not in dropped and n not in blank]
