"""The previous version of every result, kept until a run has made the new one.

Snakemake removes a job's outputs when it starts the job, so a job that failed or was
stopped took its earlier file with it: killing a runaway work-precision job deleted
``results/solver_study/work_precision.nc`` (issue 56).  Snakemake's ``update`` flag
keeps the file, but after a failure it copies the old file back and records it as made
with the new params: a result that would look up to date and is not.

So, before any job, the Snakefile links every file under ``results/`` and ``report/``
into :data:`KEPT` (:func:`keep`; hard links, nothing is copied: a job writes a new file,
never into the old one).  When the run fails, is interrupted or terminated (the
Snakefile's ``onerror``), every result that was there at planning and is missing now
is put back (:func:`restore`) dated 1970 (:data:`STALE_TIME`) and without Snakemake's
records of it (:func:`unrecord`), so that the next run plans its job again, while the
old file serves until the new one is complete.  After ``kill -9`` of Snakemake itself no
handler runs: the killed jobs' previous files stay in :data:`KEPT` until the next run's
planning.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

#: Where the previous results are kept, below the working directory.
KEPT = Path(".snakemake") / "tennis-stroke-kept"
#: The folders of the workflow's outputs.
TOPS = ("results", "report")
#: The modification time (s since 1970) of a result put back: older than any input.
STALE_TIME = 0


def _link(source: Path, target: Path) -> None:
    target.parent.mkdir(parents=True, exist_ok=True)
    try:
        os.link(source, target)
    except OSError:  # a file system without hard links
        shutil.copy2(source, target)


def keep(root: str | Path = ".") -> list[str]:
    """Link every file under ``root``'s ``results/`` and ``report/`` into :data:`KEPT`
    (replacing what was kept before); returns their paths relative to ``root``."""
    root = Path(root)
    kept, fresh = root / KEPT, root / KEPT.with_name(KEPT.name + ".new")
    shutil.rmtree(fresh, ignore_errors=True)
    paths = []
    for top in TOPS:
        for path in sorted((root / top).rglob("*")):
            if path.is_file() and not path.is_symlink():
                relative = path.relative_to(root)
                _link(path, fresh / relative)
                paths.append(str(relative))
    shutil.rmtree(kept, ignore_errors=True)
    if fresh.exists():
        fresh.rename(kept)
    return paths


def restore(paths: list[str], root: str | Path = ".") -> list[str]:
    """Put back each of ``paths`` (relative to ``root``) that is missing and kept, dated
    :data:`STALE_TIME`; returns those put back."""
    root = Path(root)
    back = []
    for relative in paths:
        target, source = root / relative, root / KEPT / relative
        if target.exists() or target.is_symlink() or not source.is_file():
            continue
        _link(source, target)
        os.utime(target, (STALE_TIME, STALE_TIME))
        back.append(relative)
    return back


def unrecord(persistence, paths: list[str]) -> None:
    """Remove Snakemake's records of ``paths`` (``persistence``: the workflow's), as
    ``snakemake --cleanup-metadata`` does: the incomplete marker of a stopped job, then
    the metadata (a failed job's names the new params and code).  A file put back then
    has no record, and Snakemake plans its job again."""
    from snakemake.io import IOFile

    for path in paths:
        for _ in range(2):  # the marker first, where there is one, then the metadata
            persistence.cleanup_metadata(IOFile(path))
