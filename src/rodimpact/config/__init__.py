"""The configuration: config.yaml, the materials and the case files, read, checked and resolved
before any job.

What lives here: :mod:`.load` (read, check and resolve config.yaml, materials and case files:
:func:`~rodimpact.config.load.load_project`), :mod:`.builder` (the case files resolved into
checked cases, one file at a time), :mod:`.yamlfile` (reading one YAML document, aliases
bounded), :mod:`.schema` (JSON-schema checks and merging), :mod:`.project`
(:class:`~rodimpact.config.project.Project`, :class:`~rodimpact.config.project.ConfigError` and
:class:`~rodimpact.config.project.ConfigFile`, the file being read, which locates a problem in
it), :mod:`.bodies` (a case's materials and contact block), :mod:`.measured` (a case's measured
records and its gauges, found and checked), :mod:`.calibration` (a set's ``calibrate`` block,
checked against its cases), :mod:`.paths` (a setting of a resolved case named by its path),
:mod:`.checks` (each run's options against its case) and :mod:`.plausible` (each run's scales
and cost before any job).

What it may import: :mod:`rodimpact.solvers.registry`, :mod:`rodimpact.solvers.field` and the
options classes (the methods and their settings, never a solver), :mod:`rodimpact.analysis`
(sweeps and study cases), :mod:`rodimpact.model`, :mod:`rodimpact.contact.laws` (the laws'
names), :mod:`rodimpact.inputs` (every file read safely), jsonschema and PyYAML. Not
:mod:`rodimpact.storage` (a sibling at the same layer), not h5py, scikit-fem or matplotlib: the
configuration check runs when snakemake plans, and in every job.
"""
