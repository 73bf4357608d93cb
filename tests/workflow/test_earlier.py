"""The earlier file of each output, kept beside it while its job runs and put back when
the job fails or is stopped (tennis_stroke.pipeline.earlier), without Snakemake: each
case of issue 63 that lost data with the kept copies, and its sibling.  The workflow's
own failed and stopped runs are in test_workflow_failsafe.py."""

import errno
import os

import pytest

from tennis_stroke.pipeline import earlier
from tennis_stroke.pipeline.earlier import STALE_TIME, beside, keep, settle


class Records:
    """Snakemake's records as ``settle`` reads them: the files marked incomplete, and
    the records removed (``cleanup_metadata``)."""

    _incomplete_path = "incomplete"

    def __init__(self, incomplete=()):
        self.incomplete, self.removed = set(incomplete), []

    def _exists_record(self, subject, path):
        return subject == self._incomplete_path and str(path) in self.incomplete

    def cleanup_metadata(self, path):
        self.removed.append(str(path))


@pytest.fixture
def run(tmp_path, monkeypatch):
    """A working folder with three results and a page, as a run finds them."""
    monkeypatch.chdir(tmp_path)
    for name in ("results/a/x.nc", "results/y.csv", "results/z.png", "report/index.html"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(f"earlier {name}")
    return tmp_path


def test_a_failed_job_s_output_is_put_back_dated_1970_and_unrecorded(run):
    """Snakemake removes a job's outputs when it starts it: the failed job's earlier file
    comes back, older than any input and without records, so its job runs again; a job
    that made its file, and one that never started, keep theirs."""
    assert keep(["results/a/x.nc", "results/y.csv", "results/none.nc"]) == [
        "results/a/x.nc",
        "results/y.csv",
    ]
    assert os.path.samefile(beside("results/a/x.nc"), "results/a/x.nc")
    (run / "results/a/x.nc").unlink()  # removed by Snakemake when its job started
    (run / "results/y.csv").unlink()
    (run / "results/y.csv").write_text("new")  # made by its job
    records = Records()
    assert settle(records) == ["results/a/x.nc"]
    assert (run / "results/a/x.nc").read_text() == "earlier results/a/x.nc"
    assert (run / "results/a/x.nc").stat().st_mtime == STALE_TIME
    assert (run / "results/y.csv").read_text() == "new"
    assert records.removed == ["results/a/x.nc"] * 2  # its incomplete marker, its record
    assert not list(run.rglob("*.earlier"))  # nothing left for --delete-all-output
    assert settle(records) == []


def test_a_stopped_job_s_partial_output_is_replaced_by_the_earlier_one(run):
    """A job stopped while it wrote a figure in place leaves a partial file that Snakemake
    marks incomplete: the earlier one replaces it (before, a 0-byte figure stayed and was
    taken for up to date)."""
    keep(["results/z.png"])
    (run / "results/z.png").unlink()
    (run / "results/z.png").write_bytes(b"")  # the stopped job's partial figure
    assert settle(Records(incomplete={"results/z.png"})) == ["results/z.png"]
    assert (run / "results/z.png").read_text() == "earlier results/z.png"


def test_nothing_is_written_in_snakemake_s_folder_nor_copied(run, monkeypatch):
    """The kept copies filled `.snakemake` on a smaller disk and were copied file by
    file from `results/` on another file system: an earlier file is a hard link in its
    own folder (one file system), nothing is copied and nothing goes to `.snakemake`."""
    import shutil

    def no_copy(*args, **kwargs):
        raise AssertionError("copied")

    monkeypatch.setattr(shutil, "copy2", no_copy)
    monkeypatch.setattr(shutil, "copyfile", no_copy)
    keep(["results/a/x.nc", "report/index.html"])
    assert not (run / ".snakemake").exists()
    assert os.stat("results/a/x.nc").st_nlink == 2


@pytest.mark.parametrize(
    "code", [errno.EXDEV, errno.EPERM, errno.ENOSPC], ids=["no link", "no hard links", "full"]
)
def test_a_refused_link_keeps_nothing_of_that_file_in_one_line(run, monkeypatch, capsys, code):
    """A file system that will not link (a full folder, one without hard links) keeps
    nothing of that file, in one line; nothing is copied, the run goes on."""

    def refused(source, target):
        raise OSError(code, os.strerror(code))

    monkeypatch.setattr(os, "link", refused)
    assert keep(["results/a/x.nc"]) == []
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        "tennis-stroke warning: the earlier results/a/x.nc is not kept while its job runs ("
    )
    assert sorted(p.name for p in (run / "results/a").iterdir()) == ["x.nc"]


def test_a_put_back_that_fails_is_one_line_and_keeps_the_earlier_file(run, monkeypatch, capsys):
    """A full results disk made the put-back crash with a traceback and leave a 0-byte
    figure: a put-back is a rename (no space needed, never a partial file), and one that
    fails anyway says so in one line, leaves the output missing (its job plans) and the
    earlier file where it is kept, for the next run to put back."""
    keep(["results/a/x.nc"])
    (run / "results/a/x.nc").unlink()
    real = os.replace

    def full(source, target):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "replace", full)
    assert settle(Records()) == []
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and "cannot be put back (No space left on device)" in lines[0]
    assert not (run / "results/a/x.nc").exists()
    monkeypatch.setattr(os, "replace", real)
    assert settle(Records()) == ["results/a/x.nc"]  # the next run's start (after kill -9 too)
    assert (run / "results/a/x.nc").read_text() == "earlier results/a/x.nc"


def test_keeping_again_replaces_no_earlier_file_by_a_newer_one(run):
    """The next run replaced the only good kept copy with a 0-byte file: a run keeps only
    the files its jobs will replace, and ends every one it kept."""
    keep(["results/a/x.nc"])
    (run / "results/a/x.nc").unlink()
    assert settle(Records()) == ["results/a/x.nc"]
    assert keep(["results/a/x.nc"]) == ["results/a/x.nc"]
    assert beside("results/a/x.nc").read_text() == "earlier results/a/x.nc"
    assert earlier.TOPS == ("results", "report")
