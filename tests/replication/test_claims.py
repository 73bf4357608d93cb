"""Claims: definitions are checked, measurements and statuses are right."""

import numpy as np
import pytest
import xarray as xr
import yaml

from tennis_stroke.inference.claims import ClaimError, load_claims
from tennis_stroke.inference.measures import measure_delay_threshold
from tennis_stroke.replication.claims import check, evaluate


def _write(tmp_path, claims):
    path = tmp_path / "claims.yaml"
    path.write_text(yaml.safe_dump({"claims": claims}))
    return path


GOOD = {
    "id": "x",
    "source": "s",
    "quantity": "q",
    "unit": "s",
    "paper_value": 1.0,
    "tolerance": 0.1,
    "expectation": "reproduce",
    "measure": {"file": "f", "var": "v"},
}


@pytest.mark.parametrize(
    "change, fragment",
    [
        ({"expectation": "maybe"}, "expectation must be one of"),
        ({"expectation": "known_deviation"}, "needs a reason"),
        ({"tolerance": -1.0}, "tolerance must be >= 0"),
    ],
)
def test_malformed_claims_are_rejected(tmp_path, change, fragment):
    with pytest.raises(ClaimError, match=fragment):
        load_claims(_write(tmp_path, [{**GOOD, **change}]))


def test_missing_key_and_duplicates(tmp_path):
    bad = {k: v for k, v in GOOD.items() if k != "unit"}
    with pytest.raises(ClaimError, match="lacks 'unit'"):
        load_claims(_write(tmp_path, [bad]))
    with pytest.raises(ClaimError, match="duplicate"):
        load_claims(_write(tmp_path, [GOOD, GOOD]))


def test_statuses(tmp_path):
    nc = tmp_path / "f.nc"
    xr.Dataset({"v": ((), 1.05), "w": ((), 2.0)}).to_netcdf(nc)
    claims = [
        GOOD,
        {**GOOD, "id": "y", "measure": {"file": "f", "var": "w"}},
        {
            **GOOD,
            "id": "z",
            "expectation": "known_deviation",
            "reason": "r",
            "measure": {"file": "f", "var": "w"},
        },
    ]
    table = evaluate(load_claims(_write(tmp_path, claims), files=["f"]), {"f": nc})
    assert list(table["status"]) == ["pass", "fail", "known_deviation"]
    csv = tmp_path / "claims.csv"
    table.to_csv(csv, index=False)
    assert check(csv) == 1
    table[table.status != "fail"].to_csv(csv, index=False)
    assert check(csv) == 0


def test_a_claim_either_side_of_the_paper_by_more_than_its_tolerance_fails(tmp_path):
    """The verdict is the closed band around the paper's value: 1.5 tolerances below
    fails as above does, half a tolerance below passes."""
    nc = tmp_path / "f.nc"
    xr.Dataset({"low": ((), 0.85), "high": ((), 1.15), "close": ((), 0.95)}).to_netcdf(nc)
    claims = [
        {**GOOD, "id": v, "measure": {"file": "f", "var": v}} for v in ("low", "high", "close")
    ]
    table = evaluate(load_claims(_write(tmp_path, claims), files=["f"]), {"f": nc})
    assert list(table["status"]) == ["fail", "fail", "pass"]


def test_delay_threshold_on_a_synthetic_map():
    c2 = np.arange(0.0, 3.01, 0.5)
    best = np.array([0.08, 0.0, 0.0, 0.0, 0.07, 0.1, 0.12])  # leaves 0 between 1.5 and 2
    ds = xr.Dataset({"best_tau": ("C2", best)}, coords={"C2": c2, "tau": np.arange(0, 0.3, 0.0025)})
    assert measure_delay_threshold(ds) == pytest.approx(1.75)
