"""The solver compiles once, in a process of its own, so a process with an empty cache
gives the same bits as one that loads the cache (solver/warmup.py)."""

import os
import subprocess
import sys

import pytest
from conftest import built_once, shared_folder

#: Strokes of the tiny workflow's elbow-force map, where a process that compiled the
#: solver in place once gave other last bits than the cached code (6e-14 km/h).
SCRIPT = """
import numpy as np
from tennis_stroke import strike_batch
psi = np.linspace(0.0, 270.0, 4)[:, None]
t_f = 0.185 + np.array([-0.05, 0.0, 0.05])[None, :]
params = {"L1": 0.4, "C2": 5.0, "tau": 0.185, "F0": 20.0, "t_d": 0.05, "psi_F_deg": psi,
          "t_F": t_f}
r = strike_batch(90.0, 52.5, params, threads=2)
print(r["v_out_kmh"].tobytes().hex(), r["omega2_phi0"].tobytes().hex())
"""


def _python(code, cache) -> subprocess.CompletedProcess:
    """``code`` run by a Python process of its own with numba's cache in ``cache``."""
    return subprocess.run(
        [sys.executable, "-c", code],
        env={**os.environ, "NUMBA_CACHE_DIR": str(cache)},
        capture_output=True,
        text=True,
        timeout=900,
    )


def _run(cache):
    done = _python(SCRIPT, cache)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


#: Tests that compile the solver (make check leaves them out).
compiles = pytest.mark.compile


@pytest.fixture(scope="session")
def cold_cache(tmp_path_factory):
    """One process run on an empty cache (it compiles the default stroke batch), once for
    every xdist worker (``built_once``), shared by the tests that read what a cold compile
    leaves: ``(cache folder, its output)``.  A test that changes the cache works on a
    copy."""
    folder = shared_folder(tmp_path_factory, "cold-cache")
    output = folder.parent / "cold-cache.out"

    def build(cache):
        cache.mkdir()
        output.write_text(_run(cache))

    built_once(folder, build)
    return folder, output.read_text()


@compiles
def test_an_empty_cache_gives_the_bits_of_a_full_one(cold_cache):
    cache, cold = cold_cache
    assert any(p.name.startswith("compiled-") for p in cache.iterdir())
    assert (cache / ".compile.lock").exists()
    warm = _run(cache)
    assert cold == warm


@compiles
def test_a_run_of_one_method_compiles_no_other(cold_cache):
    """The method is a compile-time constant (solver/integrate.py): the stroke batch of
    DOP853 (the default) caches DOP853's step kernel and not DP54's."""
    cache, _ = cold_cache
    cached = {p.name.split("-")[0] for p in cache.rglob("*.nbi")}
    assert "_kernels.step_dop853" in cached
    assert not any("dp54" in name for name in cached), sorted(cached)


#: A stroke on scipy's reference path: its group (``reference``, the model's right-hand
#: sides) is the cheapest to compile (about 3 s here, against 17 s for the stroke batch),
#: and it is cached, damaged and healed by the same code as every other group.
REFERENCE = (
    "from tennis_stroke.solver.reference import solve_stroke; "
    "print(solve_stroke(90.0, 45.0, rtol=1e-6, atol=1e-6).result['v_out_kmh'].hex())"
)


def _entry(cache, suffix):
    """The cache file of one of the group's compiled functions (the model's right-hand
    side ``dynamics.rhs_angles``)."""
    (path,) = [p for p in cache.rglob(f"dynamics.rhs_angles-*{suffix}")][:1]
    return path


DAMAGES = {
    "a truncated index": lambda c: _entry(c, ".nbi").write_bytes(
        _entry(c, ".nbi").read_bytes()[:40]
    ),
    "a data file of garbage": lambda c: _entry(c, ".nbc").write_bytes(b"\x80garbage" * 100),
    "a lost data file (the marker would lie)": lambda c: _entry(c, ".nbc").unlink(),
}


@compiles
def test_a_damaged_cache_is_cleared_and_compiled_again_in_one_line(tmp_path):
    """A truncated index or a data file of garbage gave a 40-line traceback through numba's
    caching on every call, as the marker still said the cache was complete; a lost data
    file made the process compile in place.  Each is now one line on stderr, the same
    number, and a healthy cache for the next process (on the cheapest group: the
    mechanism is the same for every group, :func:`tennis_stroke.solver.compiled._load`)."""
    first = _python(REFERENCE, tmp_path)
    assert first.returncode == 0 and "tennis-stroke" not in first.stderr, first.stderr[-2000:]
    assert any(p.name.startswith("compiled-reference-") for p in tmp_path.iterdir())
    for what, damage in DAMAGES.items():
        damage(tmp_path)
        healed = _python(REFERENCE, tmp_path)
        assert healed.returncode == 0, (what, healed.stderr[-2000:])
        assert healed.stdout == first.stdout, what
        lines = [line for line in healed.stderr.splitlines() if line.strip()]
        assert len(lines) == 1 and "cleared and compiled again" in lines[0], (what, lines)
        assert "Traceback" not in healed.stderr
        after = _python(REFERENCE, tmp_path)
        assert after.stdout == first.stdout and after.stderr == "", (what, after.stderr)


def test_the_cache_subfolder_is_numbas():
    from numba.core.caching import _CacheLocator

    from tennis_stroke._cache import compiled_sources
    from tennis_stroke.solver.compiled import cache_subfolder

    for source in compiled_sources():
        assert cache_subfolder(source) == _CacheLocator.get_suitable_cache_subpath(str(source))


#: The solver studies' fixed-step RK4 in a process that may not compile in place: a
#: stroke (the work-precision study) and an isolated contact with RK4 and with a scipy
#: method (the stability study).
RK4 = """
from tennis_stroke.solver.rk4 import fixed_step_stroke
from tennis_stroke.solver.compiled import refusing_compiles
from tennis_stroke.studies.stability import isolated_contact
with refusing_compiles():
    for method in ("scipy.DOP853", "scipy.Radau", "scipy.LSODA"):
        print(isolated_contact(method, 1e-3, 1000.0))
    print(isolated_contact("fixed.RK4", 1e-5, 1000.0))
    print(fixed_step_stroke(100.0, 60.0, {}, 2e-4)["v_out_kmh"].hex())
"""


@compiles
def test_the_studies_rk4_compiles_in_the_warm_up_not_in_the_job(tmp_path):
    """RK4 runs model functions from Python: the warm-up's ``rk4`` group compiles them in
    its own process, so a study job only loads them (it compiled them in place before,
    and two such jobs could compile the same functions at once); twice the same bits."""
    runs = [_python(RK4, tmp_path) for _ in range(2)]
    for done in runs:
        assert done.returncode == 0, done.stderr[-2000:]
    assert any(p.name.startswith("compiled-rk4-") for p in tmp_path.iterdir())
    assert runs[0].stdout == runs[1].stdout
