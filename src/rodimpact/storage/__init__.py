"""Storage: the files the workflow writes and reads back, and their provenance.

What lives here: :mod:`.runs` (one HDF5 file per run, or a file of runs: a sweep's part),
:mod:`.references` (how a run is named: its file, or ``file#name`` in a file of runs),
:mod:`.runcheck` (what a run file may hold), :mod:`.runfield` (its strain field),
:mod:`.casefile` (the case files), :mod:`.curves` (contact-law curves as HDF5), :mod:`.bands`
(prediction bands as HDF5), :mod:`.calibrations` (a set's calibration as HDF5), :mod:`.faults`
(an input a job cannot use, marked out of date:
:class:`~rodimpact.storage.faults.UnreadableInput` and
:class:`~rodimpact.storage.faults.StoredFileError`), :mod:`.atomic` (the one whole-or-nothing
writer), :mod:`.provenance` (hashes and versions) and :mod:`.sidecar` (the provenance sidecars
of tables, figures and benchmarks).

What it may import: its own modules, :mod:`rodimpact` (the version), h5py and numpy. Not
:mod:`rodimpact.config` (a sibling at the same layer), never a solver, scikit-fem or matplotlib.
"""
