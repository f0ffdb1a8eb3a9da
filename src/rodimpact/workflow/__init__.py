"""The workflow's plumbing: running a case, job resources, the sources a rule depends on,
logging, the provenance audit, the benchmarks.

What lives here: :mod:`.runner` (solve one run and store it), :mod:`.resources` (threads,
memory and time of a job), :mod:`.sources` (the package files a rule imports),
:mod:`.logs` (the scripts' logging), :mod:`.machine` (the machine a timing ran on),
:mod:`.audit` (``make provenance``) and :mod:`.bench` (``make bench``).

What it may import: everything below it (:mod:`rodimpact.io`, :mod:`rodimpact.solvers`,
:mod:`rodimpact.analysis`, :mod:`rodimpact.present`, :mod:`rodimpact.model`,
:mod:`rodimpact.contact`). Nothing imports it but the workflow's scripts and the tests.
"""
