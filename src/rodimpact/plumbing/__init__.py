"""The machinery around snakemake that the workflow's .smk files call while snakemake parses
them. :mod:`.locks` and :mod:`.targets` each open with what snakemake does on its own, why that
is not enough here, and which test fails when snakemake's internals change (the .smk blocks that
call ``sys.exit`` and set ``sys.path`` say the same in their comments).

What lives here: :mod:`.locks` (snakemake's lock left by a killed run, released),
:mod:`.targets` (command-line targets no rule makes, read with snakemake's own argument parser)
and :mod:`.sources` (the package files a rule runs, from the static import graph, and their digest).

What it may import: everything below it (:mod:`rodimpact.jobs` and the layers under it; it uses
only :mod:`rodimpact.storage.atomic` and :mod:`rodimpact.inputs.files`), and snakemake's command-line parser, inside
:func:`~rodimpact.plumbing.targets.command_line_targets` only. Not :mod:`rodimpact.tools`.
"""
