"""Reading and writing: the configuration, the run files, provenance.

What lives here: :mod:`.yamlfile` (reading one YAML document, aliases bounded),
:mod:`.schema` (JSON-schema checks), :mod:`.project`
(:class:`~rodimpact.io.project.Project` and :class:`~rodimpact.io.project.ConfigError`),
:mod:`.config` (read, check and resolve config.yaml, materials and case files),
:mod:`.checks` (each run's options against its case), :mod:`.store` (one HDF5 file per run),
:mod:`.runcheck` (what a run file may hold), :mod:`.runfield` (its strain field),
:mod:`.atomic` (the one whole-or-nothing writer), :mod:`.plausible` (each run's scales and cost
before any job), :mod:`.provenance` (hashes and versions)
and :mod:`.sidecar` (the provenance sidecars of tables, figures and benchmarks).

What it may import: :mod:`rodimpact.solvers.registry` and the options classes (the methods
and their settings, never a solver), :mod:`rodimpact.analysis` (sweeps and study cases),
:mod:`rodimpact.model`, h5py, jsonschema, PyYAML. Not scikit-fem, not matplotlib: the
configuration check runs in every workflow job.
"""
