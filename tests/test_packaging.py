"""The package installs anywhere (issue 65): a wheel built from the files git tracks (a
clean checkout), and one built from its sdist, hold every file of the package and
nothing else; installed non-editable into a fresh venv with the lock's pins of its dependencies and
run from another folder, the wheel gives the README's ``strike`` example.

The installed copy lives at a new path, so numba compiles the solver for it (its cache
is keyed by the source files' paths): a cold compile, hence the ``compile`` kind.  The
builds use the project's own setuptools (``--no-build-isolation``: nothing downloaded).
"""

import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = "tennis_stroke"
#: The README's example and the line it prints (README.md, "The command line").
STRIKE = ("strike", "--theta0", "120", "--delta0", "81.5")
V_OUT = re.compile(r"^\s*v_out_kmh\s+155\.677711\s+km/h\b", re.M)


def _run(*args: str | Path, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(a) for a in args], capture_output=True, text=True, check=True, **kwargs
    )


def tracked(root: Path = ROOT) -> list[str]:
    """The files git tracks below ``root`` that exist (relative paths)."""
    out = _run("git", "-C", root, "ls-files", "-z").stdout
    return [name for name in out.split("\0") if name and (root / name).is_file()]


def clean_checkout(dest: Path) -> Path:
    """A copy of the checkout's tracked files at ``dest``: what a clone holds, without
    the build's leftovers (``build/``, ``*.egg-info``) or files git does not know."""
    for name in tracked():
        (dest / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / name, dest / name)
    return dest


#: What ``python -m build --no-isolation`` asks of setuptools (PEP 517), in one process:
#: the sdist (``--sdist``) and the wheel, of the folder it runs in, into ``sys.argv[1]``.
#: (setuptools rewrites ``sys.argv`` as it runs: the arguments are read first.)
BUILD = """import sys
from setuptools import build_meta
out, *sdist = sys.argv[1:]
if sdist:
    build_meta.build_sdist(out)
build_meta.build_wheel(out)
"""


def build(source: Path, out: Path, sdist: bool = False) -> list[Path]:
    """The wheel (and the sdist first, with ``sdist``) built from folder ``source`` into
    ``out``, with the project's setuptools (PEP 517 hooks, called as ``python -m build``
    calls them; pip builds wheels but no sdist)."""
    _run(sys.executable, "-c", BUILD, out, *(["--sdist"] if sdist else []), cwd=source)
    return [*out.glob("*.tar.gz"), *out.glob("*.whl")]


def members(wheel: Path) -> dict[str, bytes]:
    """The wheel's files and their contents."""
    with zipfile.ZipFile(wheel) as zf:
        return {name: zf.read(name) for name in zf.namelist()}


@pytest.fixture(scope="module")
def wheels(tmp_path_factory):
    """``(wheel, wheel of the sdist)``, built from a clean copy of the checkout."""
    tmp = tmp_path_factory.mktemp("packaging")
    archive, wheel = build(clean_checkout(tmp / "checkout"), tmp / "dist", sdist=True)
    shutil.unpack_archive(archive, tmp / "unpacked", filter="data")
    (unpacked,) = (tmp / "unpacked").iterdir()
    (from_sdist,) = build(unpacked, tmp / "dist-of-sdist")
    return wheel, from_sdist


def package_files(names) -> set[str]:
    """The package's files among ``names`` (paths below ``src/`` or a wheel's root),
    compiled bytecode aside."""
    return {n for n in names if n.startswith(f"{PACKAGE}/") and "__pycache__" not in n}


@pytest.mark.process
def test_the_wheel_holds_every_file_of_the_package_and_its_sdist_the_same(wheels):
    wheel, from_sdist = wheels
    files = members(wheel)
    source = {n.removeprefix("src/") for n in tracked() if n.startswith("src/")}
    # every module, template and schema the package reads at run time, and nothing else
    assert package_files(files) == package_files(source)
    dist_info = {n.split("/", 1)[1] for n in files if ".dist-info/" in n}
    assert {"METADATA", "RECORD", "WHEEL", "entry_points.txt", "licenses/LICENSE"} <= dist_info
    assert (
        "tennis-stroke = tennis_stroke.cli:main"
        in files[next(n for n in files if n.endswith(".dist-info/entry_points.txt"))].decode()
    )
    # the sdist holds what the wheel needs: the wheel it gives is the same, file by file
    assert members(from_sdist) == files


def _name(text: str) -> str:
    """A distribution's name as the lock and the metadata compare it (PEP 503)."""
    return re.sub(r"[-_.]+", "-", text).lower()


def runtime_lock(wheel: Path, lock: Path = ROOT / "requirements.lock") -> str:
    """The entries of ``lock`` (hashes with them) that the wheel's requirements need,
    without its extras: its ``Requires-Dist`` and theirs, as the project's environment's
    installed metadata gives them (the lock pins each; ``pip check`` in the fresh venv
    then proves none is missing)."""
    from importlib.metadata import distribution

    from packaging.requirements import Requirement

    files = members(wheel)
    meta = files[next(n for n in files if n.endswith(".dist-info/METADATA"))]
    todo = [line.split(":", 1)[1] for line in meta.decode().splitlines()
            if line.startswith("Requires-Dist:")]  # fmt: skip
    needed: set[str] = set()
    while todo:
        req = Requirement(todo.pop())
        if (req.marker and not req.marker.evaluate({"extra": ""})) or _name(req.name) in needed:
            continue
        needed.add(_name(req.name))
        todo += distribution(req.name).requires or []
    entries = re.split(r"\n(?=[A-Za-z0-9])", lock.read_text())
    return "\n".join(e for e in entries if _name(e.split("==")[0]) in needed) + "\n"


@pytest.mark.compile
def test_the_wheel_in_a_fresh_venv_with_the_locks_dependencies_runs_the_readme_example(
    wheels, tmp_path
):
    """A venv of its own (no pip in it: the project's pip installs into it, its
    byte-compilation off, about 18 s), the lock's pins of what the wheel requires, then
    the wheel; run from another folder as a user runs it."""
    wheel, _ = wheels
    venv, elsewhere = tmp_path / "venv", tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "runtime.lock").write_text(runtime_lock(wheel))
    _run(sys.executable, "-m", "venv", "--without-pip", venv)
    python = venv / "bin" / "python"
    pip = (sys.executable, "-m", "pip", "--python", python)
    _run(*pip, "install", "--quiet", "--no-compile", "--require-hashes", "--no-deps",
         "-r", tmp_path / "runtime.lock")  # fmt: skip
    _run(*pip, "install", "--quiet", "--no-compile", "--no-deps", "--no-index", wheel)
    _run(*pip, "check")  # every requirement of every installed distribution is there
    # its caches in the test's folder, not the user's
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    where = _run(
        python, "-c",
        "import tennis_stroke as t; from tennis_stroke.inference.reading_space import SCHEMA;"
        " print(t.__file__, t.__version__, SCHEMA.is_file())",
        cwd=elsewhere, env=env,
    ).stdout.split()  # fmt: skip
    assert Path(where[0]).is_relative_to(venv), where
    assert where[1:] == [wheel.name.split("-")[1], "True"], where
    # the console script pip wrote, as a user runs it
    out = _run(venv / "bin" / "tennis-stroke", *STRIKE, cwd=elsewhere, env=env).stdout
    assert out.startswith("stroke theta0 = 120 deg, delta0 = 81.5 deg: ok\n"), out
    assert V_OUT.search(out), out
    assert list(elsewhere.iterdir()) == []  # nothing written where it ran
