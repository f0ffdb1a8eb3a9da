"""Contact laws: the quasi-static force-approach law of the impactor's contact with the rod.

What lives here: the interface every law implements, with the memory of a law that unloads on
another curve (its largest approach, its dent, the energy it dissipated), what a law declares of
itself (its name, label, settings, needs, methods and conflicts) and the check of a law's
positive arguments (:mod:`.law`), each law in its own module with its settings (:mod:`.hertz`,
:mod:`.film` (its rigid impact in :mod:`.film_impact`), :mod:`.stack` (a stack of bonded
layers, and the geometry every method reads of a film or stack), :mod:`.tabulated`,
:mod:`.spring` (a reference spring with closed forms), :mod:`.thornton` (Thornton's
elastic-perfectly-plastic sphere, a law with memory)), the table of laws by name with the
functions that read the declarations for the rest of the project (:mod:`.laws`), and the
published finite-element fits of an elastic-plastic sphere on a rigid flat that the continuum
is checked against (:mod:`.sphere_flat`).

What it may import: numpy, scipy and :mod:`rodimpact.settings` (how a setting is declared).
The model, the solvers and everything above them use it; it uses none of them.
"""
