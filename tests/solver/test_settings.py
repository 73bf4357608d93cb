"""Solver settings: the accuracy bound (one place, shared by the Python API, the command
line and the workflow) and the memory estimate of a batch of strokes."""

import os
from pathlib import Path

import numpy as np
import pytest
import yaml

from tennis_stroke import ParameterError, SolverSettings, strike, strike_batch
from tennis_stroke.experiments.memory import (
    BATCH_BYTES_PER_STROKE,
    MEMORY_ENV,
    MemoryLimitError,
    batch_bytes,
    check_memory,
    format_size,
    memory_limit,
    parse_size,
    result_bytes,
)
from tennis_stroke.solver.results import OK
from tennis_stroke.solver.settings import MAX_ATOL, MAX_RTOL, SolverSettingError

ROOT = Path(__file__).resolve().parents[2]
TIGHT = SolverSettings(rtol=1e-12, atol=1e-12, history=4096)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"rtol": 10.0}, "'rtol' must be <= 0.0001"),
        ({"rtol": 1.0}, "'rtol' must be <= 0.0001"),
        ({"rtol": 2 * MAX_RTOL}, "'rtol' must be <= 0.0001"),
        ({"atol": 100.0}, "'atol' must be <= 0.0001"),
        ({"atol": 1e-3, "method": "DP54"}, "'atol' must be <= 0.0001"),
        ({"rtol": float("inf")}, "'rtol' must be > 0"),
        ({"rtol": 1e-300, "atol": 1e-300}, "'rtol' must be >= 2.22e-14 (100 machine epsilons"),
        ({"rtol": 1e-15}, "'rtol' must be >= 2.22e-14"),
        ({"rtol": True}, "'rtol' must be > 0"),
        ({"rtol": "1e-8"}, "'rtol' must be > 0"),
        ({"method": "RK4"}, "solver method must be one of DP54, DOP853"),
        ({"method": None}, "solver method must be one of"),
        ({"max_steps": float("inf")}, "'max_steps' must be a whole number >= 1"),
        ({"history": 2.5}, "'history' must be a whole number >= 1"),
        ({"follow_through": float("nan")}, "'follow_through' must be >= 0"),
    ],
)
def test_out_of_range_settings_are_refused_in_one_line(kwargs, fragment):
    with pytest.raises(SolverSettingError) as err:
        SolverSettings(**kwargs)
    assert isinstance(err.value, ParameterError)  # the CLI's and the workflow's error
    assert fragment in str(err.value) and "\n" not in str(err.value)
    assert err.value.setting == next(iter(kwargs)) or "method" in kwargs


def test_the_bound_names_its_reason():
    with pytest.raises(ParameterError, match="claims' tolerances of 1 km/h"):
        SolverSettings(rtol=10.0)


def test_the_python_api_refuses_a_loose_tolerance():
    """Today's bug: rtol 10 returned status ok and a v_out far from the true one."""
    with pytest.raises(ParameterError, match="'rtol' must be <="):
        strike(120.0, 81.5, None, SolverSettings(rtol=10.0))


def test_studies_may_lift_the_bound_explicitly():
    loose = SolverSettings(rtol=0.1, atol=0.1, accuracy_bound=False)
    assert loose.as_dict()["accuracy_bound"] == 0
    assert "accuracy_bound" not in SolverSettings().as_dict()  # files keep their attributes
    with pytest.raises(SolverSettingError, match="'rtol' must be > 0"):
        SolverSettings(rtol=0.0, accuracy_bound=False)


@pytest.mark.parametrize("method", ["DOP853", "DP54"])
def test_at_the_bound_strokes_stay_within_the_claims_tolerances(method):
    """The measurement behind MAX_RTOL, on a small part of the Fig. 3 and Fig. 8 maps:
    at the bound the errors stay well inside 1 km/h, 0.5 rad/s and 1 degree."""
    grids = [
        (np.linspace(60, 120, 13)[:, None], np.linspace(0, 90, 10)[None, :], {"L1": 0.4}),
        (90.0, np.linspace(0, 100, 11)[:, None], {"L1": 0.4, "C2": 5.0, "tau": [[0.0, 0.185]]}),
    ]
    at_bound = SolverSettings(method=method, rtol=MAX_RTOL, atol=MAX_ATOL)
    for theta0, delta0, params in grids:
        ref = strike_batch(theta0, delta0, params, TIGHT)
        res = strike_batch(theta0, delta0, params, at_bound)
        assert np.array_equal(res["status"], ref["status"])
        ok = ref["status"] == OK
        assert np.max(np.abs(res["v_out_kmh"] - ref["v_out_kmh"])[ok]) < 0.5
        for key in ("omega1_contact", "omega2_contact"):
            assert np.max(np.abs(res[key] - ref[key])[ok]) < 0.25
        assert np.max(np.abs(res["theta_deg_at_phi0"] - ref["theta_deg_at_phi0"])[ok]) < 0.5


def test_the_workflow_schema_leaves_the_bound_to_the_package():
    """The schema holds no second copy of the bound: config_check applies SolverSettings."""
    schema = yaml.safe_load((ROOT / "workflow/schemas/config.schema.yaml").read_text())
    solver = schema["properties"]["solver"]["properties"]
    study = schema["properties"]["solver_study"]["properties"]
    for spec in (solver["rtol"], solver["atol"], study["compiled_tolerances"]["items"]):
        assert "maximum" not in spec and "exclusiveMaximum" not in spec
    assert "MAX_RTOL" in solver["rtol"]["description"]


