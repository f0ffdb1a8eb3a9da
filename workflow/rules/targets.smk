# Targets given on the command line that no rule makes are refused here, in one line listing
# what the nearest folder holds (rodimpact.plumbing.targets), before any job is planned. At
# parse time snakemake has not yet set its targets, so they are read from the command line
# with snakemake's own parser (a snakemake started otherwise, e.g. by its API, is not checked).
from rodimpact.plumbing.targets import unknown_target_message


def command_line_targets():
    """The targets of the ``snakemake`` command that parses this file ([] when unknown)."""
    program = Path(sys.argv[0])
    if program.name != "snakemake" and program.parts[-2:] != ("snakemake", "__main__.py"):
        return []
    from snakemake.cli import get_argument_parser

    try:
        known, _ = get_argument_parser().parse_known_args(sys.argv[1:])
    except (Exception, SystemExit):
        return []
    return list(known.targets or [])


def check_targets(targets):
    rules = list(workflow.rules)
    names = [r.name for r in rules]
    for target in targets:
        if target in names or os.path.exists(target) or any(r.is_producer(target) for r in rules):
            continue
        refuse(unknown_target_message(target, [str(p) for r in rules for p in r.output], names))


check_targets(command_line_targets())
