"""The physical model shared by every method: materials, the rod's responses, the problem.

What lives here: :mod:`.materials` (isotropic materials, elastic or yielding), :mod:`.responses` (the
rod's and the rigid impactor's responses to a force at the contact point, d'Alembert),
:mod:`.problem` (:class:`~rodimpact.model.problem.ImpactProblem`, the impact of a case as
the one-dimensional methods see it, with its contact law and its time scales), and
:mod:`.gauges` (:class:`~rodimpact.model.gauges.Gauge`, a strain gauge on the rod: its
station and length).

What it may import: numpy, scipy, :mod:`rodimpact.contact` and :mod:`rodimpact.settings` (what
a material's constants must satisfy). Nothing numerical (no step,
no mesh) and nothing of the workflow lives here.
"""
