"""Numerical options, declared once: a dataclass field per setting, with its doc, unit and bounds.

Each method's options class (a frozen dataclass deriving from :class:`Options`) declares its
settings with :func:`~rodimpact.settings.declare.setting`, the helper every block of settings
uses (the contact laws' too). Everything else is read from those declarations
(:class:`~rodimpact.settings.declare.Settings`):

- the check of every value (``__post_init__``, :class:`OptionError` naming the setting);
- the JSON schema of the method's block in ``config.yaml``'s ``numerics`` and in a case's
  overrides (:meth:`Options.json_schema`; :mod:`rodimpact.config.load` injects it), with the
  defaults the configuration is filled with;
- the list of a method's settings (:meth:`Options.names`) and the conversion of a resolved
  mapping into options (:meth:`Options.from_settings`).

What a method adds to a block of settings: :meth:`Options.check`, the checks that need the case.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rodimpact.settings.declare import OptionError, Setting, Settings, setting

__all__ = ["OptionError", "Options", "Setting", "setting"]


@dataclass(frozen=True)
class Options(Settings):
    """Base of every method's options: settings declared with :func:`setting`, checked on creation."""

    def check(self, problem: Any) -> None:
        """Checks that need the case (e.g. a stability limit); raise :class:`OptionError`.

        The base class has none.
        """
