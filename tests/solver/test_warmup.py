"""The solver compiles once, in a process of its own, so a process with an empty cache
gives the same bits as one that loads the cache (solver/warmup.py)."""

import os
import subprocess
import sys

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


def _run(cache, **env):
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT],
        env={**os.environ, "NUMBA_CACHE_DIR": str(cache), **env},
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


def test_an_empty_cache_gives_the_bits_of_a_full_one(tmp_path):
    cold = _run(tmp_path)
    assert any(p.name.startswith("compiled-") for p in tmp_path.iterdir())
    assert (tmp_path / ".compile.lock").exists()
    warm = _run(tmp_path)
    assert cold == warm


def test_a_run_of_one_method_compiles_no_other(tmp_path):
    """The method is a compile-time constant (solver/integrate.py): the stroke batch of
    DOP853 (the default) caches DOP853's step kernel and not DP54's."""
    _run(tmp_path)
    cached = {p.name.split("-")[0] for p in tmp_path.rglob("*.nbi")}
    assert "_kernels.step_dop853" in cached
    assert not any("dp54" in name for name in cached), sorted(cached)
