# rodimpact: rebuild Belyaev, Shurpatov & Ma (2018) from configuration alone.
#   snakemake -j2                       the whole paper (the sets in config.yaml: targets)
#   snakemake -j2 results/tables/table2_r1_l30.csv   only what that table needs
#   snakemake -j2 results/tables/stability.csv       one study (also work_precision.csv)
from snakemake.utils import min_version

min_version("9.0")


include: "workflow/rules/preflight.smk"


configfile: CONFIG_FILE


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/common_readings.smk"
include: "workflow/rules/common_studies.smk"
include: "workflow/rules/common_batches.smk"
include: "workflow/rules/common_sensor.smk"
include: "workflow/rules/common_compare.smk"
include: "workflow/rules/resources.smk"
include: "workflow/rules/cases.smk"
include: "workflow/rules/indentation.smk"
include: "workflow/rules/sensor.smk"
include: "workflow/rules/solve.smk"
include: "workflow/rules/tables.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/studies.smk"
include: "workflow/rules/sweeps.smk"
include: "workflow/rules/bench.smk"
include: "workflow/rules/forces.smk"
include: "workflow/rules/waves.smk"
include: "workflow/rules/compare.smk"
include: "workflow/rules/calibrate.smk"


rule all:
    default_target: True
    input:
        default_targets(),


# last: it checks the command line's targets against every rule above
include: "workflow/rules/targets.smk"
