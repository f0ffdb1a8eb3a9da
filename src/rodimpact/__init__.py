"""rodimpact: axial impact of a rigid body with a spherical nose on an elastic rod.

Rebuilds Belyaev, Shurpatov & Ma (2018), "Determining the contact force of an axial
collision of an elastic rod with a rigid impactor", from configuration alone.

``rodimpact.__version__`` is read from the git tags (:mod:`rodimpact._version`) when first
asked for, so importing the package runs no git command.
"""

from typing import Any as _Any


def __getattr__(name: str) -> _Any:
    if name == "__version__":
        from rodimpact._version import version

        return version()
    raise AttributeError(f"module 'rodimpact' has no attribute {name!r}")
