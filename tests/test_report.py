"""The HTML report's first screen, checked in headless Chromium (``make report-check``).

snakemake's report shows the workflow's description in a centred, full-height pane: a
description taller than the window pushes its title above the top, out of reach. The checks
here open pages in headless Chromium at 1400 x 900 through chromedriver: a page laid out like
the report with a short and with a tall description (the check must pass one and fail the
other), and the report snakemake builds from ``workflow/report/workflow.rst`` with the shipped
configuration. They need Debian's ``chromium`` and ``chromedriver`` (``make browser`` installs
them), and are skipped without them, unless ``RODIMPACT_REQUIRE_TOOLS`` is set (CI).
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from PIL import Image

from rodimpact.tools.report_check import CHROMEDRIVER, CHROMIUM, TitleBox, check_report, main

from helpers.repo import ROOT as REPO_ROOT

#: CI sets it (.ci/run, after make test-tools): there a missing browser fails the tests instead of
#: skipping them.
REQUIRE_BROWSER = bool(os.environ.get("RODIMPACT_REQUIRE_TOOLS"))

needs_chromium = pytest.mark.skipif(
    not (CHROMIUM.is_file() and CHROMEDRIVER.is_file()) and not REQUIRE_BROWSER,
    reason=f"{CHROMIUM} or {CHROMEDRIVER} is missing (apt-get install chromium chromium-driver; "
    "make report-check installs them)",
)

#: The report's title (workflow/report/workflow.rst).
TITLE = "rodimpact: the axial impact of a rigid body on an elastic rod"
#: The categories of the full report (and Benchmarks, after make bench): the description lists each.
CATEGORIES = (
    "Comparison with measurements",
    "The experiment's sensor",
    "Paper, Fig. 2 and Fig. 4",
    "Error against run time",
    "Parameter sweeps",
    "Stability",
    "The force handed on",
    "Benchmarks",
)


def _box(top: float, bottom: float, uncovered: bool = True) -> TitleBox:
    return TitleBox(
        text="t", top=top, bottom=bottom, left=287.0, right=781.0, width=1400.0, height=757.0, uncovered=uncovered
    )


def test_the_title_is_visible_only_whole_inside_the_window_and_uncovered() -> None:
    assert _box(8.0, 116.0).visible
    assert not _box(-75.0, 33.0).visible  # cut off at the top
    assert not _box(700.0, 800.0).visible  # cut off at the bottom
    assert not _box(8.0, 116.0, uncovered=False).visible


def _page(path: Path, description_px: int) -> Path:
    """A page laid out as snakemake's report: a navigation bar, and a full-height pane that centres
    its content (the description, ``description_px`` high, beside a tall graph)."""
    path.write_text(
        textwrap.dedent(f"""\
        <!doctype html><html><head><meta charset="utf-8"><style>
        body {{ margin: 0 }} .row {{ display: flex; width: 100vw; height: 100vh }}
        nav {{ width: 20%; height: 100vh; overflow: auto; background: #334155 }}
        .pane {{ flex-grow: 1; display: flex; align-items: center; justify-content: center; height: 100vh;
                 overflow: auto }}
        .inner {{ display: flex; gap: 12px; padding: 12px; align-items: flex-start }}
        </style></head><body><div id="loading-screen" style="display: none"></div><div class="row">
        <nav><h1>Snakemake Report</h1></nav><div class="pane"><div class="inner">
        <div class="prose" style="max-width: 32rem"><h1 class="title">{TITLE}</h1>
        <p style="height: {description_px}px">A description.</p></div>
        <div style="max-height: 100vh; width: 400px; height: 2000px"></div></div></div></div></body></html>
        """),
        encoding="utf-8",
    )
    return path


@needs_chromium
def test_a_short_description_shows_the_title_and_a_tall_one_hides_it(tmp_path: Path) -> None:
    short = check_report(_page(tmp_path / "short.html", 300), tmp_path / "short.png")
    assert short.visible and short.text == TITLE
    assert short.top >= 0 and short.width == 1400
    with Image.open(tmp_path / "short.png") as image:
        assert image.format == "PNG" and image.size[0] == 1400 and 500 < image.size[1] <= 900
    tall = check_report(_page(tmp_path / "tall.html", 3000), tmp_path / "tall.png")
    assert not tall.visible and tall.bottom < 0  # above the top: no scrolling reaches it
    assert main([str(tmp_path / "tall.html"), "--screenshot", str(tmp_path / "tall.png")]) == 1
    assert main([str(tmp_path / "short.html"), "--screenshot", str(tmp_path / "short.png")]) == 0
    assert main([str(tmp_path / "missing.html"), "--screenshot", str(tmp_path / "m.png")]) == 2


def _snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if not k.startswith("SNAKEMAKE") and k != "PYTHONPATH"}
    return subprocess.run(
        [sys.executable, "-m", "snakemake", "--nocolor", "-j1", *args],
        cwd=workdir,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


@pytest.mark.workflow
@needs_chromium
def test_the_report_description_fits_the_first_screen(tmp_path: Path) -> None:
    """The description of workflow/report/workflow.rst, with the shipped configuration and every
    category of the full report (one small result each), rendered by ``snakemake --report``."""
    rules = "\n".join(
        textwrap.dedent(f"""\
        rule r{i}:
            output: report("out/r{i}.txt", category={name!r})
            shell: "echo {i} > {{output}}"
        """)
        for i, name in enumerate(CATEGORIES)
    )
    (tmp_path / "Snakefile").write_text(
        f'configfile: "{REPO_ROOT / "config" / "config.yaml"}"\n'
        f'report: "{REPO_ROOT / "workflow" / "report" / "workflow.rst"}"\n\n'
        f'rule all:\n    input: [f"out/r{{i}}.txt" for i in range({len(CATEGORIES)})]\n\n{rules}',
        encoding="utf-8",
    )
    build = _snakemake(tmp_path)
    assert build.returncode == 0, build.stderr[-3000:]
    report = _snakemake(tmp_path, "--report", "report.html")
    assert report.returncode == 0, report.stderr[-3000:]
    box = check_report(tmp_path / "report.html", tmp_path / "report.png")
    assert box.text == TITLE
    assert box.visible, f"the title is at {box.top:.0f} to {box.bottom:.0f} px in a {box.height:.0f} px window"
