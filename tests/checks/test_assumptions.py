"""The assumptions that decide the verdict (etcheck/checks/assumptions.py) and the flight record
(etcheck/checks/flight.py): each alternative margin is the margin of a check of the alternative mission, the
exact elasticities are exact, the flags follow the mission file."""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import pytest
from helpers import set_like

from etcheck import check

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def _raw(name: str) -> dict:
    return tomllib.loads((MISSIONS / name).read_text(encoding="utf-8"))


def _rows(results: dict) -> dict:
    return {row["key"]: row for row in results["assumptions"]["rows"]}


@pytest.fixture(scope="module")
def tape() -> dict:
    return check(MISSIONS / "tape-tether.toml").results


def test_rows_and_flags_follow_the_mission_file(tape):
    rows = _rows(tape)
    assert list(rows) == ["ends", "current", "tension", "field", "damping"]
    assert rows["tension"]["flag"] == "assumed" and "tether.end_masses" in rows["tension"]["source"]
    assert rows["field"]["flag"] == "assumed"  # [orbit] listed under [mission] assumed
    assert rows["current"]["flag"] == "assumed" and "uniform along the tether" in rows["current"]["value"]
    assert rows["damping"]["flag"] == "default" and rows["ends"]["flag"] == "default"
    spun = _rows(check(MISSIONS / "set.toml").results)
    assert spun["tension"]["flag"] == "data" and spun["tension"]["value"] == "0 N"  # given in the file
    assert spun["current"]["flag"] == "data"


def test_no_tension_alternative_is_the_check_without_tension(tape):
    """The tape without its gravity-gradient tension: the margin a check of that mission gives."""
    raw = _raw("tape-tether.toml")
    del raw["tether"]["end_masses"]
    raw["mission"]["assumed"] = [a for a in raw["mission"]["assumed"] if a != "tether.end_masses"]
    raw["operation"]["end_tension"] = "0 N"
    free = check(raw).results
    assert _rows(tape)["tension"]["margin_alternative"] == pytest.approx(free["margins"][0]["value"], rel=1e-8)
    assert free["margins"][0]["verdict"] == "fail"


def test_exact_elasticities_and_the_tension_one(tape):
    rows = _rows(tape)
    assert rows["current"]["elasticity"] == -1.0 and rows["field"]["elasticity"] == -1.0  # margin ∝ 1 / (I B0)
    assert rows["damping"]["elasticity"] == 0.0  # Kelvin-Tait-Chetaev: damping does not move the critical values
    # the tension's, against a difference of two checks 1 % apart
    margins = []
    for factor in (1.01, 1 / 1.01):
        raw = _raw("tape-tether.toml")
        raw["tether"]["end_masses"] = [f"{12 * factor!r} kg", f"{12 * factor!r} kg"]
        raw["check"]["fidelity"] = "draft"  # the margins alone (to ~1e-8 on this route)
        r = check(raw).results
        margins.append((r["scene"]["tension_N"], r["margins"][0]["value"]))
    (t1, m1), (t2, m2) = margins
    assert rows["tension"]["elasticity"] == pytest.approx(math.log(m1 / m2) / math.log(t1 / t2), rel=1e-3)


def test_undamped_alternative_is_the_undamped_check():
    """Spinning SET: the margin without damping is the smallest margin of the undamped check (its draft: the
    margins alone); an undamped mission's alternative is the paper's damping."""
    damped = check(set_like(name="d", spin_rate="0.1041 rpm")).results
    undamped = check(set_like(name="u", spin_rate="0.1041 rpm", damping_time="0 s", check={"fidelity": "draft"}))
    smallest = min(m["value"] for m in undamped.results["margins"])
    assert _rows(damped)["damping"]["margin_alternative"] == pytest.approx(smallest, rel=1e-6)
    static = check(set_like(name="s", damping_time="0 s")).results
    assert _rows(static)["damping"]["alternative"].startswith("the paper's damping")
    assert _rows(static)["damping"]["margin_alternative"] == pytest.approx(static["margins"][0]["value"], rel=1e-9)


def test_ends_alternative_is_the_attachment_checks(tape):
    ends = _rows(tape)["ends"]
    (alt,) = tape["margins"][0]["alternatives"]
    assert ends["alternative"] == "both ends pinned" and ends["margin_alternative"] == alt["value"]


def test_pmg_flight_record():
    r = check(MISSIONS / "pmg.toml").results
    f = r["flight"]
    assert f["outcome"] == "coiled" and f["prediction"] == "outside" and f["agreement"] == "not decided by the model"
    assert "bows by 4.29 % of its length" in f["comparison"]
    assert any("the bow under the lateral Lorentz load" in item and "4.29 %" in item for item in f["not_modelled"])
    assert any("end masses" in item and "marked as assumed" in item for item in f["not_modelled"])
    assert check(MISSIONS / "set.toml").results["flight"] is None


def test_flight_agreement_within_the_model():
    """A flight within the model's validity: a pass against a coil disagrees, a fail agrees."""
    raw = copy.deepcopy(set_like(name="flown"))
    raw["operation"]["cross_field"] = "0 uT"
    raw["mission"]["flight"] = {"outcome": "coiled", "reported": "test"}
    assert check(raw).results["flight"]["agreement"] == "disagrees"
    raw["operation"]["current"] = "100 A"
    assert check(raw).results["flight"]["agreement"] == "agrees"
