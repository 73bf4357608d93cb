"""How many processes a test run starts, by kind: a pytest plugin that records the
command of every ``subprocess.Popen`` a test process starts (fixtures included, in the
first test that uses them), and a summary of its records.

Usage (docs/testing.md)::

    PYTHONPATH=tools make test PYTEST_ADDOPTS="-p process_count"
    .venv/bin/python tools/process_count.py            # the summary

Each xdist worker appends to ``process-count-WORKER.jsonl`` in the folder named by
``PROCESS_COUNT_DIR`` (default: the system's temporary folder; remove old records first).
Counted: the processes the test processes start themselves; a process they start may
start more (a ``tennis-stroke whatif`` its Snakemake, a SLURM job its own), which are
not.  Wrapping ``Popen.__init__`` costs microseconds a process.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

FOLDER = Path(os.environ.get("PROCESS_COUNT_DIR", tempfile.gettempdir()))
#: What a command is, by the first pattern it matches.
KINDS = (
    ("snakemake", r"/snakemake(\s|$)"),
    ("dry-run batches (tests/dry_runs.py)", r"dry_runs\.py"),
    ("tennis-stroke whatif", r"whatif"),
    ("other Python", r"python"),
    ("other", r""),
)
_started: list[str] = []


def _command(args) -> str:
    return args if isinstance(args, str) else " ".join(map(str, args))


def pytest_configure(config):
    original = subprocess.Popen.__init__

    def counted(self, args, *rest, **kwargs):
        _started.append(_command(args))
        return original(self, args, *rest, **kwargs)

    subprocess.Popen.__init__ = counted


def pytest_runtest_logfinish(nodeid, location):
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    with open(FOLDER / f"process-count-{worker}.jsonl", "a") as out:
        out.write(json.dumps({"test": nodeid, "commands": _started}) + "\n")
    _started.clear()


def summary(folder: Path = FOLDER) -> Counter:
    """The commands of every record under ``folder`` counted by :data:`KINDS`."""
    counts: Counter = Counter()
    for path in sorted(folder.glob("process-count-*.jsonl")):
        for line in path.read_text().splitlines():
            for command in json.loads(line)["commands"]:
                counts[next(k for k, pattern in KINDS if re.search(pattern, command))] += 1
    return counts


if __name__ == "__main__":
    counts = summary()
    if not counts:
        sys.exit(f"process_count: no records in {FOLDER}")
    for kind, _ in KINDS:
        print(f"{kind}: {counts[kind]}")
