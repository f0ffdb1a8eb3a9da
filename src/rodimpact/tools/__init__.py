"""What people run by hand or from make, outside the rules.

What lives here: :mod:`.cli` (the ``rodimpact`` command), :mod:`.audit` (``make provenance``:
every artifact resolves to the config and code that made it), :mod:`.report_check` (``make
report-check``: the HTML report's first screen in headless Chromium), :mod:`.bench`,
:mod:`.bench_plan`, :mod:`.bench_scaling` and :mod:`.bench_planning` (``make bench``: the benchmarks
and what they run; the last, how long snakemake takes to plan the workflow),
:mod:`.bench_sweeps` (``make bench``: a large sweep's jobs, files and wall time on one core
and on two), :mod:`.build_stats` (``make bench``: the build's own timing), :mod:`.cost_share`
(``make bench``: how much of its cost model a solve takes, per method), :mod:`.compare_tables` (are two
builds' tables the same?), :mod:`.accuracy_cost` (what an accuracy costs each method),
:mod:`.sphere_flat` (``make sphere-flat``: the continuum's elastic-plastic sphere on a rigid flat
against the published finite-element fits), :mod:`.yielding_rod` (Table 2's balls on a yielding
rod: the continuum's law with memory, and the dynamic continuum against the SEM through it),
:mod:`.sensor_plastic` (``make sensor-plastic``: Table 2's sensor as built with its layers
yielding, beside the elastic sensor) and
:mod:`.synthetic_history` (a synthetic force
history, labelled as one, for the worked example of a comparison).

What it may import: everything below it (:mod:`rodimpact.plumbing`, :mod:`rodimpact.jobs` and
the layers under them). Nothing imports it but the workflow's scripts and .smk files, and the tests.
"""
