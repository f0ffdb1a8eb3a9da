# rodimpact: two commands do all the set-up on a fresh machine with Python 3.11 and pip.
#   make paper   build .venv from environment.lock if missing or stale, then snakemake -j2
#   make test    same environment; ruff check, ruff format --check and snakefmt --check (the
#                rules in pyproject.toml), snakemake --lint, a dry run, the small configuration in
#                .test/ built end to end (.test/results), pytest
#   make test-cluster  .test/ built through profiles/slurm on a one-node SLURM scheduler of this
#                machine and checked against the local build (as root: installs Debian's
#                slurm-wlm and munge when missing); after make test, its .test/ is reused
#   make bench   benchmarks -> results/benchmarks/*.csv (one job at a time, for clean timings),
#                results/benchmarks/build.csv: the last build's time per rule (jobs, solvers, overhead)
#                from snakemake's job records, and results/benchmarks/planning.csv: the dry run's
#                time, a one-rule workflow's and a sem sweep's of 100 to 100,000 points planned
#                alone, cost_share.csv: each method's solve time over its cost model's, and
#                sweep_scaling.csv / sweep_point.csv: sem sweeps of 100 to 10,000 points built in
#                parts with -j1 and -j2, and where a point's time goes; run make paper first
#   make convergence   only the error-against-run-time study -> results/tables/work_precision.csv
#   make convergence-separate   the study's separate cases (levels over a minute each, not in
#                make paper) -> results/tables/work_precision_separate*.{csv,md,html}
#   make sphere-flat   the continuum's elastic-plastic sphere on a rigid flat against the published
#                finite-element fits, on three meshes (not in make paper: about 11 minutes) ->
#                results/verification/sphere_flat.{csv,pdf,png}
#   make sensor-plastic   Table 2's sensor as built with its layers yielding (J2, the law with
#                memory), elastic and over the layers' yield ranges, and the law with memory against
#                the dynamic continuum on two rows (not in make paper: about 31 minutes) ->
#                results/sensor_plastic/sensor_plastic{,_dynamic}.csv, sensor_plastic.md
#   make stability     only the stress cases and the stability map -> results/tables/stability.csv
#   make sensor-axes   each constant of the sensor stack along its range by the continuum (not in
#                make paper: the check that the band's corners bound the time) ->
#                results/tables/sensor_band_axes.{csv,md,html}
#   make film-axes     each constant of the sensor film along its range by the thin-layer law (not
#                in make paper: the check that the film band's corners bound the time) ->
#                results/tables/film_band_axes.{csv,md,html}
#   make report        make paper, then the self-contained HTML report -> results/report.html
#                      (every table and figure with its caption; the benchmarks too if they exist)
#   make test-tools    install what some tests use beyond Python, when missing (as root):
#                      make browser (Debian's chromium and chromium-driver: the report's tests)
#                      and make latex (pdflatex and booktabs: the LaTeX table's test); without
#                      them those tests skip, unless RODIMPACT_REQUIRE_TOOLS is set (CI)
#   make report-check  open results/report.html in headless Chromium at 1400 x 900, save the first
#                      screen as results/report_screenshot.png, and fail unless the report's title
#                      is on it (installs Debian's chromium and chromium-driver when missing)
#   make readme-images the figures README.md shows -> docs/images/*.png (built first when needed)
#   make provenance    audit results/: every file resolves to the config and committed code that
#                      made it, and is up to date (fails on a hand-edited or stale file)

PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-from-lock
CORES  ?= 2

.PHONY: paper test test-cluster test-tools browser latex bench sphere-flat sensor-plastic convergence convergence-separate stability sensor-axes film-axes report report-check readme-images provenance env clean distclean

$(STAMP): environment.lock pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info[:2] == (3, 11) else "rodimpact needs Python 3.11 (environment.lock is for 3.11), found " + sys.version.split()[0])'
	rm -rf $(VENV)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --require-hashes -r environment.lock
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	touch $(STAMP)

env: $(STAMP)

paper: $(STAMP)
	$(BIN)/snakemake -j$(CORES)

