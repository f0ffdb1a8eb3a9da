"""The code that the workflow's rules run (through workflow/scripts/): one job's science and
its bookkeeping.

What lives here: :mod:`.runner` (solve one run and store it), :mod:`.batch` (several runs in
one job), :mod:`.band` (the film's prediction band, thin-layer law), :mod:`.sensor_band` (the
sensor stack's band by the law the continuum calibrates), :mod:`.indentation` (the continuum's
indentation as a contact-law curve), :mod:`.calibrate` (a set's declared constants fitted to its
measurements, with leave-one-out), :mod:`.calibration_model` (what a calibration fits: the set's
quantities run at its constants, or read between runs on a grid), :mod:`.cases` (the case files' contents),
:mod:`.resources` (threads, memory and time of a job, estimated from its case), :mod:`.parts` (a
sweep's runs cut into jobs of about a target cost), :mod:`.logs`
(the scripts' logging), :mod:`.timing` (how a timed run is repeated) and :mod:`.machine` (the
machine a timing ran on).

What it may import: everything below it (:mod:`rodimpact.present`, :mod:`rodimpact.config`,
:mod:`rodimpact.storage`, :mod:`rodimpact.solvers`, :mod:`rodimpact.analysis`,
:mod:`rodimpact.model`, :mod:`rodimpact.contact`). Not :mod:`rodimpact.plumbing` or
:mod:`rodimpact.tools`.
"""
