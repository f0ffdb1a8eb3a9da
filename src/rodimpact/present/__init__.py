"""Presentation: tables and figures, built from stored runs only (never from a solver).

What lives here: :mod:`.tables` (Table 2, the comparisons, the sweep table, and
:func:`~.tables.write_table`), :mod:`.columns` (every column's label, unit and rounding, read by
every table written for people), :mod:`.table_formats` (a table as HTML, LaTeX and Markdown, in
panels of chosen columns), :mod:`.table_views` (which columns each table shows), :mod:`.figures`
(Fig. 2, Fig. 4, the force's closed form), :mod:`.table2_figures` and :mod:`.table2_drawing` (the Table 2
figure: contact time against ball mass per reading of the rod; the figure assembled, what each panel
shows), :mod:`.film_tables` and :mod:`.film_figures` (the sensor
film: Table 2 with and without it, its prediction bands, the indentation curves, the contact
force), :mod:`.sensor_tables` and :mod:`.sensor_artifacts` (the sensor as built: its band from the
continuum), :mod:`.compare`, :mod:`.compare_figures` and
:mod:`.compare_artifacts` (any case set against its measurements: its table, its figure, a figure per
kind of measured record, a row per case), :mod:`.calibration_artifacts` and
:mod:`.calibration_figures` (a set's calibration: its tables and figure, labelled a fit, not a
prediction), :mod:`.study_figures` (error against run time, the
stability map), :mod:`.wave_figures`
(the strain over the rod against time: its figure and its artifact), :mod:`.forces` (each
run's contact force as CSV, and its closed form as JSON) and
:mod:`.artifacts` (one function per artifact of the workflow, gathered from :mod:`.table_artifacts`,
:mod:`.figure_artifacts` and :mod:`.study_artifacts`, which share :mod:`.artifact_common`).

What it may import: :mod:`rodimpact.storage` (to read runs, bands, curves and case files, and write
files), :mod:`rodimpact.analysis`, :mod:`rodimpact.solvers.registry` (labels, styles, order of the
methods), :mod:`rodimpact.contact.laws` (the law of a case, its words), :mod:`rodimpact.contact.stack`
(the layers of a case's film or stack), pandas
and matplotlib (headless). Never a solver.
"""
