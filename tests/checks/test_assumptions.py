"""The assumptions that decide the verdict (etcheck/checks/verdict/assumptions.py) and the flight record
(etcheck/checks/verdict/flight.py): each alternative margin is the margin of a check of the alternative mission, the
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
    assert "the profile along the tether" in rows["tension"]["value"]
    assert rows["field"]["flag"] == "assumed"  # [orbit] listed under [mission] assumed
    assert rows["current"]["flag"] == "assumed" and "varies along the tether" in rows["current"]["value"]
    assert rows["damping"]["flag"] == "default" and rows["ends"]["flag"] == "default"
    spun = _rows(check(MISSIONS / "set.toml").results)
    assert spun["tension"]["flag"] == "data" and spun["tension"]["value"] == "0 N"  # given in the file
    assert spun["current"]["flag"] == "data" and "uniform along the tether" in spun["current"]["value"]


def _tensioned(**fields) -> dict:
    """SET with an end tension (rung 1, the exact determinant's route)."""
    return set_like(name="taut", **({"end_tension": "0.02 N"} | fields))


def test_no_tension_alternative_is_the_check_without_tension():
    """One tension along the tether: the margin without it is the margin a check of that mission gives."""
    taut = check(_tensioned()).results
    free = check(set_like(name="free", end_tension="0 N")).results
    assert _rows(taut)["tension"]["margin_alternative"] == pytest.approx(free["margins"][0]["value"], rel=1e-8)
    assert _rows(taut)["tension"]["margin_alternative"] < taut["margins"][0]["value"]


def test_exact_elasticities_and_the_tension_one():
    taut = check(_tensioned()).results
    rows = _rows(taut)
    assert rows["current"]["elasticity"] == -1.0 and rows["field"]["elasticity"] == -1.0  # margin ∝ 1 / (I B0)
    assert rows["damping"]["elasticity"] == 0.0  # Kelvin-Tait-Chetaev: damping does not move the critical values
    # the tension's, against a difference of two checks 1 % apart
    margins = []
    for factor in (1.01, 1 / 1.01):
        r = check(_tensioned(end_tension=f"{0.02 * factor!r} N", check={"fidelity": "draft"})).results
        margins.append((r["scene"]["tension_N"], r["margins"][0]["value"]))
    (t1, m1), (t2, m2) = margins
    assert rows["tension"]["elasticity"] == pytest.approx(math.log(m1 / m2) / math.log(t1 / t2), rel=1e-3)


def test_with_profiles_the_alternatives_are_the_checks_beside_the_verdict(tape):
    """The tape tether (rung 1v: its collected current and its gravity-gradient tension along it): one current
    along the whole tether gives the margin of the uniform check of the same tether under its smallest tension;
    the tension's and the damping's alternatives are what rung 1v computed beside its verdict."""
    rows = _rows(tape)
    load = tape["scaled"]["B"]
    prof = tape["profiles"]
    assert rows["tension"]["margin_alternative"] == pytest.approx(prof["uniform_tension_bound"]["value"] / load,
                                                                  rel=1e-12)
    assert rows["damping"]["alternative"] == "no damping"
    assert rows["damping"]["margin_alternative"] == pytest.approx(prof["undamped"]["value"] / load, rel=1e-12)
    assert rows["current"]["elasticity"] == -1.0 and rows["field"]["elasticity"] == -1.0  # b(s) fixed: B_c / B
    raw = _raw("tape-tether.toml")
    del raw["operation"]["current_profile"], raw["operation"]["collection"], raw["tether"]["end_masses"]
    raw["operation"]["end_tension"] = f"{tape['mission']['operation']['gravity_gradient']['minimum_N']!r} N"
    raw["mission"]["assumed"] = [a for a in raw["mission"]["assumed"] if a != "tether.end_masses"]
    uniform = check(raw).results
    assert uniform["plan"]["route"] != "profiles"
    assert rows["current"]["margin_alternative"] == pytest.approx(uniform["margins"][0]["value"], rel=1e-8)
    # the largest current from the load margin (exact for a profile of fixed shape)
    (current,) = [lim for lim in tape["design_limits"]["limits"] if lim["input"] == "current"]
    margin = tape["margins"][0]
    assert current["limit"] == pytest.approx(current["mission_value"] * margin["value"] / margin["required"],
                                             rel=1e-14)
    assert {lim["status"] for lim in tape["design_limits"]["limits"] if lim["input"] != "current"} == {"not sought"}


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
    rows = _rows(r)  # one current, its tension along it (rung 1v): a conservative load
    assert rows["damping"]["elasticity"] == 0.0 and rows["tension"]["alternative"].startswith("the smallest tension")


def test_flight_agreement_within_the_model():
    """A flight within the model's validity: a pass against a coil disagrees, a fail agrees."""
    raw = copy.deepcopy(set_like(name="flown"))
    raw["operation"]["cross_field"] = "0 uT"
    raw["mission"]["flight"] = {"outcome": "coiled", "reported": "test"}
    assert check(raw).results["flight"]["agreement"] == "disagrees"
    raw["operation"]["current"] = "100 A"
    assert check(raw).results["flight"]["agreement"] == "agrees"


def test_a_margin_of_zero_has_no_elasticity():
    """ProSEDS (a round wire with its collected current: flutter at any load, margin 0): ln 0 has no derivative, so
    neither the current nor the field gets an elasticity, and no largest current is given."""
    r = check(MISSIONS / "proseds.toml").results
    assert r["margins"][0]["value"] == 0.0
    rows = _rows(r)
    assert rows["current"]["elasticity"] is None and rows["field"]["elasticity"] is None
    assert "zero" in rows["current"]["elasticity_method"]
    (current,) = [lim for lim in r["design_limits"]["limits"] if lim["input"] == "current"]
    assert current["limit"] is None