test: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/snakefmt --check Snakefile workflow/rules
	$(BIN)/snakemake --lint
	$(BIN)/snakemake -n --quiet rules
	$(BIN)/snakemake -j$(CORES) --directory .test
	$(BIN)/python -m pytest

test-cluster: $(STAMP)
	$(BIN)/python tests/cluster/check_cluster.py

bench: $(STAMP)
	$(BIN)/snakemake -j1 --forcerun bench_sem bench_sem_scaling bench_fem -- results/benchmarks/sem.csv \
		results/benchmarks/sem_scaling.csv results/benchmarks/fem.csv
	$(BIN)/python -m rodimpact.tools.bench results/benchmarks/fem.csv
	$(BIN)/python -m rodimpact.tools.build_stats --csv results/benchmarks/build.csv
	$(BIN)/python -m rodimpact.tools.bench_planning --csv results/benchmarks/planning.csv --sweep-points 100 1000 10000 100000
	$(BIN)/python -m rodimpact.tools.cost_share --csv results/benchmarks/cost_share.csv
	$(BIN)/python -m rodimpact.tools.bench_sweeps --csv results/benchmarks/sweep_scaling.csv --point-split 1000

sphere-flat: $(STAMP)
	$(BIN)/python -m rodimpact.tools.sphere_flat --out results/verification

sensor-plastic: $(STAMP)
	$(BIN)/python -m rodimpact.tools.sensor_plastic --out results/sensor_plastic --jobs $(CORES)

convergence: $(STAMP)
	$(BIN)/snakemake -j$(CORES) results/tables/work_precision.csv results/tables/work_precision_orders.md

convergence-separate: $(STAMP)
	$(BIN)/snakemake -j$(CORES) results/tables/work_precision_separate.csv results/tables/work_precision_separate_orders.md

stability: $(STAMP)
	$(BIN)/snakemake -j$(CORES) results/tables/stability.csv results/figures/stability_map.png

sensor-axes: $(STAMP)
	$(BIN)/snakemake -j$(CORES) results/tables/sensor_band_axes.csv results/tables/sensor_band_axes.md

film-axes: $(STAMP)
	$(BIN)/snakemake -j$(CORES) results/tables/film_band_axes.csv results/tables/film_band_axes.md

# After the build (a no-op when it is up to date), so the report never shows stale results;
# the benchmarks are not rebuilt (make bench), only reported when they exist.
report: paper
	$(BIN)/snakemake --report results/report.html all $(wildcard results/benchmarks/sem.csv results/benchmarks/fem.csv \
		results/tables/work_precision_separate_orders.csv)

# What some tests use beyond Python, from Debian's packages (as root): CI installs them before
# make test (make test-tools), so that those tests run instead of skipping.
test-tools: browser latex

# chromium and chromedriver: make report-check and the report's tests
browser:
	@if [ ! -x /usr/bin/chromium ] || [ ! -x /usr/bin/chromedriver ]; then \
		apt-get install -y chromium chromium-driver || \
		{ apt-get update && apt-get install -y chromium chromium-driver; }; \
	fi

# pdflatex with booktabs: the test that compiles a LaTeX table
latex:
	@if ! command -v pdflatex > /dev/null; then \
		apt-get install -y --no-install-recommends texlive-latex-base texlive-latex-recommended || \
		{ apt-get update && apt-get install -y --no-install-recommends texlive-latex-base texlive-latex-recommended; }; \
	fi

# Checks the report as it is (make report builds it); chromium and its driver from Debian's packages.
report-check: $(STAMP) browser
	$(BIN)/python -m rodimpact.tools.report_check results/report.html --screenshot results/report_screenshot.png

# The figures README.md embeds: copies of the build's PNGs, committed with the README.
README_IMAGES := fig2_contact_force table2_contact_time wave_map_model
readme-images: $(STAMP)
	$(BIN)/snakemake -j$(CORES) $(README_IMAGES:%=results/figures/%.png)
	mkdir -p docs/images
	cp $(README_IMAGES:%=results/figures/%.png) docs/images/

provenance: $(STAMP)
	$(BIN)/python -m rodimpact.tools.audit --json logs/provenance_audit.json

clean:
	rm -rf results logs .snakemake

distclean: clean
	rm -rf $(VENV)
