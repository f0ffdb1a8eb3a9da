# Every set of targets.sets whose case file declares `calibrate:` (docs/calibration.md): its
# constants fitted to its measurements by the block's method, with leave-one-out, in one job that
# writes results/calibration/{set}.h5; then its tables and figure, labelled a fit, not a
# prediction, from that file only. The records are inputs: a changed record refits.


rule calibrate:
    """One set's declared constants fitted to its measurements, each case held out in turn, and
    the cases of its apply_to predicted at the fitted constants."""
    input:
        case=lambda w: sorted({case_file_of(c["id"]) for c in calibration_cases_of(w.set)}),
        records=lambda w: compare_histories(w.set),
        # the curves the cases' own runs take: read at the cases' own constants, not recomputed
        curves=lambda w: sorted({os.path.dirname(f) for f in calibration_curves(w.set).values()}),
    output:
        h5="results/calibration/{set}.h5",
    log:
        "logs/calibration/{set}.log",
    wildcard_constraints:
        set=one_of(CALIBRATED_SETS),
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **calibration_resources(),
    params:
        code=calibration_sources,
        set_name="{set}",
        cases=lambda w: calibration_cases_of(w.set),
        block=lambda w: PROJECT.calibrate[w.set],
        numerics=config["numerics"],
        curves=lambda w: calibration_curves(w.set),
    script:
        "../scripts/calibrate.py"


rule calibration_artifacts:
    """One set's calibration as tables (per measurement, per constant) and a figure; one job, as
    both read the same file."""
    input:
        calibration="results/calibration/{set}.h5",
    output:
        csv=report(
            "results/tables/calibration_{set}.csv",
            caption="../report/calibration.rst",
            category="Calibration (a fit, not a prediction)",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Fitted constants and held-out predictions", "format": "CSV"},
        ),
        parameters_csv="results/tables/calibration_{set}_parameters.csv",
        md="results/tables/calibration_{set}.md",
        html="results/tables/calibration_{set}.html",
        pdf=report(
            "results/figures/calibration_{set}.pdf",
            caption="../report/calibration_figure.rst",
            category="Calibration (a fit, not a prediction)",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Errors, fitted and held out; the constants", "format": "PDF"},
        ),
        png=report(
            "results/figures/calibration_{set}.png",
            caption="../report/calibration_figure.rst",
            category="Calibration (a fit, not a prediction)",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Errors, fitted and held out; the constants", "format": "PNG"},
        ),
        provenance="results/tables/calibration_{set}.provenance.json",
    log:
        "logs/tables/calibration_{set}.log",
    wildcard_constraints:
        set=one_of(CALIBRATED_SETS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.calibration_tables:make_calibration_artifacts"),
        title=lambda w: PROJECT.calibrate[w.set].get("title", f"the constants of {set_title(w.set)}"),
    script:
        "../scripts/artifact.py"


default_target(calibration_targets)
