"""Contact laws: the quasi-static force-approach law of the impactor's contact with the rod.

What lives here: the interface every law implements (:mod:`.law`), each law in its own
module (:mod:`.hertz`, :mod:`.film`, :mod:`.tabulated`), and the table of laws by name (:mod:`.laws`), which a case selects.

What it may import: numpy and scipy only. It is the lowest layer of the package: the
model, the solvers and everything above them use it; it uses none of them.
"""
