"""The machinery around snakemake that the workflow's .smk files call while snakemake parses
them (each module says what snakemake does on its own, why that is not enough here, and which
test notices when snakemake's internals change).

What lives here: :mod:`.plan_cache` (the checked project and the jobs' estimates, kept between
snakemake runs), :mod:`.locks` (snakemake's lock left by a killed run, released),
:mod:`.targets` (command-line targets no rule makes) and :mod:`.sources` (the package files a
rule depends on, from the static import graph).

What it may import: everything below it (:mod:`rodimpact.jobs` and the layers under it); it uses
only :mod:`rodimpact.storage.atomic`. Not :mod:`rodimpact.tools`. Snakemake itself is never
imported here: the .smk files hand over what the modules read.
"""
