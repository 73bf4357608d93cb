"""The earlier file of each output a run is about to make, kept beside it until its job
has made the new one.  Snakemake removes a job's outputs when it starts the job, and
its ``update()`` flag, which keeps them, copies them into ``.snakemake/backups``,
copies a failed job's back over the file and records the job as complete with the new
params, so that the old file looks up to date (snakemake/snakemake#3808; #1150).

:func:`keep` hard-links each existing output of the planned jobs to a hidden name in its
own folder (``results/x/.fig9.nc.earlier``): the same file system, nothing copied, and a
file system that refuses the link keeps nothing of that file, in one line.  At the end
of a run (:func:`settle`; the Snakefile's ``onsuccess`` and ``onerror``, and at the next
run's start after ``kill -9``) each kept file goes: the output is there and complete, or
the earlier file is renamed back over a missing or incomplete one (a rename: no space
needed, never a partial file), dated 1970 and without Snakemake's records of it, so the
next run plans its job again.  Only files of a run in progress (or killed) are kept:
``--delete-all-output`` after a run leaves nothing behind.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

#: The name an earlier file is kept under, in its output's folder.
PREFIX, SUFFIX = ".", ".earlier"
#: The folders of the workflow's outputs.
TOPS = ("results", "report")
#: The modification time (s since 1970) of a file put back: older than any input.
STALE_TIME = 0


def beside(path: str | Path) -> Path:
    """The name ``path``'s earlier file is kept under."""
    path = Path(path)
    return path.with_name(f"{PREFIX}{path.name}{SUFFIX}")


def keep(outputs) -> list[str]:
    """Link each existing file of ``outputs`` (the planned jobs' outputs) to
    :func:`beside` it; returns those kept.  A link refused (a file system without hard
    links, a full folder) keeps nothing of that file: one line names it."""
    kept = []
    for output in map(Path, map(str, outputs)):
        if not output.is_file() or output.is_symlink():
            continue
        try:
            beside(output).unlink(missing_ok=True)
            os.link(output, beside(output))
        except OSError as exc:
            sys.stderr.write(
                f"tennis-stroke warning: the earlier {output} is not kept while its job "
                f"runs ({exc.strerror or exc}): a failed job leaves none\n"
            )
            continue
        kept.append(str(output))
    return kept


def _incomplete(persistence, path: str) -> bool:
    """Whether Snakemake marks ``path`` incomplete (a job that started and did not end)."""
    from snakemake.io import IOFile

    return persistence._exists_record(persistence._incomplete_path, IOFile(path))


def settle(persistence, root: str | Path = ".") -> list[str]:
    """End every kept file under ``root``'s :data:`TOPS`: dropped where its output is
    there and complete, else renamed back over it, dated :data:`STALE_TIME`, with
    Snakemake's records of it (``persistence``: the workflow's) removed as ``snakemake
    --cleanup-metadata`` does.  Returns the outputs put back; a put-back that fails is
    one line, the earlier file left where it is kept."""
    from snakemake.io import IOFile

    back = []
    for top in TOPS:
        for kept in sorted((Path(root) / top).rglob(f"{PREFIX}*{SUFFIX}")):
            output = kept.with_name(kept.name[len(PREFIX) : -len(SUFFIX)])
            name = os.path.relpath(output, root)
            try:
                if output.exists() and not _incomplete(persistence, name):
                    kept.unlink()
                    continue
                os.replace(kept, output)
                os.utime(output, (STALE_TIME, STALE_TIME))
            except OSError as exc:
                sys.stderr.write(
                    f"tennis-stroke error: the earlier {name} cannot be put back "
                    f"({exc.strerror or exc}); it is kept as {kept}\n"
                )
                continue
            for _ in range(2):  # the incomplete marker first, where there is one, then the record
                persistence.cleanup_metadata(IOFile(name))
            back.append(name)
    return back
