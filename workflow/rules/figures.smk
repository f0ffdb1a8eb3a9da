# Figures: read HDF5 runs only; rendered headless.


rule fig2:
    """Fig. 2: contact force against time for the case 'model', every method it runs."""
    input:
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
        code=SRC_PRESENT,
    output:
        pdf=report(
            "results/figures/fig2_contact_force.pdf",
            caption="../report/fig2.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2: contact force", "format": "PDF"},
        ),
        png=report(
            "results/figures/fig2_contact_force.png",
            caption="../report/fig2.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2: contact force", "format": "PNG"},
        ),
        provenance="results/figures/fig2_contact_force.provenance.json",
    log:
        "logs/figures/fig2_contact_force.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig2.py"


rule fig4:
    """Fig. 4: displacement of the cross-section at half the rod length, case 'model'."""
    input:
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
        code=SRC_PRESENT,
    output:
        pdf=report(
            "results/figures/fig4_midrod_displacement.pdf",
            caption="../report/fig4.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 4",
            labels={"artifact": "Fig. 4: displacement half-way along the rod", "format": "PDF"},
        ),
        png=report(
            "results/figures/fig4_midrod_displacement.png",
            caption="../report/fig4.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 4",
            labels={"artifact": "Fig. 4: displacement half-way along the rod", "format": "PNG"},
        ),
        provenance="results/figures/fig4_midrod_displacement.provenance.json",
    params:
        fraction=0.5,
    log:
        "logs/figures/fig4_midrod_displacement.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig4.py"


rule fig_table2:
    """Contact time against ball mass: measured, published and ours, one panel per rod (a grid by
    rod radius and length), with the curves of the table2 set's sweeps, and the readings with the
    film and their bands."""
    input:
        runs=[run for v in TABLE2_VARIANTS for run in table2_runs(v)],
        sweep_runs=sweep_point_runs(PROJECT.sweeps_in("table2")),
        bands=expand("results/studies/film_band_{variant}.h5", variant=FILM_VARIANTS),
        sensor_bands=sensor_band_files([v for v, band in SENSOR_READINGS.items() if band and v in SENSOR_VARIANTS]),
        code=SRC_PRESENT,
    output:
        pdf=report(
            "results/figures/table2_contact_time.pdf",
            caption="../report/table2_contact_time.rst",
            category="Paper, Table 2",
            subcategory="All readings",
            labels={"artifact": "Contact time against ball mass", "format": "PDF"},
        ),
        png=report(
            "results/figures/table2_contact_time.png",
            caption="../report/table2_contact_time.rst",
            category="Paper, Table 2",
            subcategory="All readings",
            labels={"artifact": "Contact time against ball mass", "format": "PNG"},
        ),
        provenance="results/figures/table2_contact_time.provenance.json",
    params:
        variants=TABLE2_VARIANTS,
        film_variants=FILM_VARIANTS,
        sensors=SENSOR_VARIANTS,
        # each reading in words (the case file's description): the panels' titles
        descriptions={v: spec.get("description", "") for v, spec in PROJECT.variants.get("table2", {}).items()},
    log:
        "logs/figures/table2_contact_time.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig_table2.py"


# The contact force with and without the film: the lightest and the heaviest ball on the text's
# rod, by the SEM and the continuum.
FILM_FORCE = {"rows": ["ball_3.16mm", "ball_12.73mm"], "variants": ["r10_l30", "r10_l30_film"],
              "methods": ["sem", "fem_axi"]}
# its runs: each row on each reading, by each of the methods the case runs
FILM_FORCE_RUNS = [f"results/runs/{case['id']}/{method}.h5"
                   for case in (PROJECT.cases[f"{row}-{variant}"] for row in FILM_FORCE["rows"]
                                for variant in FILM_FORCE["variants"])
                   for method in FILM_FORCE["methods"] if method in case["methods"]]


rule fig_film_force:
    """The contact force P(t) with and without the sensor film, lightest and heaviest ball."""
    input:
        runs=FILM_FORCE_RUNS,
        code=SRC_PRESENT,
    output:
        pdf=report(
            "results/figures/film_force.pdf",
            caption="../report/film_force.rst",
            category="Paper, Table 2",
            subcategory="The sensor film",
            labels={"artifact": "Contact force with and without the film", "format": "PDF"},
        ),
        png=report(
            "results/figures/film_force.png",
            caption="../report/film_force.rst",
            category="Paper, Table 2",
            subcategory="The sensor film",
            labels={"artifact": "Contact force with and without the film", "format": "PNG"},
        ),
        provenance="results/figures/film_force.provenance.json",
    params:
        rows=FILM_FORCE["rows"],
        variants=FILM_FORCE["variants"],
        methods=FILM_FORCE["methods"],
    log:
        "logs/figures/film_force.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig_film_force.py"
