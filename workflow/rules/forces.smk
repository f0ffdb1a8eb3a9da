# The contact force handed on (rodimpact.present.forces): for every run of the target sets'
# cases, P(t) as CSV under its provenance, and a Chebyshev closed form with its measured error,
# in results/forces/{set}/{case}/{method}.{csv,json}. Reading a run and fitting it takes a
# fraction of a second, so one job exports a whole case set (its directory), with one
# provenance sidecar. The closed form drawn over the force of the case 'model' is drawn by the job
# that draws its other figures (figures.smk, rule paper_model: results/figures/force_fit_model.*).


rule forces:
    """Every run of one case set: its contact force as CSV and its closed form as JSON, in the set's
    directory results/forces/{set}/{case}/{method}.{csv,json}, with one provenance sidecar."""
    input:
        runs=run_batches(lambda w: runs_of(PROJECT.cases_in(w.set))),
    output:
        directory=directory("results/forces/{set}"),
        provenance="results/forces/{set}.provenance.json",
    log:
        "logs/forces/{set}.log",
    wildcard_constraints:
        set=one_of(config["targets"]["sets"]),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.forces:export_forces_into"),
        runs=lambda w: runs_of(PROJECT.cases_in(w.set)),
        names=lambda w: [f"{c['id']}/{m}" for c in PROJECT.cases_in(w.set) for m in c["methods"]],
    script:
        "../scripts/artifact.py"


# The contact force handed on, per built set.
default_target(
    lambda: [f"results/forces/{s}{ending}" for s in config["targets"]["sets"] for ending in ("", ".provenance.json")]
)
