"""The HTML report (``snakemake --report``) of the session's ``.test/`` build (tests/conftest.py,
``dottest``), made in a copy of it: one self-contained file with every table and figure of the
default target, each captioned from the live configuration, and the workflow's description.
"""

from __future__ import annotations

import html
import json
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from snakemake.utils import Paramspace

from rodimpact.analysis.measured import measured_cases
from rodimpact.analysis.sweeps import sweep_frame
from rodimpact.config.load import load_global_config, load_project
from rodimpact.solvers.registry import METHODS as REGISTRY

from helpers.copies import DOTTEST, DotTestBuild, clone_build, project_cases
from helpers.repo import ROOT as REPO_ROOT
from helpers.snakemake_cli import snakemake

REPORT_TIMEOUT_S = 120
REPORT_MAX_BYTES = 20 * 2**20
REPORT_CATEGORIES = {
    "The experiment's sensor",
    "Paper, Fig. 2 and Fig. 4",
    "Error against run time",
    "Stability",
    "The force handed on",
    "Comparison with measurements",
}
REPORT_MIME = {".csv": "text/csv", ".png": "image/png", ".pdf": "application/pdf"}
#: The attribute through which each tag makes a browser fetch something as the page renders.
FETCHING = {"script": "src", "link": "href", "img": "src", "iframe": "src", "frame": "src",
            "embed": "src", "source": "src", "track": "src", "video": "src", "audio": "src",
            "object": "data", "input": "src"}  # fmt: skip


