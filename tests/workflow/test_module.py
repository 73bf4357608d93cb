"""The workflow imported by another one as a Snakemake ``module`` (issue 65): the
consumer's Snakefile is the README's (the shape ``snakedeploy deploy-workflow`` writes,
its ``config/`` folder a copy of ours), it asks for one figure, and every file it makes
is under its own folder: the imported checkout is the same, file by file, afterwards."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest
from conftest import CHECKOUT, ROOT, file_states, workdir
from tiny import TINY, TINY_READINGS

#: The consumer's Snakefile, as the README shows it (``{workflow}``: the imported
#: checkout's workflow/Snakefile).
CONSUMER = """\
configfile: "config/config.yaml"
module tennis:
    snakefile: "{workflow}"
    config: config
use rule * from tennis as tennis_*
"""


@pytest.mark.workflow
def test_a_consumer_workflow_imports_it_and_writes_only_its_own_folder(tmp_path):
    """Before: the import stopped with a traceback at common.smk, looking for the schema
    in the importing folder (workflow.basedir is the importing workflow's)."""
    module = tmp_path / "tennis"
    module.mkdir()
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")
    for name in CHECKOUT:
        if (ROOT / name).is_dir():
            shutil.copytree(ROOT / name, module / name, ignore=ignore)
        else:
            shutil.copy2(ROOT / name, module / name)
    before = file_states(module)
    consumer = workdir(tmp_path / "consumer", TINY, TINY_READINGS)
    (consumer / "workflow").mkdir()
    snakefile = consumer / "workflow" / "Snakefile"
    snakefile.write_text(CONSUMER.format(workflow=module / "workflow" / "Snakefile"))
    figure = "results/figures/fig04_omegas.png"
    command = [sys.executable, "-m", "snakemake", figure, "--cores", "2"]
    done = subprocess.run(command, cwd=consumer, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    assert (consumer / figure).stat().st_size > 0
    assert (consumer / "results" / "strokes" / "fig4.nc").stat().st_size > 0
    assert file_states(module) == before


def test_the_readme_shows_the_consumer_snakefile():
    """The README's consumer is the one tested here."""
    text = (ROOT / "README.md").read_text()
    assert CONSUMER.format(workflow="path/to/tennis-stroke/workflow/Snakefile") in text
