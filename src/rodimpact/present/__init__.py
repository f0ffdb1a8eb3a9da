"""Presentation: tables and figures, built from stored runs only (never from a solver).

What lives here: :mod:`.tables` (Table 2, the comparisons, the sweep table), :mod:`.figures`
(Fig. 2, Fig. 4, the Table 2 figure), :mod:`.study_figures` (error against run time, the
stability map) and :mod:`.artifacts` (one function per artifact of the workflow).

What it may import: :mod:`rodimpact.io` (to read runs and write files),
:mod:`rodimpact.analysis`, :mod:`rodimpact.solvers.registry` (labels, styles, order of the
methods), pandas and matplotlib (headless). Never a solver.
"""
