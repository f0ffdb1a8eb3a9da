"""Figures fit for a journal, checked where a test can: every axis labelled with its unit,
nothing drawn outside the canvas, one legend per axes inside the figure, and curves that lie on
each other told apart by their markers. Rendered headless from runs stored as the workflow
stores them."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import pytest  # noqa: E402

from rodimpact.io.store import read_run, write_run  # noqa: E402
from rodimpact.present.figures import plot_contact_force, plot_force_fits  # noqa: E402
from rodimpact.present.forces import force_fit_of  # noqa: E402
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions  # noqa: E402
from rodimpact.solvers.sem.solver import solve_sem  # noqa: E402

from conftest import model_problem  # noqa: E402

UNIT = re.compile(r"\((µs|kN|N|s|m|%|[^()]*% of[^()]*)\)")


def assert_journal_ready(fig: matplotlib.figure.Figure) -> None:
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    canvas = fig.bbox
    tight = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    assert tight.x0 >= -1 and tight.y0 >= -1 and tight.x1 <= canvas.x1 + 1 and tight.y1 <= canvas.y1 + 1, tight
    for ax in fig.axes:
        if ax.get_ylabel():
            assert UNIT.search(ax.get_ylabel()), ax.get_ylabel()
        if ax.get_xlabel():
            assert UNIT.search(ax.get_xlabel()), ax.get_xlabel()
        legends = [child for child in ax.get_children() if isinstance(child, matplotlib.legend.Legend)]
        assert len(legends) <= 1
        for legend in legends:
            box = legend.get_window_extent(renderer)
            assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= canvas.x1 + 1 and box.y1 <= canvas.y1 + 1
    assert any(ax.get_xlabel() for ax in fig.axes)


@pytest.fixture(scope="module")
def model_runs(tmp_path_factory: pytest.TempPathFactory) -> list:
    """The model impact by both SEM schemes (their curves lie on each other), stored and read back."""
    directory = tmp_path_factory.mktemp("runs")
    records = []
    for method, options in (("sem", SEMOptions()), ("sem_paper", PaperSEMOptions(steps_per_contact=4000))):
        result = solve_sem(model_problem(), options)
        series = {"time": (result.time, "s", "time since first contact"),
                  "contact_force": (result.contact_force, "N", "contact force")}
        path = write_run(directory / f"{method}.h5", method=method, config={"id": "model"}, series=series,
                         summary=result.summary(), wall_time_s=0.1, code_version="0.1.0+gdeadbeef")
        records.append(read_run(path))
    return records


def test_fig2_tells_overlapping_curves_apart_and_names_its_markers(model_runs: list) -> None:
    fig = plot_contact_force(model_runs, title="Contact force, case 'model'")
    assert_journal_ready(fig)
    (ax,) = fig.axes
    curves = [line for line in ax.lines if line.get_label().startswith(("SEM", "FEM"))]
    assert len(curves) == 2 and len({line.get_marker() for line in curves}) == 2
    starts = [line.get_markevery()[0] for line in curves]
    assert len(set(starts)) == 2  # staggered: the markers of curves on each other do not coincide
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert any("maxima" in label for label in labels)


def test_the_force_fit_figure_is_journal_ready(model_runs: list) -> None:
    fig = plot_force_fits(model_runs, [force_fit_of(r) for r in model_runs], title="Closed form, case 'model'")
    assert_journal_ready(fig)


def test_the_checker_catches_a_legend_off_the_canvas_and_a_label_without_unit() -> None:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="a curve")
    ax.set_xlabel("time $t$ (µs)")
    ax.set_ylabel("contact force $P$ (kN)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.5, 1.0))
    with pytest.raises(AssertionError):
        assert_journal_ready(fig)
    ax.get_legend().remove()
    ax.set_ylabel("contact force")
    with pytest.raises(AssertionError):
        assert_journal_ready(fig)
    plt.close(fig)
