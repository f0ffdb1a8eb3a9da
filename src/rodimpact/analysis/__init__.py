"""Analysis of histories and stored runs: features of a force history, and the studies.

What lives here: :mod:`.errors` (an error relative to a reference, signed: the one
definition), :mod:`.signals` (force maxima, the zig-zag of an unstable step),
:mod:`.studies` (the cases of the numerical studies: work-precision levels, stress
references, stability-map points), :mod:`.work_precision` (errors against run time and
observed orders), :mod:`.convergence` (an order fitted with its standard error, Roache's grid
convergence index), :mod:`.stability_study` (the stress runs' verdicts and the stability
map), :mod:`.sweeps` (parameter sweeps of a case), :mod:`.waves` (the paths of the wave fronts in the
rod, for its strain map), :mod:`.force_fit` (a closed form of a computed contact force),
:mod:`.measured` (a measured record's file, force, strain at a gauge or velocity, read and
checked), :mod:`.record_checks` (what a record can show of its case's impact: a pulse above its
noise, its sign, a pre-trigger, its size and timing), :mod:`.history_compare` (a computed force
against a measured one: alignment, error norms, contact times read at a threshold),
:mod:`.wave_compare` (a computed wave signal, a gauge's strain or a velocity, against a measured
one: its first pulse's arrival, peak and integral, error norms), :mod:`.observations` (every
measured quantity of a case against one run: what the comparison tables list and a calibration
fits), :mod:`.calibration` (declared constants fitted by bounded least squares, with standard
errors, correlations and identifiability), :mod:`.calibration_loo` (its leave-one-out: each
case held out, refitted without it, predicted) and :mod:`.records` (what the analyses
read of a stored run).

What it may import: :mod:`rodimpact.contact`, :mod:`rodimpact.model`, :mod:`rodimpact.inputs`
(a measured record read safely), numpy, scipy, pandas. Stored runs are read by duck typing
(any object with ``config``, ``summary``, ``series``), so nothing here imports the storage or
the solvers.
"""
