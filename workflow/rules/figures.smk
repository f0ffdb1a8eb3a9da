# Figures: read HDF5 runs only; rendered headless.


rule fig2:
    """Fig. 2: contact force against time for the case 'model', every method it runs."""
    input:
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
        code=SRC_PRESENT,
    output:
        pdf="results/figures/fig2_contact_force.pdf",
        png="results/figures/fig2_contact_force.png",
    log:
        "logs/figures/fig2_contact_force.log",
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
        pdf="results/figures/fig4_midrod_displacement.pdf",
        png="results/figures/fig4_midrod_displacement.png",
    params:
        fraction=0.5,
    log:
        "logs/figures/fig4_midrod_displacement.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig4.py"


rule fig_table2:
    """Contact time against ball mass: measured, published and ours, per geometry variant."""
    input:
        runs=[run for v in TABLE2_VARIANTS for run in table2_runs(v)],
        code=SRC_PRESENT,
    output:
        pdf="results/figures/table2_contact_time.pdf",
        png="results/figures/table2_contact_time.png",
    params:
        variants=TABLE2_VARIANTS,
    log:
        "logs/figures/table2_contact_time.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig_table2.py"