class _Fetches(HTMLParser):
    """What a page or an HTML fragment makes the browser fetch: (tag, address) pairs that
    are not embedded data. Script bodies are not markup (they hold the embedded libraries)."""

    def __init__(self) -> None:
        super().__init__()
        self.fetched: list[tuple[str, str]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        address = values.get(FETCHING.get(tag, ""))
        if address is not None and not address.startswith("data:"):
            self.fetched.append((tag, address))
        style = values.get("style") or ""
        self.fetched += [
            (tag, url) for url in re.findall(r"url\(\s*['\"]?([^'\")]+)", style) if not url.startswith("data:")
        ]


def _fetched(markup: str) -> list[tuple[str, str]]:
    parser = _Fetches()
    parser.feed(markup)
    parser.close()
    return parser.fetched


def _report_variable(page: str, name: str):
    """The JSON value of ``var <name> = ...;`` in its own script element of snakemake's
    report page (``<script id="<name, with - for _>">``, the value on one line)."""
    script = name.replace("_", "-")
    match = re.search(rf'<script id="{script}">\s*var {name} = (.*);\s*</script>', page)
    assert match, f"no variable {name} in the report"
    return json.loads(match.group(1))


def _text(fragment: str) -> str:
    """The words of an HTML fragment, whitespace collapsed."""
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", fragment)).split())


def _settings_line(config: dict, method: str) -> str:
    """How a caption states a method's settings: its own settings, from config.yaml."""
    block = config["numerics"][method]
    names = REGISTRY[method].options.names()
    values = ("null" if block.get(key) is None else block[key] for key in names)
    return f"{method}: " + ", ".join(f"{key} = {value}" for key, value in zip(names, values))


def _expected_report(workdir: Path) -> dict[str, list[str]]:
    """Each report item of the default target, with what its caption must say: key text of
    its template, and values of the build's own configuration (whose fem_axi level, cases and
    studies differ from the repository's)."""
    config = load_global_config(workdir / "config" / "config.yaml")
    project = load_project(config, root=workdir, schema_dir=REPO_ROOT / "workflow" / "schemas")
    variants = sorted(project.variants["table2"])
    plain = [v for v in variants if "contact" not in project.variants["table2"][v]]
    settings = {m: _settings_line(config, m) for m in REGISTRY}
    model, table2 = project.cases["model"]["methods"], project.cases_in("table2")[0]["methods"]
    expected: dict[str, list[str]] = {}
    for variant in variants:
        expected[f"results/tables/table2_{variant}.csv"] = [
            f"Table 2 of the paper, rod geometry reading {variant}",
            "41.66 % to 57.93 %",
            "9.54 % to 49.42 %",
            '(docs/paper-notes.md, "Impulse responses")',
            '(docs/paper-notes.md, "The experiment\'s rod")',
            "table2_variants.csv",
            *(case["id"] for case in project.cases_in("table2", variant)),
            *(settings[m] for m in project.cases_in("table2", variant)[0]["methods"]),
        ]
    expected["results/tables/table2_variants.csv"] = [
        "Error against the measurements, per rod geometry reading and method",
        "Paper's mean error",
        *variants,
        *(settings[m] for m in table2),
    ]
    expected["results/tables/table2_film.csv"] = [
        "Table 2 without the sensor, with the film alone and with the sensor as built",
        "Against the paper",
    ]
    if config.get("sensor", {}).get("band"):
        expected["results/tables/sensor_band.csv"] = [
            "The sensor as built: the continuum's prediction and its band",
            "What to see",
            "sensor_band/{reading}/*.h5",
        ]
    expected["results/tables/film_band.csv"] = ["prediction band", "Against the paper"]
    expected["results/tables/film_indentation.csv"] = ["calibrated by the continuum", "Against the paper"]
    for ext in ("png", "pdf"):
        expected[f"results/figures/film_force.{ext}"] = ["with and without the sensor film", "Against the paper"]
    sweeps = project.sweeps_in("table2") if hasattr(project, "sweeps_in") else []
    sweep_text = ["The continuous curve", *(c["id"] for c in sweeps)] if sweeps else ["No sweep is configured"]
    for name in config["targets"]["sets"]:
        swept = project.sweeps_in(name) if hasattr(project, "sweeps_in") else []
        if swept:
            # each point named as its run is (snakemake's Paramspace of the grid)
            points = {
                point
                for c in swept
                for point in Paramspace(sweep_frame(c["sweep"]), filename_params="*").instance_patterns
            }
            expected[f"results/tables/sweep_{name}.csv"] = [
                f"Parameter sweeps of the case set {name}",
                f"at {len(points)} points from",
                *(c["id"] for c in swept),
                *(settings[m] for m in sorted({m for c in swept for m in c["sweep"]["methods"]})),
            ]
    for name in config["targets"]["sets"]:  # every set with measurements, compared (compare.smk)
        cases = measured_cases(project.cases_in(name))
        if not cases:
            continue
        expected[f"results/tables/compare_{name}.csv"] = [
            "A case set against its measurements",
            "What to see",
            "Comparing with your experiment",
        ]
        for ext in ("png", "pdf"):
            expected[f"results/figures/compare_{name}.{ext}"] = ["measured values (black", "What to see"]
            for ending, key in (
                ("force", "force_history"),
                ("strain", "strain_history"),
                ("velocity", "velocity_history"),
            ):
                if any(c["measured"].get(key) for c in cases):
                    expected[f"results/figures/compare_{name}_{ending}.{ext}"] = [
                        "One case's measured record",
                        "What to see",
                    ]
        if name in project.calibrate:  # a calibrated set (calibrate.smk): a fit, not a prediction
            expected[f"results/tables/calibration_{name}.csv"] = ["A fit, not a prediction", "leave-one-out"]
            for ext in ("png", "pdf"):
                expected[f"results/figures/calibration_{name}.{ext}"] = ["A fit, not a prediction", "What to see"]
    for ext in ("png", "pdf"):
        # the headline (the sensor's rod, or the rods without approximations) names its companion
        expected[f"results/figures/table2_contact_time.{ext}"] = [
            "Contact time against ball mass",
            "table2_contact_time_readings.png",
            *(settings[m] for m in table2),
        ]
        expected[f"results/figures/table2_contact_time_readings.{ext}"] = [
            "Contact time against ball mass, every reading",
            *plain,
            *sweep_text,
            "41.66 % to 57.93 %",
            *(settings[m] for m in table2),
        ]
        expected[f"results/figures/fig2_contact_force.{ext}"] = [
            "Fig. 2 of the paper: the contact force P(t)",
            "11 % in contact time",
            "9 % in the local extrema",
            "300,000 nodes",
            "fig2_comparison.csv",
            *(settings[m] for m in model),
        ]
        expected[f"results/figures/fig4_midrod_displacement.{ext}"] = [
            "Fig. 4 of the paper: the axial displacement of the cross-section at 0.5 of the rod length",
            *(settings[m] for m in model),
        ]
        for case in config["work_precision"]["cases"]:
            expected[f"results/figures/work_precision_{case}.{ext}"] = [
                f"Error against run time, case {case}",
                "The paper has no such study",
                "Filled markers: the levels the order is fitted on",
                "p the method's expected order",
                *(f"{m}: {len(spec['levels'])} levels" for m, spec in config["work_precision"]["methods"].items()),
            ]
        spec = config["stability"]["map"]
        expected[f"results/figures/stability_map.{ext}"] = [
            "Stability map of the SEM schemes",
            f"{spec['steps_per_contact']} steps per Hertz time",
            ", ".join(map(str, spec["mass_kg"])) + " kg",
            f"{len(spec['mass_kg']) * len(spec['impedance_kg_s'])} points",
            "2 Z / k_c(α_H)",
        ]
        expected[f"results/figures/force_fit_model.{ext}"] = [
            "The contact force handed on",
            "Chebyshev series",
            "1 % of the largest force",
        ]
        for case in (c for c, spec in project.cases.items() if "strain_field" in spec["outputs"]):
            grid = project.cases[case]["field_grid"]
            expected[f"results/figures/wave_map_{case}.{ext}"] = [
                "The waves in the rod: the axial strain",
                case,
                "The incident wave",
                "Its reflection at the far end",
                "The superposition during the contact",
                "The waves left after the separation",
                f"recorded on {grid['sections']} cross-sections",
                "a superposition of waves propagating",
                *(settings[m] for m in ("sem", "fem1d")),
            ]
    expected["results/tables/stability_map.csv"] = expected["results/figures/stability_map.png"]
    expected["results/tables/fig2_comparison.csv"] = [
        "Fig. 2's numbers",
        "Contact time vs SEM",
        "11 % and 9 %",
        *(settings[m] for m in model),
    ]
    levels = [f"{m}: {len(spec['levels'])} levels" for m, spec in config["work_precision"]["methods"].items()]
    expected["results/tables/work_precision.csv"] = ["Every level of the error-against-run-time study", *levels]
    expected["results/tables/work_precision_orders.csv"] = [
        "Orders of convergence",
        "Observed order against Expected order",
        "grid convergence index",
        *levels,
        *(
            f"expected orders: contact time {spec['expected_orders']['contact_time']}"
            for spec in config["work_precision"]["methods"].values()
        ),
    ]
    stress = [c for name in config["stability"]["sets"] for c in project.cases_in(name)]
    expected["results/tables/stability.csv"] = [
        "Stability on stiff and extreme cases",
        "verdict",
        *(c["id"] for c in stress),
        *(
            f"{m}: relative contact-time error {tolerance['contact_time']}"
            for m, tolerance in config["stability"]["tolerances"].items()
        ),
        *(settings[m] for m in sorted({m for c in stress for m in c["methods"]})),
    ]
    return expected


def test_report_captions_name_no_method_or_setting() -> None:
    """The captions take each method's settings from the configuration (whose numerics blocks
    hold exactly each method's own, generated from the registry): no caption lists them."""
    templates = sorted((REPO_ROOT / "workflow" / "report").glob("*.rst"))
    assert len(templates) >= 10
    for path in templates:
        text = path.read_text(encoding="utf-8")
        assert "own_settings" not in text and '"tolerance", "energy_tolerance"' not in text, path.name


@pytest.mark.workflow
def test_report_is_self_contained_and_captioned(dottest: DotTestBuild, tmp_path: Path) -> None:
    """``snakemake --report``: one HTML file that fetches nothing, with every table and figure
    of the default target, each captioned from the live configuration, and the description."""
    project = clone_build(dottest, tmp_path / "p").workdir
    run = snakemake(project.parent, "--report", "report.html", timeout=REPORT_TIMEOUT_S, workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    report = project / "report.html"
    assert 0 < report.stat().st_size < REPORT_MAX_BYTES, report.stat().st_size
    page = report.read_text(encoding="utf-8")
    # Self-contained: no element fetches anything (snakemake inlines its libraries and styles
    # and embeds every result as a data: URI), and no stylesheet imports one.
    assert _fetched(page) == []
    assert not re.search(r"@import\s+(url\()?\s*['\"]?(https?:)?//", page)

    results = _report_variable(page, "results")
    expected = _expected_report(project)
    assert sorted(results) == sorted(expected)
    categories = _report_variable(page, "categories")
    swept = any(path.startswith("results/tables/sweep_") for path in expected)
    calibrated = any(path.startswith("results/tables/calibration_") for path in expected)
    assert set(categories) == REPORT_CATEGORIES | ({"Parameter sweeps"} if swept else set()) | (
        {"Calibration (a fit, not a prediction)"} if calibrated else set()
    )
    for path, result in results.items():
        assert result["name"] == Path(path).name
        assert result["data_uri"].startswith(f"data:{result['mime_type']};")
        assert result["mime_type"] == REPORT_MIME[Path(path).suffix]
        assert "system-message" not in result["caption"], f"{path}: reStructuredText error in its caption"
        assert _fetched(result["caption"]) == [], path
        caption = _text(result["caption"])
        missing = [phrase for phrase in expected[path] if phrase not in caption]
        assert not missing, f"{path}: caption lacks {missing}:\n{caption}"
    # the tables shown in their captions are the artifacts' own HTML tables, rounded
    shown = [
        *(f"table2_{v}" for v in sorted(project_cases(project).variants["table2"])),
        "table2_variants",
        "fig2_comparison",
        *(Path(p).stem for p in expected if p.startswith("results/tables/sweep_")),
    ]
    for stem in shown:
        table = _text((project / f"results/tables/{stem}.html").read_text(encoding="utf-8"))
        assert table and table in _text(results[f"results/tables/{stem}.csv"]["caption"]), stem
    table = _text((project / "results/tables/work_precision_orders.html").read_text(encoding="utf-8"))
    assert table and table in _text(results["results/tables/work_precision_orders.csv"]["caption"])

    description = _report_variable(page, "workflow_desc")
    assert "system-message" not in description and _fetched(description) == []
    text = _text(description)
    for phrase in [
        "rodimpact: the axial impact of a rigid body on an elastic rod",
        "DOI 10.18721/JPM.11115",
        *REPORT_CATEGORIES,
    ]:
        assert phrase in text, f"the description lacks {phrase!r}:\n{text}"
