"""The columns many tables share, declared once: what a case, a ball, a method, a measured time
or an error is to a reader (:class:`~rodimpact.present.table.Column`).

A table declares its columns beside its frame (its own module); the columns it shares with
other tables it takes from here, by name (:data:`COLUMNS`, :func:`shared`), and the columns it
makes per method from :func:`method_time` and :func:`method_error`, which carry the method's
words from the registry. Nothing here reads a meaning out of a column's name.
"""

from __future__ import annotations

from collections.abc import Iterable

from rodimpact.contact.laws import LAWS
from rodimpact.present.table import Column
from rodimpact.solvers.registry import METHODS

__all__ = [
    "COLUMNS",
    "ROLE_WORDS",
    "method_error",
    "method_header",
    "method_time",
    "shared",
]

#: The readings of Table 2 with and without the sensor film, in words (a column made per method
#: and reading, ``{method}_{role}_us``).
ROLE_WORDS = {
    "no_film": "no film",
    "film": "film",
    "film_calibrated": "film, calibrated",
    "no_film_calibrated": "calibrated, no film",
    "sensor": "sensor as built",
    "sensor_calibrated": "sensor as built, calibrated",
}


def method_header(method: str) -> str:
    """A method's name in a table header: its registry ``header``, else its label, else its name."""
    if method not in METHODS:
        return method
    return METHODS[method].header or METHODS[method].label


def _per(method: str, role: str | None) -> tuple[str, str]:
    """The stem of a column made per method (and reading) and its words."""
    if role is None:
        return method, method_header(method)
    return f"{method}_{role}", f"{method_header(method)}, {ROLE_WORDS[role]}"


def method_time(method: str, role: str | None = None) -> Column:
    """The contact time a method computes (of the reading ``role``), µs: ``{method}[_{role}]_us``."""
    stem, words = _per(method, role)
    return Column(f"{stem}_us", words, "µs")


def method_error(method: str, role: str | None = None) -> Column:
    """A method's error against the measurement (of the reading ``role``), %:
    ``{method}[_{role}]_error_pct``."""
    stem, words = _per(method, role)
    return Column(f"{stem}_error_pct", f"{words} error", "%")


_TEXT = ""

#: The columns several tables share, by name.
COLUMNS: dict[str, Column] = {
    column.name: column
    for column in (
        # what a row is
        Column("case_id", "Case", fmt=_TEXT, in_words="case_words", said_by=("row",)),
        Column("case_words", "Case", fmt=_TEXT),
        Column("row", "Ball", fmt=_TEXT),
        Column("variant", "Reading", fmt=_TEXT),
        Column(
            "method",
            "Method",
            fmt=_TEXT,
            words={name: spec.label for name, spec in METHODS.items()},
            in_words="method_label",
        ),
        Column("method_label", "Method", fmt=_TEXT),
        Column(
            "contact_law",
            "Contact law",
            fmt=_TEXT,
            words={n: law.label for n, law in LAWS.items()},
            said_by=("method_label",),
        ),
        Column("film", "Film", fmt=_TEXT),
        Column("n_cases", "Cases", fmt=_TEXT),
        Column("status", "Status", fmt=_TEXT),
        Column("message", "Message", fmt=_TEXT),
        Column("warning", "Warning", fmt=_TEXT),
        # the balls and the rod
        Column("diameter_mm", "Diameter", "mm"),
        Column("mass_g", "Mass", "g", ".3g"),
        Column("velocity_m_s", "Velocity", "m/s", ".4f"),
        Column("rod_radius_mm", "Rod radius", "mm", ".3g"),
        Column("rod_length_mm", "Rod length", "mm", ".1f"),
        Column("film_modulus_pa", "Film modulus", "Pa", ".3g"),
        # measured and printed by the paper
        Column("measured_us", "Measured", "µs"),
        Column("published_fem_us", "Paper FEM", "µs"),
        Column("published_sem_us", "Paper SEM", "µs"),
        Column("published_fem_error_pct", "Paper FEM error", "%"),
        Column("published_sem_error_pct", "Paper SEM error", "%"),
        # a band of predictions
        Column("nominal_us", "Nominal", "µs"),
        Column("band_min_us", "Band min", "µs"),
        Column("band_max_us", "Band max", "µs"),
        Column("measured_in_band", "Measured in band", fmt=_TEXT),
        Column("monotone", "Monotone", fmt=_TEXT),
        # a run's numbers
        Column("contact_time_us", "Contact time", "µs", ".3f"),
        Column("n_contacts", "Contacts", fmt=_TEXT),
        Column("wall_time_s", "Wall time", "s", ".3f"),
    )
}


def shared(names: Iterable[str]) -> tuple[Column, ...]:
    """The shared columns ``names`` (:data:`COLUMNS`).

    Raises
    ------
    KeyError
        A name that is not a shared column (declare it beside its table).
    """
    return tuple(COLUMNS[name] for name in names)
