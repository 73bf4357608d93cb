"""Result files: xarray datasets with CF attributes and provenance, written atomically
(the YAML files are read by :mod:`tennis_stroke.io.config_files`).

Every variable and coordinate gets ``units`` and ``long_name`` from one table
(:data:`tennis_stroke.io.units.VARIABLES`).  Global attributes record the resolved
parameters, the readings, the solver settings, the package version and the git commit.
Files are written under a temporary name and renamed, so a final name never holds a
truncated file.  A temporary's name says which process writes it (host and process id),
so that the next write of the same file removes the temporaries whose writer is gone (a
``kill -9`` mid-write), never a live writer's (:func:`remove_stale_temporaries`).
"""

from __future__ import annotations

import errno
import json
import os
import platform
import re
import socket
import subprocess
import tempfile
import time
from collections.abc import Mapping
from datetime import UTC, datetime
from functools import cache
from importlib.metadata import version
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._version import __version__
from ..model.params import MODEL_OPTIONS, PARAMETERS, READINGS, scalar_params
from ..solver.results import FILE_NAMES, STATUS_NAMES
from ..solver.settings import SolverSettings
from .environment import environment_attrs
from .errors import OutputError, ProvenanceError, ResultError
from .interrupts import deferred_signals
from .units import VARIABLES, cf_attrs

if TYPE_CHECKING:  # imported where a dataset is made or read: the planning needs none
    import xarray as xr

#: Global attributes that differ between two runs of the same job, and only those: when
#: the file was written, and wall-clock timings (of the job, of a map's chunks, of the
#: model ladder's two models).  Variables holding wall-clock measurements carry a
#: ``timing`` attribute instead.
RUN_ATTRS = (
    "history",
    "wall_time_s",
    "chunk_wall_times_s",
    "us_per_stroke_spring",
    "us_per_stroke_impact",
)


@cache
def installed_version(package: str) -> str:
    """The installed version of ``package`` (read once per process)."""
    return version(package)


#: The files of a checkout the paper's jobs read (their code, configuration, workflow and
#: environment): uncommitted changes to them, and only to them, mark a commit ``-dirty``
#: (a scenario declared in ``config/scenarios.yaml``, a doc or a test changes no job).
JOB_INPUTS = (
    "src",
    "workflow",
    "config/config.yaml",
    "config/claims.yaml",
    "config/readings.yaml",
    "pyproject.toml",
    "requirements.lock",
)


@cache
def git_commit() -> str:
    """Commit of the source tree this package runs from (read once per process: a job's
    files all carry the commit it started from), with ``-dirty`` if a file of
    :data:`JOB_INPUTS` has uncommitted changes; outside a git checkout the commit an
    installed copy records, else ``"unknown"``.  A checkout git refuses to read (another
    user's) raises :class:`~tennis_stroke.io.errors.ProvenanceError`
    (:func:`commit_of`)."""
    return commit_of(Path(__file__).parent)


#: What git says when it refuses a repository whose owner is not the user running it
#: (git >= 2.36: "detected dubious ownership"; 2.35.2-2.35.x: "unsafe repository").
_NOT_OWNED = ("dubious ownership", "unsafe repository")


def commit_of(folder: Path) -> str:
    """:func:`git_commit` of the checkout holding ``folder``.

    Raises
    ------
    ProvenanceError
        The folder is in a git checkout that git refuses to read because another user
        owns it (a CI container running as root over the runner's checkout): its files
        would record no commit, so none is written; the message names the fix.
    """
    try:
        out = subprocess.run(
            ["git", "rev-parse", "HEAD"],
            cwd=folder,
            capture_output=True,
            text=True,
            timeout=5,
            check=True,
        )
        dirty = subprocess.run(
            [
                *["git", "status", "--porcelain", "--untracked-files=no", "--"],
                *(f":(top){path}" for path in JOB_INPUTS),
            ],
            cwd=folder,
            capture_output=True,
            text=True,
            timeout=5,
            check=True,
        )
    except subprocess.CalledProcessError as exc:
        said = " ".join(str(exc.stderr or "").split())
        if any(words in said for words in _NOT_OWNED):
            raise ProvenanceError(
                f"no result written: it would not record its commit, since git refuses the "
                f"checkout of {folder} owned by another user ({said}; or run as its owner)"
            ) from None
        return installed_commit()
    except (OSError, subprocess.SubprocessError):
        return installed_commit()
    return out.stdout.strip() + ("-dirty" if dirty.stdout.strip() else "")


