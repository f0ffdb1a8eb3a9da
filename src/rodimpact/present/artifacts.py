"""One function per artifact of the workflow: read HDF5 runs, write tables and figures.

The workflow's scripts call these and nothing else; tests call them directly. They are written in
:mod:`.table_artifacts` (the tables), :mod:`.figure_artifacts` (the figures),
:mod:`.study_artifacts` (the work-precision and stability studies) and :mod:`.sensor_artifacts`
(the bands' tables; the film's axes from here), sharing :mod:`.artifact_common`, and gathered
here: the presentation rules' code digest
(``SRC_PRESENT`` in ``workflow/rules/common.smk``) is the closure of this module's imports, so a
module that writes an artifact for those rules is imported here. The figure modules (matplotlib)
are imported by the functions that draw, so that a table's job does not load them.
"""

from __future__ import annotations

from rodimpact.present.artifact_common import case_in_words
from rodimpact.present.figure_artifacts import (
    make_fig2,
    make_fig4,
    make_fig_film_force,
    make_fig_force_fit,
    make_fig_readings,
)
from rodimpact.present.sensor_artifacts import make_axes_table
from rodimpact.present.study_artifacts import (
    make_stability,
    make_stability_map,
    make_work_precision,
    make_work_precision_figure,
)
from rodimpact.present.table_artifacts import (
    make_comparison,
    make_film_band_table,
    make_film_indentation_table,
    make_film_table,
    make_readings_summary,
    make_readings_table,
    make_sweep_table,
)

__all__ = [
    "make_comparison",
    "make_fig2",
    "make_fig4",
    "make_fig_film_force",
    "make_fig_readings",
    "make_axes_table",
    "make_film_band_table",
    "make_film_indentation_table",
    "make_stability",
    "make_stability_map",
    "make_sweep_table",
    "make_readings_table",
    "make_film_table",
    "make_readings_summary",
    "make_work_precision",
    "make_work_precision_figure",
    "make_fig_force_fit",
    "case_in_words",
]
