"""Figures fit for a journal, checked where a test can: every axis labelled with its unit (or
named as a relative quantity), nothing drawn outside the canvas, at most one legend per axes and
every legend inside the figure, short legends in readable type, titles and legends in words (no
internal ids, no version strings, Greek letters set in mathtext), and curves that lie on each
other told apart by their markers.

Every figure the workflow draws is rendered here by the artifact function its rule calls, from
small runs made with the workflow's own writer (:func:`rodimpact.jobs.runner.run_to_file`),
read back from their HDF5 files; a band file is written with synthetic numbers by
:func:`rodimpact.storage.bands.write_band`."""

from __future__ import annotations

import copy
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import rodimpact.present.compare_figures as compare_figures  # noqa: E402
import rodimpact.present.figures as figures  # noqa: E402
import rodimpact.present.study_figures as study_figures  # noqa: E402
from rodimpact.analysis.studies import level_case, map_point_case, map_point_names  # noqa: E402
from rodimpact.analysis.sweeps import sweep_point_case, sweep_points  # noqa: E402
from rodimpact.jobs.indentation import indentation_to_file  # noqa: E402
from rodimpact.jobs.runner import run_to_file  # noqa: E402
from rodimpact.present.figure_artifacts import (  # noqa: E402
    make_fig2,
    make_fig4,
    make_fig_film_force,
    make_fig_force_fit,
    make_fig_readings,
)
from rodimpact.present.figures import METHOD_LABELS  # noqa: E402
from rodimpact.present.forces import export_forces  # noqa: E402
from rodimpact.present.study_figures import (  # noqa: E402
    make_stability_map,
    make_work_precision_figure,
    order_text,
    quantity_words,
)
from rodimpact.present.table2_figures import SECOND_CONTACT_LABEL, short_source  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402
from rodimpact.storage.bands import BAND_PARAMETERS, CaseBand, write_band  # noqa: E402
from rodimpact.storage.runs import read_summary  # noqa: E402

from helpers.figures import MAX_LEGEND_ENTRIES, assert_journal_ready  # noqa: E402


@pytest.fixture
def rendered(monkeypatch: pytest.MonkeyPatch) -> list:
    """The figures the artifact functions save, kept instead of drawn into files (empty files
    stand in for them, for the provenance sidecar to hash); the Table 2 figure is written for
    real, and its test checks the files."""
    kept: list = []

    def keep(fig, *, pdf, png, **_):
        kept.append(fig)
        for path in (pdf, png):
            Path(path).write_bytes(b"")

    monkeypatch.setattr(figures, "save_figure", keep)
    for module in (study_figures, compare_figures):  # the modules that took it by name
        monkeypatch.setattr(module, "save_figure", keep)
    return kept


def outputs(folder: Path, name: str) -> dict:
    return {
        "pdf": folder / f"{name}.pdf",
        "png": folder / f"{name}.png",
        "provenance": folder / f"{name}.provenance.json",
    }


# ---------------------------------------------------------------- the model case: Fig. 2, Fig. 4


