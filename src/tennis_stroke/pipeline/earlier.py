"""A job's earlier output, kept beside it until the job has made the new one: Snakemake
removes a job's outputs when it starts it, and its ``update()`` flag copies them into
``.snakemake/backups``, back over the file after a failure, and then records the failed
job as complete with the new params (snakemake/snakemake#3808; #1150).

:func:`keep` hard-links each output to a hidden name in its own folder (one file system:
never a copy); :func:`settle`, when the run ends or the next one starts, drops it or
renames it back (no space needed, never a partial file) dated 1970 and unrecorded, so the
job runs again.  Nothing stays after a run: ``--delete-all-output`` frees every result.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

#: The name an earlier file is kept under, in its output's folder; the outputs' folders;
#: the modification time (s since 1970) of a file put back, older than any input.
PREFIX, SUFFIX, TOPS, STALE_TIME = ".", ".earlier", ("results", "report"), 0


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