def installed_commit() -> str:
    """The commit an installed (non-editable) copy was built from, where pip recorded it
    (``pip install git+URL@REV``: PEP 610's ``direct_url.json``), else ``"unknown"``; the
    version is in the ``source`` attribute either way."""
    import importlib.metadata

    try:
        text = importlib.metadata.distribution("tennis-stroke").read_text("direct_url.json")
        commit = json.loads(text or "{}").get("vcs_info", {}).get("commit_id")
    except (importlib.metadata.PackageNotFoundError, ValueError, AttributeError):
        commit = None
    return f"{commit} (installed)" if commit else "unknown"


def provenance(
    params: Mapping[str, object], settings: SolverSettings | Mapping[str, object]
) -> dict[str, object]:
    """Global attributes: parameters (``param_*`` with units), readings, solver, versions.
    ``settings``: the compiled solver's, or the options of another path as a mapping
    (:attr:`tennis_stroke.solver.reference.ReferenceStroke.solver`)."""
    import xarray as xr

    attrs: dict[str, object] = {
        "Conventions": "CF-1.10",
        "title": "Youn double-pendulum tennis stroke with ball collision",
        "source": f"tennis-stroke {__version__}",
        "tennis_stroke_version": __version__,
        "git_commit": git_commit(),
        "python_version": platform.python_version(),
        "numpy_version": np.__version__,
        # From the installed metadata: a figure or claims job does not import numba.
        "numba_version": installed_version("numba"),
        "scipy_version": installed_version("scipy"),
        "xarray_version": xr.__version__,
        "history": f"{datetime.now(UTC).isoformat(timespec='seconds')} written by tennis-stroke",
        **environment_attrs(),
    }
    for name, value in scalar_params(params).items():
        if name in READINGS:
            attrs[f"reading_{name}"] = str(value)
        elif name in MODEL_OPTIONS:
            attrs[f"option_{name}"] = str(value)
        else:
            attrs[f"param_{name}"] = float(value)
            attrs[f"param_{name}_units"] = PARAMETERS[name].unit
    options = settings if isinstance(settings, Mapping) else settings.as_dict()
    for name, value in options.items():
        attrs[f"solver_{name}"] = value
    return attrs


def result_dataset(
    results: Mapping[str, np.ndarray],
    coords: Mapping[str, np.ndarray],
    params: Mapping[str, object],
    settings: SolverSettings | Mapping[str, object],
    extra_attrs: Mapping[str, object] | None = None,
) -> xr.Dataset:
    """A dataset of stroke results on named grid axes, with CF metadata and provenance.

    Parameters
    ----------
    results : mapping of str to ndarray
        Result fields (:data:`RESULT_FIELDS`) shaped like the grid.
    coords : mapping of str to 1-D ndarray
        Grid axes in order, each named in :data:`tennis_stroke.io.units.VARIABLES`.
    params : mapping
        Resolved parameters (scalars become attributes).
    settings : SolverSettings or mapping
        The solver's settings (:func:`provenance`).
    extra_attrs : mapping, optional
        More global attributes (e.g. wall time).
    """
    import xarray as xr

    dims = list(coords)
    coord_vars = {}
    for name, values in coords.items():
        coord_vars[name] = (name, np.asarray(values, dtype=float), cf_attrs(name))
    data_vars = {}
    for field, values in results.items():
        attrs = cf_attrs(FILE_NAMES.get(field, field))
        if field == "status":
            attrs["flag_values"] = np.array(sorted(STATUS_NAMES), dtype=np.int64)
            attrs["flag_meanings"] = " ".join(STATUS_NAMES[k] for k in sorted(STATUS_NAMES))
        data_vars[FILE_NAMES.get(field, field)] = (dims, np.asarray(values), attrs)
    ds = xr.Dataset(data_vars, coords=coord_vars)
    ds.attrs.update(provenance(params, settings))
    ds.attrs.update(extra_attrs or {})
    return ds


