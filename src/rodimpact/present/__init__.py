"""Presentation: tables and figures, built from stored results only (never from a solver); the
words a reader sees are made here, from the numbers, ids and units the results hold.

What lives here:

- the table machinery: :mod:`.table` (a table declared once, :class:`~.table.Table`: its frame and
  a :class:`~.table.Column` for each column, its panels; every format written from it by
  pandas: CSV, Markdown, HTML, LaTeX), :mod:`.columns` (the columns many tables share, and the
  columns made per method, with the method's words);
- the tables, each declared once beside its frame, with the function its job calls:
  :mod:`.readings` (each reading of a set with variants, the paper's Table 2 for the paper's set,
  and the errors per reading), :mod:`.film_tables` (Table 2 with and without the sensor film, the
  film's bands, the indentation curves), :mod:`.sensor_tables` (the sensor as built: its band
  from the continuum; the bands' axes), :mod:`.sweep_table` (every sweep point),
  :mod:`.fig2_table` (Fig. 2 in numbers), :mod:`.compare` (any case set against its
  measurements, and its summary), :mod:`.calibration_tables` (a set's calibration, labelled a fit,
  not a prediction; its figure too), :mod:`.study_tables` (the orders of convergence, the stress
  cases);
- the figures: :mod:`.figures` (Fig. 2, Fig. 4, the force's closed form; saving a figure with its
  provenance), :mod:`.figure_artifacts` (the figures' jobs: the paper's model case, contact time
  against ball mass per reading, the contact force with and without the film),
  :mod:`.table2_figures` (the Table 2 figure: contact time against ball mass, a panel per reading
  of the rod), :mod:`.film_figures` (the contact force with and without the film),
  :mod:`.compare_figures` (a set against its measurements: its figure, a figure per kind of
  measured record), :mod:`.calibration_figures` (a calibration's figure), :mod:`.study_figures`
  (error against run time, the stability map), :mod:`.wave_figures` (the strain over the rod
  against time);
- :mod:`.forces` (each run's contact force as CSV, and its closed form as JSON), :mod:`.inputs`
  (what an artifact reads besides its table: runs' summaries, case files, the one case a figure
  shows) and :mod:`.words` (a case and a reading in words).

A presentation rule names the function its job calls (``module:function``) and its code digest
covers that module's imports only: a change here reruns the presentation jobs that import it,
never a solver, an indentation, a band or a calibration.

What it may import: :mod:`rodimpact.storage` (to read runs, bands, curves, calibrations and case
files, and write files), :mod:`rodimpact.analysis`, :mod:`rodimpact.model` (a case's impact on a
rigid wall, for a comparison's warnings), :mod:`rodimpact.solvers.registry` (labels, styles, order
of the methods), :mod:`rodimpact.contact.laws` (the law of a case, its words),
:mod:`rodimpact.contact.stack` (the layers of a case's film or stack), pandas (with jinja2 for its
Styler and tabulate for its Markdown) and matplotlib (headless). Never a solver.
"""
