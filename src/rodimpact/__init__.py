"""rodimpact: axial impact of a rigid body with a spherical nose on an elastic rod.

Rebuilds Belyaev, Shurpatov & Ma (2018), "Determining the contact force of an axial
collision of an elastic rod with a rigid impactor", from configuration alone.
"""

from importlib import metadata as _metadata
from pathlib import Path as _Path


def _version() -> str:
    """The version in pyproject.toml, its one place: read from the checkout this package lives
    in, else from the installed distribution's metadata."""
    pyproject = _Path(__file__).resolve().parents[2] / "pyproject.toml"
    if pyproject.is_file():
        import tomllib

        project = tomllib.loads(pyproject.read_text(encoding="utf-8")).get("project", {})
        if project.get("name") == "rodimpact" and "version" in project:
            return str(project["version"])
    try:
        return _metadata.version("rodimpact")
    except _metadata.PackageNotFoundError:
        return "0+unknown"


__version__ = _version()