def relabelled(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with ``units`` and ``long_name`` of every variable and coordinate named in
    the table (:data:`tennis_stroke.io.units.VARIABLES`) written again from it (the other
    attributes kept): a map gathered from its chunks carries today's labels, so a new
    long name reruns no chunk."""
    for name in [*ds.data_vars, *ds.coords]:
        if name in VARIABLES:
            units, long_name = VARIABLES[name]
            ds[name].attrs.update(units=units, long_name=long_name)
    return ds


def labelled(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with ``units`` and ``long_name`` on every variable and coordinate: those
    without get units ``"1"`` (labels, counts, values in a per-row unit named beside
    them) and their own name as long name."""
    for name in [*ds.data_vars, *ds.coords]:
        ds[name].attrs.setdefault("units", "1")
        ds[name].attrs.setdefault("long_name", name)
    return ds


def _umask() -> int:
    """The process's umask (read without changing it where ``/proc`` tells it)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)  # the only portable way to read it: set and restore at once
    os.umask(mask)
    return mask


def read_only(path: Path) -> bool:
    """Whether the existing file ``path`` is one its owner or this process may not write
    (its owner's write bit is off: refused even to root, who may write anything)."""
    return not (os.access(path, os.W_OK) and path.stat().st_mode & 0o200)


def _host() -> str:
    """This machine's name as a temporary's name holds it (at most 32 characters)."""
    return re.sub(r"[^A-Za-z0-9.-]", "-", socket.gethostname())[:32] or "host"


def _temporary_name(path: Path) -> re.Pattern:
    """The names of ``path``'s temporaries (:func:`temporary_beside`): ``.NAME.HOST.PID.``
    then ``mkstemp``'s eight characters and ``.tmp``; ``HOST.PID.`` absent in those of
    the earlier writer (before 2026-12-08)."""
    start = re.escape(f".{path.name[:64]}.")
    return re.compile(start + r"(?:(?P<host>[A-Za-z0-9.-]+)\.(?P<pid>\d+)\.)?[a-z0-9_]{8}\.tmp")


def _running(pid: int) -> bool:
    """Whether process ``pid`` of this machine exists (another user's too)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # PermissionError: it exists, another user's
        return True
    return True


#: How old a temporary without its writer's name (the earlier writer's) must be to be
#: taken as stale: no write of a result lasts a day.
STALE_UNNAMED_SECONDS = 24 * 3600


def remove_stale_temporaries(path: Path) -> list[Path]:
    """Remove the temporaries of ``path`` (beside it) whose writer is gone: written on this
    machine by a process that no longer runs, or, without a writer's name, older than
    :data:`STALE_UNNAMED_SECONDS`.  A live writer's temporary (a concurrent write of the
    same file) and another machine's (a shared folder) are kept.  Returns those
    removed; a temporary that cannot be removed is left."""
    pattern, host, removed = _temporary_name(path), _host(), []
    try:
        names = os.listdir(path.parent)
    except OSError:
        return removed
    for name in names:
        match = pattern.fullmatch(name)
        if match is None:
            continue
        tmp = path.parent / name
        try:
            if match["pid"] is None:
                stale = time.time() - tmp.lstat().st_mtime > STALE_UNNAMED_SECONDS
            else:
                pid = int(match["pid"])
                stale = match["host"] == host and pid != os.getpid() and not _running(pid)
            if stale:
                tmp.unlink()
                removed.append(tmp)
        except OSError:  # gone meanwhile (another writer removed it), or not ours to remove
            continue
    return removed


def temporary_beside(path: Path) -> Path:
    """An empty new file in ``path``'s folder, to be renamed to ``path``: with the mode of
    ``path`` where it is a file (a replaced file keeps its mode), else the permissions any
    new file gets under the umask (``mkstemp`` would give 0600).  Its name holds this
    machine's name and this process's id; ``path``'s stale temporaries are removed first
    (:func:`remove_stale_temporaries`)."""
    # a short prefix: the temporary name is never longer than a name the folder takes
    mode = path.stat().st_mode & 0o7777 if path.is_file() else 0o666 & ~_umask()
    remove_stale_temporaries(path)
    prefix = f".{path.name[:64]}.{_host()}.{os.getpid()}."
    fd, tmp = tempfile.mkstemp(prefix=prefix, suffix=".tmp", dir=path.parent)
    try:
        os.fchmod(fd, mode)
    finally:
        os.close(fd)
    return Path(tmp)


def check_writable(path: str | os.PathLike) -> Path:
    """Fail early (:class:`OutputError`) if ``path`` cannot be created; return the path to
    write (a symbolic link's target: the link stays a link).  A path that exists must be a
    regular file, never a device or a pipe, and writable (a read-only file is the user's
    way to keep it).

    Creates and removes a temporary file beside ``path``: the only reliable test.
    """
    path = Path(path)
    if path.is_symlink():  # write where the link points (the rename replaces the target)
        path = path.resolve()
    parent = path.parent
    if path.is_dir():
        raise OutputError(f"output path {str(path)!r} is a directory")
    if path.exists() and not path.is_file():
        raise OutputError(f"output path {str(path)!r} is not a regular file (a device, a pipe)")
    if path.is_file() and read_only(path):
        raise OutputError(f"output path {str(path)!r} is read-only (make it writable to write it)")
    file = next((p for p in (parent, *parent.parents) if p.exists() and not p.is_dir()), None)
    if file is not None:
        raise OutputError(f"output directory {str(file)!r} is a file, not a directory")
    if not parent.is_dir():
        raise OutputError(f"output directory {str(parent)!r} does not exist")
    try:
        with deferred_signals():  # a signal between making and removing it leaves nothing
            temporary_beside(path).unlink()
    except OSError as exc:
        raise OutputError(f"cannot write to {str(parent)!r}: {exc.strerror}") from None
    return path


def write_bytes_whole(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` whole or not at all (:func:`check_writable` first): a
    temporary file beside it (:func:`temporary_beside`) renamed into place, so a failed
    write leaves what ``path`` held; a failure is one line (:class:`OutputError`)."""
    target = check_writable(path)
    tmp = temporary_beside(target)
    try:
        tmp.write_bytes(data)
        os.replace(tmp, target)
    except OSError as exc:
        raise OutputError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None
    finally:
        tmp.unlink(missing_ok=True)


def cf_encoded(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` (a shallow copy) with the encodings and attribute types CF asks for where
    xarray's defaults differ; values, dtypes as read back and attributes are unchanged.

    - A coordinate variable (1-D, named like its dimension) has no ``_FillValue``
      (CF 2.5.1): xarray would write NaN on float ones.
    - A string coordinate variable is written as a character array
      (``name(name, stringN)``, CF 2.2): CF coordinate variables are numeric and
      monotonic, so a variable-length string one is not one, and the CF checker fails on
      it; xarray reads the character array back as the same strings and index.
    - ``flag_values`` has the type of its variable (CF 3.5), when that type holds the
      flag values exactly.
    - Every variable that is not a scalar (HDF5 filters no scalars) carries HDF5's
      Fletcher-32 checksum (``fletcher32``): a damaged byte
      inside the file, which the superblock check (:func:`damage`) cannot see and which
      would otherwise be read as a wrong number, makes reading fail
      (:func:`load_result` names the file).
    """
    out = ds.copy(deep=False)
    for var in out.variables.values():
        if var.ndim > 0:
            var.encoding = {**var.encoding, "fletcher32": True}
    for name in out.dims:
        if name not in out.variables:
            continue
        var = out.variables[name]
        encoding = dict(var.encoding)
        if var.dtype.kind in "fc":
            encoding["_FillValue"] = None
        elif var.dtype.kind in "OUS":
            encoding.pop("_FillValue", None)
            encoding["dtype"] = "S1"
        var.encoding = encoding
    for var in out.variables.values():
        flags = var.attrs.get("flag_values")
        if flags is None or var.dtype.kind not in "iuf":
            continue
        flags = np.asarray(flags)
        typed = flags.astype(var.dtype)
        if flags.dtype != var.dtype and np.array_equal(typed, flags):
            var.attrs["flag_values"] = typed
    return out


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file in the same folder, then rename),
    CF-encoded (:func:`cf_encoded`), with the permissions the umask gives a new file.

    SIGINT and SIGTERM wait until the file is written (:mod:`tennis_stroke.io.interrupts`:
    an interrupt inside the netCDF library would leave its lock held and hang the
    process); then the temporary file is removed, ``path`` keeps what it held, and the
    signal takes effect."""
    path = check_writable(path)
    # the temporary file is made with the signals already deferred: a signal between its
    # making and the deferral left it behind (a SIGTERM to a workflow run, seen in CI)
    with deferred_signals() as received:
        try:
            tmp = temporary_beside(path)
        except OSError as exc:
            raise OutputError(f"cannot write {str(path)!r}: {exc}") from None
        try:
            cf_encoded(ds).to_netcdf(tmp, engine="netcdf4")
            if received:
                tmp.unlink(missing_ok=True)
            else:
                os.replace(tmp, path)
        except OSError as exc:
            tmp.unlink(missing_ok=True)
            raise OutputError(f"cannot write {str(path)!r}: {_reason(exc)}") from None
        except RuntimeError as exc:  # the netCDF library's errors ("NetCDF: HDF error")
            tmp.unlink(missing_ok=True)
            full = _free_bytes(path.parent) < FULL_DISK_BYTES
            reason = "no space left on the device (disk full)" if full else str(exc)
            raise OutputError(f"cannot write {str(path)!r}: {reason}") from None
        except BaseException:
            tmp.unlink(missing_ok=True)
            raise
    return path


#: Free bytes below which a failed write is put down to a full disk (the netCDF library
#: reports a full disk as "NetCDF: HDF error").
FULL_DISK_BYTES = 1 << 20


def _free_bytes(folder: Path) -> int:
    try:
        stat = os.statvfs(folder)
    except OSError:
        return 1 << 62
    return stat.f_bavail * stat.f_frsize


def _reason(exc: OSError) -> str:
    """An OS error in words: a full disk says so."""
    if exc.errno == errno.ENOSPC:
        return "no space left on the device (disk full)"
    return str(exc)


def load_result(path: str | os.PathLike) -> xr.Dataset:
    """The result file ``path`` read into memory (every array, so every checksum is
    verified); a missing, truncated, damaged or foreign file raises :class:`ResultError`
    naming it and the way out."""
    import xarray as xr

    try:
        kind = "file" if Path(path).is_file() else "missing" if not Path(path).exists() else ""
    except OSError as exc:
        kind = f"cannot be read ({exc.strerror})"
    if kind != "file":
        problem = kind or "not a file"
        rebuild = _rebuild(path, remove=kind != "missing")
        raise ResultError(f"result file {str(path)!r}: {problem}: {rebuild}")
    problem = damage(path)
    if problem is None:
        try:
            ds = xr.open_dataset(path)
        except (OSError, ValueError, RuntimeError) as exc:
            problem = _first_line(exc)
            if "HDF error" in problem:  # also a file lock refused on a shared file system
                problem += (
                    " while opening it (on a shared file system, try HDF5_USE_FILE_LOCKING=FALSE)"
                )
        else:
            try:
                with ds:
                    return ds.load()
            except (OSError, ValueError, RuntimeError) as exc:
                problem = f"{_first_line(exc)} while reading its data: a checksum does not match"
    raise ResultError(f"result file {str(path)!r} cannot be read ({problem}): {_rebuild(path)}")


def _rebuild(path: str | os.PathLike, remove: bool = True) -> str:
    """The way out for a bad result file: the workflow's target that makes it again."""
    make = f"make it with: snakemake -j2 {path}"
    return f"remove it and {make}" if remove else make


def _first_line(exc: BaseException) -> str:
    return str(exc).splitlines()[0] if str(exc) else type(exc).__name__


#: The signature that starts every HDF5 file (netCDF-4 is HDF5).
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


def damage(path: str | os.PathLike) -> str | None:
    """Why the netCDF file ``path`` is damaged, or None if it looks whole: without reading
    it (fast enough to check every result before a run), from its HDF5 superblock: the
    signature, and the end-of-file address it records against the file's size (a
    truncated file is shorter; garbage has no signature)."""
    try:
        with open(path, "rb") as f:
            head = f.read(96)
        size = os.path.getsize(path)
    except OSError as exc:
        return f"cannot be read ({exc.strerror})"
    if not head.startswith(HDF5_SIGNATURE):
        return "not a netCDF-4 file (no HDF5 signature)"
    version = head[8]
    try:
        if version in (0, 1):
            offsets = head[13]
            start = 24 + (4 if version == 1 else 0) + 2 * offsets
        elif version in (2, 3):
            offsets = head[9]
            start = 12 + 2 * offsets
        else:
            return None
        eof = int.from_bytes(head[start : start + offsets], "little")
    except IndexError:
        return "truncated (shorter than its superblock)"
    if eof > size:
        return f"truncated ({size} of its {eof} bytes)"
    return None
