"""Settings declared once: a dataclass field per setting, with its doc, unit and bounds.

What lives here: :mod:`.declare`: :func:`~rodimpact.settings.declare.setting` (the field
that declares one setting), :class:`~rodimpact.settings.declare.Setting` (the declaration),
:class:`~rodimpact.settings.declare.Settings` (the base of every block of settings: a
method's numerical options, a contact law's parameters, the strain field's grid), which
checks values, builds the block's JSON schema and converts it from and to plain mappings,
and :class:`~rodimpact.settings.declare.OptionError`, the error that names the setting at fault.

What it may import: the standard library only. It is the lowest layer: the contact laws, the
solvers and the configuration declare their settings with it.
"""
