"""The semi-analytical method (SEM): contact law + impulse responses + Volterra equation.

What lives here: :mod:`.options` (``sem``'s and ``sem_paper``'s settings), :mod:`.stability`
(the paper scheme's step limit and the implicit scheme's step choice), :mod:`.history` (the
force history and the rod's exact response to it), :mod:`.roots` (Brent's root finder for
the end of a contact), :mod:`.grid` (steps commensurate with the wave round trip), :mod:`.cost`
(the cost model), :mod:`.stepper` (one run at a fixed step: its state, the two schemes' steps,
every node of the implicit one made by one method), :mod:`.record` (the histories a run
stores besides its force and motions, and their continuation after a completed run for the
gauges and the far end's velocity) and :mod:`.solver`
(:func:`~rodimpact.solvers.sem.solver.solve_sem`, the driver).

What it may import: :mod:`rodimpact.contact`, :mod:`rodimpact.model`,
:mod:`rodimpact.analysis.signals` and the shared pieces of :mod:`rodimpact.solvers`. This
``__init__`` imports nothing, so that reading the options does not load the solver.
"""
