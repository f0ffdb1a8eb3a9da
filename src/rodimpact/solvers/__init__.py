"""The solvers: one package per method, the registry that declares them, and what they share.

What lives here: :mod:`.registry` (:data:`~rodimpact.solvers.registry.METHODS`, each method
declared once), :mod:`.options` (how a setting is declared), :mod:`.stepping` (what every
time-stepping solver shares: the settings, the stop limits, the end test's window, the
histories a run records and the result built from them, with its energy balance), :mod:`.result` (the
:class:`~rodimpact.solvers.result.ImpactResult` every solver returns), :mod:`.field` (the
grid of the strain field over the rod, output ``strain_field``), :mod:`.gauge_series` (the
strain gauges' and the far end's datasets, outputs ``gauge_strain`` and
``far_end_velocity``), :mod:`.cost` (the
cost model's shared pieces), and the methods' packages :mod:`.sem` (``sem``,
``sem_paper``), :mod:`.fem1d` and :mod:`.fem_axi`.

What it may import: :mod:`rodimpact.contact`, :mod:`rodimpact.model`,
:mod:`rodimpact.analysis.signals`, numpy, scipy and scikit-fem; never the configuration,
the storage, the presentation or the workflow. This ``__init__`` imports nothing, so that
reading the registry loads no solver.
"""