@pytest.fixture(scope="module")
def model_runs(shipped_project, tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """The model impact by both SEM schemes (their curves lie on each other), stored as the
    workflow stores them."""
    folder = tmp_path_factory.mktemp("model")
    return [
        run_to_file(shipped_project.cases["model"], method, folder / f"{method}.h5") for method in ("sem", "sem_paper")
    ]


def test_fig2_tells_overlapping_curves_apart_and_names_its_markers(model_runs, rendered, tmp_path) -> None:
    make_fig2(model_runs, **outputs(tmp_path, "fig2"))
    (fig,) = rendered
    assert_journal_ready(fig)
    (ax,) = fig.axes
    curves = [line for line in ax.lines if line.get_label().startswith(("SEM", "FEM"))]
    assert len(curves) == 2 and len({line.get_marker() for line in curves}) == 2
    starts = [line.get_markevery()[0] for line in curves]
    assert len(set(starts)) == 2  # staggered: the markers of curves on each other do not coincide
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert any("maxima" in label for label in labels)


def test_fig4_names_its_station_and_the_end_of_contact_once(model_runs, rendered, tmp_path) -> None:
    make_fig4(model_runs, 0.5, **outputs(tmp_path, "fig4"))
    (fig,) = rendered
    assert_journal_ready(fig)
    (ax,) = fig.axes
    assert "x$ = 0.25 m (µm)" in ax.get_ylabel()  # half of the model's 0.5 m rod
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert sum("end of the first contact" in label for label in labels) == 1, labels
    curves = [line for line in ax.lines if line.get_label().startswith("SEM")]
    assert len({line.get_marker() for line in curves}) == 2


def test_the_force_fit_figure_is_journal_ready(model_runs, rendered, tmp_path) -> None:
    jsons = [tmp_path / f"{p.stem}.json" for p in model_runs]
    export_forces(
        model_runs,
        [tmp_path / f"{p.stem}.csv" for p in model_runs],
        jsons,
        provenance=tmp_path / "forces.provenance.json",
    )
    make_fig_force_fit(model_runs, jsons, **outputs(tmp_path, "force_fit"))
    (fig,) = rendered
    assert_journal_ready(fig)


# ------------------------------------------------------- Table 2: readings, sweeps, film, bands

ROWS = ("ball_3.16mm", "ball_5.56mm", "ball_12.73mm")
READINGS = ("r1_l30", "r1_l301", "r10_l30", "r10_l301", "r10_l30_film")
#: The readings with the sensor as built -> calibrated by the continuum.
SENSORS = {"r10_l30_sensor": False, "r10_l30_sensor_cal": True}
#: A user's own measurement of one more ball, on the text's rod.
OWN = ("ball_4.75mm-r10_l30", "Our drop tests, 2024 (high-speed camera, 20 balls)")


@pytest.fixture(scope="module")
def table2(shipped_project, tmp_path_factory: pytest.TempPathFactory) -> dict:
    """Rows of Table 2 on every rod and on the text's rod with the film, by the SEM; every third
    point of the thin long rod's sweep; two balls of the film's sweep; a band per film row."""
    folder = tmp_path_factory.mktemp("table2")
    cases = [shipped_project.cases[f"{row}-{variant}"] for row in ROWS for variant in READINGS]
    own = copy.deepcopy(shipped_project.cases[OWN[0]])
    own["measured"] = {**own["measured"], "source": OWN[1], "contact_time_us": 50.0}
    runs = [run_to_file(case, "sem", folder / case["id"] / "sem.h5") for case in [*cases, own]]
    sweep_runs = []
    for sweep_id, pick in (
        ("ball_sweep-r1_l301", slice(None, None, 3)),
        ("ball_sweep_film-r10_l30_film", slice(15, 21)),
    ):
        sweep = shipped_project.sweeps[sweep_id]
        for index, point in list(enumerate(sweep_points(sweep["sweep"])))[pick]:
            case = sweep_point_case(sweep, point, f"p{index}")
            sweep_runs.append(run_to_file(case, "sem", folder / sweep_id / f"p{index}.h5"))
    film = [read_summary(p) for p in runs if read_summary(p).config["variant"] == "r10_l30_film"]
    bands = [
        CaseBand(
            r.case_id,
            float(r.config["measured"]["contact_time_us"]),
            1e6 * r.summary["contact_time_s"],
            np.ones((2, 3)),
            1e6 * r.summary["contact_time_s"] * np.array([0.92, 1.08]),
            {n: np.array([1.0, 2.0]) for n in BAND_PARAMETERS},
            {n: np.array([1.0, 2.0]) for n in BAND_PARAMETERS},
        )
        for r in film
    ]
    band = write_band(folder / "film_band_r10_l30_film.h5", bands, variant="r10_l30_film", method="sem", config={})
    # the sensor as built: the continuum on one row, the calibrated SEM on every row, with a band each
    sensor = shipped_project.cases["ball_3.16mm-r10_l30_sensor"]
    runs.append(run_to_file(sensor, "fem_axi", folder / sensor["id"] / "fem_axi.h5"))
    sensor_bands = []
    for row in ROWS:
        case = shipped_project.cases[f"{row}-r10_l30_sensor_cal"]
        curve = folder / f"{case['id']}.curve.h5"
        indentation_to_file(case, str(curve))
        runs.append(run_to_file(case, "sem", folder / case["id"] / "sem.h5", contact_curve=curve))
        t = 1e6 * read_summary(runs[-1]).summary["contact_time_s"]
        sensor_bands.append(
            write_band(
                folder / f"sensor_band_{case['id']}.h5",
                [
                    CaseBand(
                        case["id"],
                        float(case["measured"]["contact_time_us"]),
                        t,
                        np.ones((2, 1)),
                        t * np.array([0.8, 1.3]),
                        {"a: thickness_m": np.array([1.0, 2.0])},
                        {"a: thickness_m": np.array([t, 1.1 * t])},
                        ("a: thickness_m",),
                    )
                ],
                variant="r10_l30_sensor_cal",
                method="sem",
                config={},
            )
        )
    descriptions = {v: spec["description"] for v, spec in shipped_project.variants["table2"].items()}
    return {
        "runs": runs,
        "sweeps": sweep_runs,
        "band": band,
        "descriptions": descriptions,
        "sensor_bands": sensor_bands,
    }


@pytest.fixture(scope="module")
def table2_figures(table2, tmp_path_factory: pytest.TempPathFactory):
    """The headline figure and its companion, as make_fig_readings draws them."""
    kept = []
    folder = tmp_path_factory.mktemp("fig")
    out, companion = outputs(folder, "table2_contact_time"), outputs(folder, "table2_contact_time_readings")
    real = figures.save_figure
    figures.save_figure = lambda fig, **kwargs: (kept.append(fig), real(fig, **kwargs))
    try:
        make_fig_readings(
            table2["runs"],
            [*READINGS, *SENSORS],
            sweep_runs=table2["sweeps"],
            film_variants=["r10_l30_film"],
            band_files=[table2["band"]],
            descriptions=table2["descriptions"],
            sensors=SENSORS,
            sensor_band_files=table2["sensor_bands"],
            title="Table 2",
            **out,
            **{f"companion_{k}": v for k, v in companion.items()},
        )
    finally:
        figures.save_figure = real
    headline, readings = kept
    headline.outputs, readings.outputs = out, companion
    return headline, readings


@pytest.fixture(scope="module")
def table2_figure(table2_figures):
    """The companion: every reading of the rod, the paper's numbers and the approximations."""
    return table2_figures[1]


@pytest.fixture(scope="module")
def table2_headline(table2_figures):
    """The headline: the text's rod, with the sensor as built."""
    return table2_figures[0]


def test_the_headline_is_the_texts_rod_with_the_sensor_and_the_models_without_it(table2_headline, table2) -> None:
    """One panel, the text's rod; the measurements, the sensor as built (the continuum's points,
    the calibrated SEM, the band) and the models without it; no approximation and no published
    number; at most 8 legend entries."""
    assert_journal_ready(table2_headline)
    assert all(table2_headline.outputs[kind].stat().st_size > 10_000 for kind in ("pdf", "png"))
    words = table2["descriptions"]
    assert set(_panels(table2_headline)) == {words["r10_l30"]}
    labels = _legend_labels(table2_headline)
    assert len(labels) <= 8, labels
    assert not any("approximation" in label or "the paper's" in label for label in labels), labels
    assert any(label.startswith("measured") for label in labels)
    assert any(METHOD_LABELS["fem_axi"] in label and "sensor as built" in label for label in labels)
    assert any("calibrated by the continuum" in label for label in labels)
    assert any("band" in label and "continuum" in label for label in labels)
    assert f"{METHOD_LABELS['sem']}, no film" in labels  # the models without the sensor


def _panels(fig) -> dict:
    """Visible panels by the first line of their title."""
    return {ax.get_title().split("\n")[0]: ax for ax in fig.axes if ax.get_visible()}


def test_table2_figure_is_journal_ready_and_titled_in_words(table2_figure, table2) -> None:
    assert_journal_ready(table2_figure)
    assert all(table2_figure.outputs[kind].stat().st_size > 10_000 for kind in ("pdf", "png"))
    words = table2["descriptions"]
    assert set(_panels(table2_figure)) == {words[v] for v in READINGS if not v.endswith("_film")}
    (text,) = [ax.get_title() for ax in table2_figure.axes if ax.get_title().startswith(words["r10_l30"])]
    # the film reading drawn on the panel it extends, said once (the sensor as built on this rod is
    # the headline's); wrapped to the panel's width: compared word by word
    assert " ".join(text.split()).endswith("without the sensor, and with the film alone (red)"), text


def test_table2_panels_form_a_grid_by_radius_and_length(table2_figure, table2) -> None:
    panels, words = _panels(table2_figure), table2["descriptions"]
    where = {v: panels[words[v]].get_position() for v in ("r1_l30", "r1_l301", "r10_l30", "r10_l301")}
    assert where["r1_l30"].y0 == pytest.approx(where["r1_l301"].y0) and where["r1_l30"].y0 > where["r10_l30"].y0
    assert where["r1_l30"].x0 == pytest.approx(where["r10_l30"].x0) and where["r1_l30"].x0 < where["r1_l301"].x0
    assert where["r10_l30"].y0 == pytest.approx(where["r10_l301"].y0)


def test_table2_axes_are_one_scale_fitted_to_the_data(table2_figure, table2) -> None:
    axes = list(_panels(table2_figure).values())
    assert len({ax.get_xlim() for ax in axes}) == 1 and len({ax.get_ylim() for ax in axes}) == 1
    masses = [1000 * read_summary(p).config["impactor"]["mass_kg"] for p in table2["runs"]]
    (x0, x1), (y0, y1) = axes[0].get_xlim(), axes[0].get_ylim()
    assert x0 < min(masses) and x1 > max(masses) and x1 / x0 < 2.0 * max(masses) / min(masses)
    shown = np.concatenate(
        [
            np.asarray(line.get_ydata(), float)[
                (np.asarray(line.get_xdata(), float) >= x0) & (np.asarray(line.get_xdata(), float) <= x1)
            ]
            for ax in axes
            for line in ax.lines
        ]
    )
    shown = shown[np.isfinite(shown)]
    assert y0 < shown.min() and y1 > shown.max()  # nothing drawn at the table's masses is cut off
    assert y1 < 1.5 * shown.max() and y0 > shown.min() / 1.5  # and the data fill the axes


def test_table2_rings_the_runs_with_a_second_contact(table2_figure, table2) -> None:
    many = [read_summary(p) for p in [*table2["runs"], *table2["sweeps"]]]
    many = [r for r in many if int(r.summary["n_contacts"]) > 1]
    assert many  # the thin long rod strikes some balls twice
    rings = [line for ax in table2_figure.axes for line in ax.lines if line.get_label() == SECOND_CONTACT_LABEL]
    ringed = sorted(round(float(y), 6) for line in rings for y in line.get_ydata())
    assert ringed == sorted(round(1e6 * float(r.summary["contact_time_s"]), 6) for r in many)
    assert SECOND_CONTACT_LABEL in _legend_labels(table2_figure)


def _legend_labels(figure) -> list[str]:
    """The figure legend's labels, unwrapped (the legend wraps them to its columns' width)."""
    return [" ".join(t.get_text().split()) for t in figure.legends[0].get_texts()]


def test_table2_measured_points_by_source_and_the_papers_points(table2_figure, table2) -> None:
    labels = _legend_labels(table2_figure)
    paper = 'measured (Table 2, column "Natural experiment")'
    assert paper in labels and f"measured ({short_source(OWN[1])})" in labels
    assert short_source(OWN[1]) == "Our drop tests, 2024"
    panel = _panels(table2_figure)[table2["descriptions"]["r10_l30"]]
    (own,) = [line for line in panel.lines if line.get_label() == f"measured ({short_source(OWN[1])})"]
    assert list(own.get_ydata()) == [50.0]
    configs = [r.config for r in map(read_summary, table2["runs"]) if r.config["variant"] == "r10_l30"]
    paper = [line for line in panel.lines if line.get_label() == "the paper's FEM (up) and SEM (down), its Table 2"]
    for family, marker in (("fem", "^"), ("sem", "v")):
        (line,) = [line for line in paper if line.get_marker() == marker]
        expected = sorted(c["published"][family]["contact_time_us"] for c in configs)
        assert sorted(v for v in line.get_ydata() if np.isfinite(v)) == pytest.approx(expected)


@pytest.mark.parametrize("which", ["headline", "companion"])
def test_every_prediction_drawn_names_its_model(table2_figures, which) -> None:
    """Each line and band of a model in the Table 2 figure says which model it is in the legend:
    a method and how it takes the contact (no film, the film as a thin layer, the sensor as built,
    calibrated by the continuum), or the paper's; the thin-layer law is labelled an approximation,
    and the sensor's band as the continuum's."""
    table2_figure = table2_figures[0 if which == "headline" else 1]
    models = [*METHOD_LABELS.values(), "the paper's"]
    contact = ("no film", "thin layer", "sensor as built")
    labels = _legend_labels(table2_figure)
    drawn = {artist.get_label() for ax in table2_figure.axes for artist in [*ax.lines, *ax.containers]}
    drawn = {label for label in drawn if not label.startswith("_")}
    assert drawn <= set(labels)  # everything drawn is in the legend
    predictions = [label for label in drawn if not label.startswith("measured") and label != SECOND_CONTACT_LABEL]
    for label in predictions:
        if "band" in label:
            assert ("continuum" in label) != ("approximation" in label), label
        else:
            assert any(model in label for model in models), label
            assert "the paper's" in label or any(words in label for words in contact), label
        if "thin layer" in label and "band" not in label and "sweep" not in label:
            assert "approximation" in label, label
    sensor = [label for label in predictions if "sensor as built" in label]
    if which == "companion":
        assert any("approximation" in label for label in predictions)  # the thin layer is here
        return
    assert any(METHOD_LABELS["fem_axi"] in label for label in sensor)  # the continuum, the headline
    assert any("calibrated by the continuum" in label for label in sensor)
    assert any("band" in label and "continuum" in label for label in sensor)


def test_short_source_cuts_long_sources_at_a_word() -> None:
    assert (
        short_source('Table 2, column "Natural experiment" (time of the contact interaction, us)')
        == 'Table 2, column "Natural experiment"'
    )
    long = "Drop tests of steel balls on an aluminium rod at the laboratory of a university, 2024"
    assert len(short_source(long)) <= 48 and short_source(long).endswith("…") and " " in short_source(long)


def test_the_film_force_figure_is_journal_ready(table2, rendered, tmp_path) -> None:
    runs = [
        p
        for p in table2["runs"]
        if p.parent.name.split("-")[0] in ("ball_3.16mm", "ball_12.73mm")
        and p.parent.name.split("-")[1] in ("r10_l30", "r10_l30_film")
    ]
    assert len(runs) == 4
    make_fig_film_force(runs, ["ball_3.16mm", "ball_12.73mm"], **outputs(tmp_path, "film_force"))
    (fig,) = rendered
    assert_journal_ready(fig)


# ----------------------------------------------------------------------- the numerical studies


def test_work_precision_has_a_panel_per_quantity_and_one_legend_of_methods(
    shipped_project, shipped_config, rendered, tmp_path
) -> None:
    methods = {name: dict(shipped_config["work_precision"]["methods"][name]) for name in ("sem", "sem_paper")}
    methods["sem"]["levels"] = [{"steps_per_contact": n} for n in (25, 50, 100, 200, 400)]
    methods["sem_paper"]["levels"] = [{"steps_per_contact": n} for n in (250, 500, 1000, 2000)]
    runs = []
    for method, spec in methods.items():
        for level, overrides in enumerate(spec["levels"]):
            case = level_case(
                shipped_project.cases["ball_3.16mm-r1_l30"], method, shipped_config["numerics"], overrides
            )
            runs.append(
                run_to_file(
                    case, method, tmp_path / f"{method}_level{level}.h5", level=level, code_version="1.2.3+gdeadbeef"
                )
            )
    study = {"methods": methods, "fit_levels": 3, "arrival_window": shipped_config["work_precision"]["arrival_window"]}
    make_work_precision_figure(runs, study, **outputs(tmp_path, "work_precision"))
    (fig,) = rendered
    assert_journal_ready(fig)
    panels = [ax for ax in fig.axes if ax.get_visible()]
    titles = [ax.get_title() for ax in panels]
    assert titles[0] == "contact time" and titles[1] == quantity_words("max_1") == "first force maximum"
    assert set(titles) >= {
        "contact time",
        "first force maximum",
        "force history, $L_2$ norm",
        "force history, max norm",
    } and len(titles) == len(set(titles))
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == [
        *(METHODS[m].label for m in methods),
        "level in the fit",
        "level not in the fit",
        "expected order (slope guide)",
    ]
    words = {
        "contact time": "contact_time",
        "force history, $L_2$ norm": "history_l2",
        "force history, max norm": "history_max",
    }
    for ax in panels:  # each panel's box: the observed order ± its standard error, the expected in parentheses
        orders = [t.get_text() for t in ax.get_legend().get_texts()]
        expected = [methods[m]["expected_orders"][words.get(ax.get_title(), "max")] for m in methods]
        assert [o.rsplit(" (", 1)[1] for o in orders] == [f"{order_text(e)})" for e in expected], orders
        assert all(re.fullmatch(r"(\d\.\d\d ± \d\.\d\d|–) \(.+\)", o) for o in orders), orders
    (contact,) = [ax for ax in panels if ax.get_title() == "contact time"]
    sem_order = float(contact.get_legend().get_texts()[0].get_text().split()[0])
    assert 1.8 < sem_order < 2.3
    # a slope guide per method under its fitted levels, labelled with its expected order
    assert [t.get_text() for t in contact.texts] == ["$h^{2}$", "$h^{1}$"]
    assert order_text(1.5) == "3/2" and order_text(1.667) == "5/3" and order_text(2.0) == "2"
    assert "Table 2 row 1" in fig._suptitle.get_text() and "rod radius 1 mm, length 30.1 mm" in fig._suptitle.get_text()


def test_the_stability_map_is_journal_ready(shipped_project, shipped_config, rendered, tmp_path) -> None:
    spec = {
        "base_case": "model",
        "mass_kg": [1e-4, 1e-2],
        "impedance_kg_s": [10.0, 1000.0],
        "steps_per_contact": 100,
        "accuracy": 1e-2,
        "methods": ["sem", "sem_paper"],
    }
    runs, references = [], []
    for name in map_point_names(spec):
        for method in ("reference", *spec["methods"]):
            case = map_point_case(shipped_project.cases["model"], spec, name, method, shipped_config["numerics"])
            path = run_to_file(case, case["methods"][0], tmp_path / name / f"{method}.h5", keep_failed=True)
            (references if method == "reference" else runs).append(path)
    make_stability_map(runs, references, spec, csv=tmp_path / "stability_map.csv", **outputs(tmp_path, "stability_map"))
    (fig,) = rendered
    assert_journal_ready(fig)
    assert len([ax for ax in fig.axes if ax.get_visible()]) == 2


# --------------------------------------------------------------------------------- the checker


def test_the_checker_catches_a_legend_off_the_canvas_a_label_without_unit_and_ids() -> None:
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
    ax.set_ylabel("contact force $P$ (kN)")
    assert_journal_ready(fig)
    for title in ("case r1_l301", "AMD EPYC; Linux 6.18.44", "rodimpact 0.1.0+gdeadbeef", "Z = S sqrt(E rho)"):
        ax.set_title(title)
        with pytest.raises(AssertionError):
            assert_journal_ready(fig)
    ax.set_title(r"$Z = S\sqrt{E\rho}$, force history, $L_2$ norm")
    assert_journal_ready(fig)
    lines = ax.plot(np.zeros((2, MAX_LEGEND_ENTRIES + 1)))
    ax.legend(lines, [f"curve {k}" for k in range(len(lines))], fontsize=5)
    with pytest.raises(AssertionError):
        assert_journal_ready(fig)
    plt.close(fig)


@pytest.mark.parametrize("which", ["headline", "companion"])
def test_no_panel_of_the_table2_figures_has_more_than_8_legend_entries(table2_figures, which) -> None:
    """What one panel draws, counted as the legend shows it (one entry per label)."""
    figure = table2_figures[0 if which == "headline" else 1]
    for title, ax in _panels(figure).items():
        labels = {a.get_label() for a in [*ax.lines, *ax.containers, *ax.collections]}
        labels = {label for label in labels if not label.startswith("_")}
        assert len(labels) <= 8, (title, sorted(labels))
