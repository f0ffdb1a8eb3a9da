"""The workflow's plumbing: running a case, job resources, the sources a rule depends on,
logging, the provenance audit, the benchmarks.

What lives here: :mod:`.runner` (solve one run and store it), :mod:`.batch` (several runs in
one job), :mod:`.resources` (threads, memory and time of a job), :mod:`.plan_cache` (the
checked project and the jobs' estimates, kept between snakemake runs), :mod:`.sources` (the
package files a rule imports), :mod:`.logs` (the scripts' logging), :mod:`.machine` (the
machine a timing ran on), :mod:`.audit` (``make provenance``), :mod:`.bench` and
:mod:`.build_stats` (``make bench``: the benchmarks, and the build's own timing),
:mod:`.report_check` (``make report-check``: the HTML report's first screen in headless Chromium).

What it may import: everything below it (:mod:`rodimpact.io`, :mod:`rodimpact.solvers`,
:mod:`rodimpact.analysis`, :mod:`rodimpact.present`, :mod:`rodimpact.model`,
:mod:`rodimpact.contact`). Nothing imports it but the workflow's scripts and the tests.
"""
