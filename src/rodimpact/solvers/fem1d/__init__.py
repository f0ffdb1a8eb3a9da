"""``fem1d``: the rod as a one-dimensional finite-element bar (scikit-fem), the impactor rigid.

What lives here: :mod:`.options` (the settings), :mod:`.bar` (mesh, mass and stiffness,
probes), :mod:`.cost` (the cost model: elements times steps) and :mod:`.solver`
(:func:`~rodimpact.solvers.fem1d.solver.solve_fem1d`).

What it may import: :mod:`rodimpact.contact`, :mod:`rodimpact.model`,
:mod:`rodimpact.analysis.signals`, the shared pieces of :mod:`rodimpact.solvers`, scikit-fem.
This ``__init__`` imports nothing.
"""
