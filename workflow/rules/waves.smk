# The waves in the rod, drawn: for every case that lists the output strain_field, the axial
# strain over the whole rod against time, one panel per method that records it (the registry's
# records_field), on one colour scale, with the wave fronts' paths and the contacts marked
# (rodimpact.present.wave_figures). No other case pays for it: the rule's {case} takes only
# the cases asking for the field (WAVE_CASES, common.smk).


rule wave_map:
    """The axial strain over the rod against time, for one case that lists strain_field."""
    input:
        runs=run_batches(lambda w: field_runs(PROJECT.cases[w.case])),
    output:
        pdf=report(
            "results/figures/wave_map_{case}.pdf",
            caption="../report/wave_map.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="The waves in the rod",
            labels={"artifact": "Strain along the rod against time, {case}", "format": "PDF"},
        ),
        png=report(
            "results/figures/wave_map_{case}.png",
            caption="../report/wave_map.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="The waves in the rod",
            labels={"artifact": "Strain along the rod against time, {case}", "format": "PNG"},
        ),
        provenance="results/figures/wave_map_{case}.provenance.json",
    log:
        "logs/figures/wave_map_{case}.log",
    wildcard_constraints:
        case=one_of(WAVE_CASES),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.wave_figures:make_wave_map"),
        runs=lambda w: field_runs(PROJECT.cases[w.case]),
        field_grid=lambda w: PROJECT.cases[w.case]["field_grid"],  # for the caption
        far_end=lambda w: PROJECT.cases[w.case]["rod"]["far_end"],
    script:
        "../scripts/artifact.py"


# The strain map of every built case that lists strain_field.
default_target(
    lambda: expand(
        "results/figures/wave_map_{case}.{ext}",
        ext=["pdf", "png"],
        case=[c["id"] for s in config["targets"]["sets"] for c in PROJECT.cases_in(s) if c["id"] in WAVE_CASES],
    )
)
