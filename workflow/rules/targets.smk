# Targets given on the command line that no rule makes are refused here, in one line listing
# what the nearest folder holds, before any job is planned. At parse time snakemake has not yet
# set its targets, so they are read from the command line with snakemake's own parser: what
# snakemake does on its own, why that is not enough and which test notices a change of its
# internals are in rodimpact.plumbing.targets.
from rodimpact.plumbing.targets import command_line_targets, unknown_target_message, untargeted_set_message


def check_targets(targets):
    rules = list(workflow.rules)
    names = [r.name for r in rules]
    # the case sets the configuration declares but does not build, by the case file of each
    untargeted = {
        name: PROJECT.cases[ids[0]].get("source_file", "config/cases")
        for name, ids in PROJECT.sets.items()
        if ids and name not in config["targets"]["sets"]
    }
    for target in targets:
        if target in names or os.path.isfile(target) or any(r.is_producer(target) for r in rules):
            continue
        message = untargeted_set_message(target, untargeted, CONFIG_FILE)
        if message is not None:
            refuse(message)
        # a file of a batch: its rule writes the directory holding it, as a whole
        batch = next(
            (
                (str(parent), r.name)
                for parent in Path(target).parents
                if str(parent) not in (".", "")
                for r in rules
                if r.is_producer(str(parent))
            ),
            None,
        )
        refuse(unknown_target_message(target, [str(p) for r in rules for p in r.output], names, batch=batch))


check_targets(command_line_targets(sys.argv))
