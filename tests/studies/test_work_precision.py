"""The work-precision study per scene: its layout, its errors against the independent
reference falling with the tolerance, and the rule table read from fixed data."""

import numpy as np
import pytest
from conftest import assert_same_results, work_precision_table

from tennis_stroke.io.netcdf import write_netcdf
from tennis_stroke.pipeline.chunks import gather_chunks, mark_chunk
from tennis_stroke.studies.tables import ERRORS, meets, rule_table, summary
from tennis_stroke.studies.work_precision import UNTIL_MET, work_precision

SCENES = {"swing": {"contact_model": "swing_speed"}, "contact": {}}


@pytest.fixture(scope="module")
def table():
    return work_precision(
        SCENES, 2, 2, [1e-4, 1e-9], [1e-6], [1e-3], ("DOP853",), state_times=4, repeats=1
    )


def test_every_error_per_stroke_per_scene_against_an_independent_reference(table):
    assert table.attrs["reference"].startswith("scipy DOP853")
    for name in (*ERRORS, "rhs_evals"):
        assert table[name].dims == ("scene", "method", "setting", "stroke")
    assert list(table["scene"].values) == list(SCENES)
    run = table["failed"].notnull()
    assert float(table["failed"].where(run).sum()) == 0
    assert int(run.sum()) == 2 * (2 * 2 + 1 + 1)  # scenes x (compiled 2 x 2, scipy, RK4)


def test_the_compiled_errors_fall_with_the_tolerance_in_every_measure(table):
    worst = summary(table).sel({"method": "tennis_stroke.DOP853"})
    for scene in SCENES:
        for name in ERRORS:
            tight, loose = (
                float(worst[f"{name}_worst"].sel(scene=scene, setting=s)) for s in (1e-9, 1e-4)
            )
            assert tight < loose, (scene, name, tight, loose)
        evals = worst["rhs_evals"].sel(scene=scene)
        assert float(evals.sel(setting=1e-9)) > float(evals.sel(setting=1e-4))


def test_rk4_on_the_swing_scene_meets_the_ball_at_phi_zero(table):
    """Fixed-step RK4 follows the cheap rungs (no spring contact): its swing-only v_out is
    close to the reference's, where a spring contact would be km/h away."""
    err = table["v_out_error"].sel({"scene": "swing", "method": "fixed.RK4", "setting": 1e-3})
    assert float(err.max()) < 0.1


def _fixed(v_out, events, evals, failed):
    """One scene (``contact``) of :func:`conftest.work_precision_table`."""
    return work_precision_table(*(np.asarray(a)[None] for a in (v_out, events, evals, failed)))


def test_the_rule_is_the_cheapest_setting_meeting_both_requirements():
    """RK45 at 1e-4 is cheapest but misses the event times; DOP853 at 1e-4 meets both
    but lost a stroke; so RK45 at 5e-8 (cheaper than DOP853 at 5e-8) is the rule."""
    ds = _fixed(
        v_out=[[1e-5, 1e-7], [1e-5, 1e-8]],
        events=[[1e-7, 1e-9], [1e-5, 1e-9]],
        evals=[[100, 400], [50, 300]],
        failed=[[1, 0], [0, 0]],
    )
    [row] = rule_table(ds).to_dict("records")
    assert (row["method"], row["setting"], row["rhs_evals"]) == ("scipy.RK45", 5e-8, 300)
    assert row["default_meets"] and row["default_rhs_evals"] == 400


def test_a_scene_no_setting_meets_says_none():
    ds = _fixed([[1.0, 1.0], [1.0, 1.0]], [[0, 0], [0, 0]], [[1, 2], [3, 4]], [[0, 0], [0, 0]])
    [row] = rule_table(ds).to_dict("records")
    assert row["method"] == "none" and not row["default_meets"]


def test_one_job_per_scene_gathers_to_the_whole_table_bit_for_bit(table, tmp_path):
    """The workflow runs each scene as a chunk of its own (``rows``) and gathers them:
    every variable but the wall times (a ``timing`` attribute: not compared) and every
    attribute but the chunks' own equal the whole table's."""
    paths = []
    for i in reversed(range(len(SCENES))):
        part = work_precision(
            SCENES,
            2,
            2,
            [1e-4, 1e-9],
            [1e-6],
            [1e-3],
            ("DOP853",),
            state_times=4,
            repeats=1,
            rows=(i, len(SCENES)),
        )
        assert list(part["scene"].values) == [list(SCENES)[i]]
        part = mark_chunk(part, i, len(SCENES))
        assert part.attrs["chunk_dim"] == "scene"
        paths.append(write_netcdf(part, tmp_path / f"{i}-of-{len(SCENES)}.nc"))
    whole = write_netcdf(table, tmp_path / "whole.nc")
    assert_same_results(gather_chunks(paths), whole, also_differ=["chunk_count"])


def test_scipy_and_rk4_stop_at_their_first_setting_that_meets_the_requirement():
    """A tighter setting of a method with Python right-hand sides costs more and cannot
    be the rule: each runs its settings from the loosest up to the first that meets the
    requirement; the compiled methods run all of theirs."""
    ds = work_precision(
        {"swing": SCENES["swing"]},
        2,
        2,
        [1e-4, 1e-9],
        [1e-6, 1e-8],
        [1e-3, 5e-4],
        ("Radau",),
        state_times=4,
        repeats=1,
    )
    s = summary(ds).sel(scene="swing")
    required = {"v_out": 1e-4, "event_time": 1e-6}
    met = meets(
        s["v_out_error_worst"],
        s["event_time_error_worst"],
        ds["failed"].sel(scene="swing"),
        required,
    )
    ran = ds["failed"].sel(scene="swing").notnull()
    cut = 0
    for method in ds["method"].values:
        family = str(method).split(".")[0]
        settings = [
            v for v in ds["setting"].values if bool(ran.sel({"method": method, "setting": v}))
        ]
        tried = sorted(settings, reverse=True)
        if family not in UNTIL_MET:
            assert len(tried) == 2, method
            continue
        first = next((v for v in tried if bool(met.sel({"method": method, "setting": v}))), None)
        assert first is not None and tried[-1] == first, (method, tried)
        cut += 2 - len(tried)
    assert cut == 2  # Radau at 1e-8 and RK4 at 5e-4 were not run
