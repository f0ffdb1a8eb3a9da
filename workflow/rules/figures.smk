# Figures: read HDF5 runs only; rendered headless.


rule paper_model:
    """Fig. 2 (contact force against time), its numbers (contact time and maxima per method against
    the SEM and the paper's), Fig. 4 (displacement of the cross-section at half the rod length) and
    the closed form of the force handed on drawn over it, from the runs of the case 'model' by
    every method it runs: one job, as they read the same runs."""
    input:
        runs=run_batches(lambda w: runs_of([PROJECT.cases["model"]])),
        forces=lambda w: f"results/forces/{PROJECT.cases['model']['set']}",
    output:
        fig2_pdf=report(
            "results/figures/fig2_contact_force.pdf",
            caption="../report/fig2.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2: contact force", "format": "PDF"},
        ),
        fig2_png=report(
            "results/figures/fig2_contact_force.png",
            caption="../report/fig2.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2: contact force", "format": "PNG"},
        ),
        fig2_provenance="results/figures/fig2_contact_force.provenance.json",
        csv=report(
            "results/tables/fig2_comparison.csv",
            caption="../report/fig2_comparison.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2 in numbers", "format": "CSV"},
        ),
        md="results/tables/fig2_comparison.md",
        html="results/tables/fig2_comparison.html",
        table_provenance="results/tables/fig2_comparison.provenance.json",
        fig4_pdf=report(
            "results/figures/fig4_midrod_displacement.pdf",
            caption="../report/fig4.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 4",
            labels={"artifact": "Fig. 4: displacement half-way along the rod", "format": "PDF"},
        ),
        fig4_png=report(
            "results/figures/fig4_midrod_displacement.png",
            caption="../report/fig4.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 4",
            labels={"artifact": "Fig. 4: displacement half-way along the rod", "format": "PNG"},
        ),
        fig4_provenance="results/figures/fig4_midrod_displacement.provenance.json",
        force_fit_pdf=report(
            "results/figures/force_fit_model.pdf",
            caption="../report/force_fit.rst",
            category="The force handed on",
            labels={"artifact": "Contact force and its closed form", "format": "PDF"},
        ),
        force_fit_png=report(
            "results/figures/force_fit_model.png",
            caption="../report/force_fit.rst",
            category="The force handed on",
            labels={"artifact": "Contact force and its closed form", "format": "PNG"},
        ),
        force_fit_provenance="results/figures/force_fit_model.provenance.json",
    log:
        "logs/figures/paper_model.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.figure_artifacts:make_paper_model"),
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
        fraction=0.5,
        jsons=lambda w: force_files([PROJECT.cases["model"]], "json"),
    script:
        "../scripts/artifact.py"


rule fig_readings:
    """Contact time against ball mass for a set with variants, in two figures: the headline (the
    rod the sensor was built on: measured, the sensor as built, the models without it) and its
    companion (every rod, one panel each in a grid by radius and length, with the published
    results, the sweeps' curves, and the readings with the thin-layer film and their bands)."""
    input:
        runs=run_batches(lambda w: set_reading_runs(w.set)),
        sweep_parts=lambda w: sweep_part_files(PROJECT.sweeps_in(w.set)),
        band_files=lambda w: expand(
            "results/studies/film_band_{variant}.h5", variant=[v for v in FILM_VARIANTS if READING_SET_OF[v] == w.set]
        ),
        sensor_bands=lambda w: sensor_band_dirs([v for v in SENSOR_READINGS if v in sensor_variants(w.set)]),
    output:
        pdf=report(
            "results/figures/{set}_contact_time.pdf",
            caption="../report/table2_contact_time.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={
                "set": "{set}",
                "artifact": "Contact time against ball mass, the sensor as built",
                "format": "PDF",
            },
        ),
        png=report(
            "results/figures/{set}_contact_time.png",
            caption="../report/table2_contact_time.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={
                "set": "{set}",
                "artifact": "Contact time against ball mass, the sensor as built",
                "format": "PNG",
            },
        ),
        provenance="results/figures/{set}_contact_time.provenance.json",
        companion_pdf=report(
            "results/figures/{set}_contact_time_readings.pdf",
            caption="../report/table2_contact_time_readings.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Contact time against ball mass, every reading", "format": "PDF"},
        ),
        companion_png=report(
            "results/figures/{set}_contact_time_readings.png",
            caption="../report/table2_contact_time_readings.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Contact time against ball mass, every reading", "format": "PNG"},
        ),
        companion_provenance="results/figures/{set}_contact_time_readings.provenance.json",
    log:
        "logs/figures/{set}_contact_time.log",
    wildcard_constraints:
        set=one_of(READING_SETS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.figure_artifacts:make_fig_readings"),
        runs=lambda w: set_reading_runs(w.set),
        sweep_runs=lambda w: sweep_point_runs(PROJECT.sweeps_in(w.set)),
        sensor_band_files=lambda w: sensor_band_files([v for v in SENSOR_READINGS if v in sensor_variants(w.set)]),
        variants=lambda w: READING_SETS[w.set],
        film_variants=lambda w: [v for v in FILM_VARIANTS if READING_SET_OF[v] == w.set],
        sensors=lambda w: sensor_variants(w.set),
        descriptions=lambda w: {v: READING_DESCRIPTIONS[v] for v in READING_SETS[w.set]},
        title=lambda w: set_title(w.set),
        published=lambda w: set_published(w.set),
    script:
        "../scripts/artifact.py"


# The contact force with and without the film: config["sensor"]["film_force"] (common.smk).
rule fig_film_force:
    """The contact force P(t) with and without the sensor film, lightest and heaviest ball."""
    input:
        runs=run_batches(FILM_FORCE_RUNS),
    output:
        pdf=report(
            "results/figures/film_force.pdf",
            caption="../report/film_force.rst",
            category="The experiment's sensor",
            subcategory="The sensor film",
            labels={"artifact": "Contact force with and without the film", "format": "PDF"},
        ),
        png=report(
            "results/figures/film_force.png",
            caption="../report/film_force.rst",
            category="The experiment's sensor",
            subcategory="The sensor film",
            labels={"artifact": "Contact force with and without the film", "format": "PNG"},
        ),
        provenance="results/figures/film_force.provenance.json",
    log:
        "logs/figures/film_force.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.figure_artifacts:make_fig_film_force"),
        runs=FILM_FORCE_RUNS,
        rows=FILM_FORCE["rows"],
        variants=FILM_FORCE["variants"],
        methods=FILM_FORCE["methods"],
    script:
        "../scripts/artifact.py"


# Fig. 2, its numbers, Fig. 4 and the force's closed form, when the set 'model' is built.
default_target(
    lambda: (
        [
            *expand("results/figures/fig2_contact_force.{ext}", ext=["pdf", "png"]),
            *expand("results/figures/fig4_midrod_displacement.{ext}", ext=["pdf", "png"]),
            *expand("results/tables/fig2_comparison.{ext}", ext=["csv", "md", "provenance.json"]),
            *expand("results/figures/force_fit_model.{ext}", ext=["pdf", "png"]),
        ]
        if "model" in config["targets"]["sets"]
        else []
    )
)
