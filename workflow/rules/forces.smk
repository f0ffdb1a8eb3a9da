# The contact force handed on (rodimpact.present.forces): for every run of the target sets'
# cases, P(t) as CSV under its provenance, and a Chebyshev closed form with its measured error,
# in results/forces/{case}/{method}.{csv,json}. Reading a run and fitting it takes a fraction of
# a second, so one job exports a whole case set (rule forces_<set>), with one provenance
# sidecar. The closed form drawn over the force: results/figures/force_fit_model.{pdf,png}.
SRC_FORCES = sources("rodimpact.present.forces", "rodimpact.jobs.logs")


for set_name in config["targets"]["sets"]:

    rule:
        """Every run of one case set: its contact force as CSV and its closed form as JSON."""
        name:
            f"forces_{rule_name(set_name)}"
        input:
            runs=run_batches(runs_of(PROJECT.cases_in(set_name))),
        output:
            csvs=force_files(PROJECT.cases_in(set_name), "csv"),
            jsons=force_files(PROJECT.cases_in(set_name), "json"),
            provenance=f"results/forces/{set_name}.provenance.json",
        params:
            code=SRC_FORCES,
            runs=runs_of(PROJECT.cases_in(set_name)),
        log:
            f"logs/forces/{set_name}.log",
        group: GROUP_TABLES
        threads: 1
        resources:
            **PRESENTATION_RESOURCES,
        conda:
            "../envs/rodimpact.yaml"
        script:
            "../scripts/force_export.py"


rule fig_force_fit:
    """The closed form of the contact force over the computed force, case 'model', every method."""
    input:
        runs=run_batches(lambda w: runs_of([PROJECT.cases["model"]])),
        jsons=lambda w: force_files([PROJECT.cases["model"]], "json"),
    output:
        pdf=report(
            "results/figures/force_fit_model.pdf",
            caption="../report/force_fit.rst",
            category="The force handed on",
            labels={"artifact": "Contact force and its closed form", "format": "PDF"},
        ),
        png=report(
            "results/figures/force_fit_model.png",
            caption="../report/force_fit.rst",
            category="The force handed on",
            labels={"artifact": "Contact force and its closed form", "format": "PNG"},
        ),
        provenance="results/figures/force_fit_model.provenance.json",
    params:
        code=SRC_PRESENT,
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
    log:
        "logs/figures/force_fit_model.log",
    group: GROUP_TABLES
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig_force_fit.py"