def test_the_solver_s_defaults_and_methods_have_one_home():
    """The solver's defaults live in SolverSettings and its methods in METHOD_IDS: the
    schema file writes neither (not a default, not a method name), and the schema the
    workflow checks with gives exactly the package's, everywhere it names a method."""
    from tennis_stroke.pipeline.config_check import load_schema
    from tennis_stroke.solver.settings import METHOD_IDS

    path = ROOT / "workflow/schemas/config.schema.yaml"
    text = path.read_text()
    assert "5.0e-8" not in text and "default: DOP853" not in text
    assert "[DOP853, DP54]" not in text and "[DP54, DOP853]" not in text
    schema = load_schema(path)
    solver = schema["properties"]["solver"]["properties"]
    default = SolverSettings()
    for key in ("method", "rtol", "atol"):
        assert solver[key]["default"] == getattr(default, key), key
    assert f"default {default.t_max:g})" in solver["t_max"]["description"]
    rung = schema["properties"]["model_ladder"]["properties"]["rungs"]["items"]
    for spec in (solver["method"], rung["properties"]["solver"]["properties"]["method"]):
        assert sorted(spec["enum"]) == sorted(METHOD_IDS)


@pytest.mark.parametrize(
    "text, size",
    [
        ("8G", 8 * 1024**3),
        ("8g", 8 * 1024**3),
        ("512MiB", 512 * 1024**2),
        ("1.5 GB", int(1.5 * 1024**3)),
        ("100K", 100 * 1024),
        ("2T", 2 * 1024**4),
        ("1000", 1000),
        (4096, 4096),
        ("1e6", 10**6),
    ],
)
def test_memory_sizes(text, size):
    assert parse_size(text) == size


@pytest.mark.parametrize("text", ["", "lots", "-1G", "0", "8X", "G", "nan", "inf", True, 0.5])
def test_bad_memory_sizes_are_refused(text):
    with pytest.raises(ValueError, match="memory size must be"):
        parse_size(text)


@pytest.mark.parametrize("text", ["1e400G", "1e308T", float("inf")])
def test_a_size_beyond_any_float_is_refused_as_not_finite(text):
    """Once refused as "must be at least 1 byte", which is not what is wrong."""
    with pytest.raises(ValueError, match="must be a finite number of bytes"):
        parse_size(text)


def test_memory_limit_precedence(monkeypatch):
    monkeypatch.delenv(MEMORY_ENV, raising=False)
    default, source = memory_limit(None, "--max-memory")
    physical = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    assert 0 < default <= physical and "--max-memory" in source and MEMORY_ENV in source
    monkeypatch.setenv(MEMORY_ENV, "3G")
    assert memory_limit() == (3 * 1024**3, MEMORY_ENV)
    assert memory_limit("2G", "--max-memory") == (2 * 1024**3, "--max-memory")
    monkeypatch.setenv(MEMORY_ENV, "three")
    with pytest.raises(ValueError, match=f"^{MEMORY_ENV}: memory size must be"):
        memory_limit()


def test_check_memory_names_the_estimate_and_the_limit():
    check_memory(1024, "a small thing", (2048, "here"))
    with pytest.raises(MemoryLimitError) as err:
        check_memory(batch_bytes(31623 * 31623), "a sweep", (8 * 1024**3, "--max-memory"))
    assert str(err.value) == (
        "a sweep needs about 425 GiB of memory, above the limit of 8 GiB (--max-memory)"
    )
    assert format_size(result_bytes(10**9)) == "104 GiB"


def _peak_rss_after(fn) -> int:
    """Growth of the peak resident memory (bytes) while ``fn`` runs (Linux)."""
    Path("/proc/self/clear_refs").write_text("5")  # reset the peak (VmHWM) to now

    def status(key):
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith(key):
                return int(line.split()[1]) * 1024
        raise KeyError(key)

    start = status("VmRSS:")
    fn()
    return status("VmHWM:") - start


@pytest.mark.skipif(not Path("/proc/self/clear_refs").exists(), reason="needs Linux /proc")
def test_the_batch_estimate_matches_the_memory_a_batch_takes():
    """The bytes per stroke come from the arrays strike_batch holds; measured, the peak
    stays within 15 % of the estimate (strokes stop at once: t_max is tiny)."""
    quick = SolverSettings(t_max=1e-3)
    theta0, delta0 = np.linspace(60, 120, 1000)[:, None], np.linspace(0, 90, 500)[None, :]
    strike_batch(theta0[:2], delta0, None, quick, threads=1)  # warm up
    try:
        grown = _peak_rss_after(lambda: strike_batch(theta0, delta0, None, quick, threads=1))
    except OSError:
        pytest.skip("cannot reset the peak resident memory here")
    per_stroke = grown / theta0.size / delta0.size
    assert 0.85 * BATCH_BYTES_PER_STROKE < per_stroke < 1.15 * BATCH_BYTES_PER_STROKE


def test_the_tightest_rtol_runs_even_with_a_tiny_atol():
    """MIN_RTOL is scipy's floor of 100 machine epsilons; at it, with atol 1e-300, a
    stroke still succeeds (at rtol = atol = 1e-300 every stroke failed its steps)."""
    from tennis_stroke import strike
    from tennis_stroke.solver.settings import MIN_RTOL

    tight = strike(90.0, 45.0, {}, SolverSettings(rtol=MIN_RTOL, atol=1e-300))
    usual = strike(90.0, 45.0, {}, SolverSettings())
    assert tight["status_name"] == "ok"
    assert abs(tight["v_out_kmh"] - usual["v_out_kmh"]) < 1e-4
