# The config file read once before Snakemake reads it, so that a YAML syntax error is
# named with its file and line (Snakemake's own message gives neither).  Not when another
# workflow imports this one as a module with `config:` (Snakemake then skips the
# `configfile:` below, and the importing workflow read its own file).
import sys

from tennis_stroke.io.config_files import ConfigFileError, load_yaml

if not workflow.modifier.skip_configfile:
    try:
        load_yaml("config/config.yaml")
    except ConfigFileError as _exc:
        sys.stderr.write(f"tennis-stroke config error: {_exc}\n")
        sys.exit(1)
