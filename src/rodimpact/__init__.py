"""rodimpact: axial impact of a rigid body with a spherical nose on an elastic rod.

Rebuilds Belyaev, Shurpatov & Ma (2018), "Determining the contact force of an axial
collision of an elastic rod with a rigid impactor", from configuration alone.

The layers, lowest first; a package imports its own modules and the layers below it, never
one above (``tests/test_architecture.py`` checks every import, and that this list is its own):

1. :mod:`rodimpact.settings` and :mod:`rodimpact.inputs` (siblings): options declared once, as
   dataclass fields with doc, unit, bounds; a user's files read safely (regular files only,
   bounded, decoded);
2. :mod:`rodimpact.contact`: the contact laws, one module each behind one interface;
3. :mod:`rodimpact.model`: the impact problem, the rod's and the impactor's responses;
4. :mod:`rodimpact.analysis`: signals, sweeps, convergence and comparisons of results;
5. :mod:`rodimpact.solvers`: the methods (SEM, FEM 1-D, the axisymmetric continuum) and their
   registry;
6. :mod:`rodimpact.config` and :mod:`rodimpact.storage` (siblings, neither imports the other):
   the configuration read and checked; results written and read (HDF5, provenance, atomically);
7. :mod:`rodimpact.present`: tables and figures, from stored results only;
8. :mod:`rodimpact.jobs`: what one workflow job does (a batch of runs, a band, a case file);
9. :mod:`rodimpact.plumbing`: what the Snakefile needs (source digests, a killed run's lock, targets);
10. :mod:`rodimpact.tools`: commands run by hand or by make (audit, benchmarks, checks).

``rodimpact.__version__`` is read from the git tags (:mod:`rodimpact._version`) when first
asked for, so importing the package runs no git command.
"""

from typing import Any as _Any


def __getattr__(name: str) -> _Any:
    if name == "__version__":
        from rodimpact._version import version

        return version()
    raise AttributeError(f"module 'rodimpact' has no attribute {name!r}")
