"""Snakemake adapter of every presentation rule: its job calls the function the rule names
(``params.make``, ``module:function`` in rodimpact.present), passing by name each of the rule's
params, named inputs and named outputs the function takes (a param it does not take is there
only to rerun the job when it changes), and ``threads``, the job's cores, to one that reads its
runs in parallel. A function that returns a table
(:class:`rodimpact.present.table.TableArtifact`) has it written to the rule's outputs; one that
returns nothing wrote its own."""

import inspect
from importlib import import_module

from rodimpact.jobs.logs import script_logging
from rodimpact.present.table import write_artifact

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    module, _, name = snakemake.params.make.partition(":")
    make = getattr(import_module(module), name)
    takes = inspect.signature(make).parameters
    outputs = dict(snakemake.output.items())
    given = {**dict(snakemake.input.items()), **dict(snakemake.params.items()), **outputs}
    given["threads"] = snakemake.threads  # the cores snakemake gave the job, for a function that reads in parallel
    made = make(**{key: value for key, value in given.items() if key in takes})
    if made is not None:
        write_artifact(made, **outputs)
