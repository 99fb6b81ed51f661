"""Design limits (etcheck/checks/verdict/design_limits.py): each located limit is where a fresh check of the mission,
with that one input set to the limit, has its smallest straight margin at the required margin; the exact
power laws hold exactly; the gravity-gradient end masses give the limiting tension."""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest
from helpers import set_like, tape

from etcheck import check
from etcheck.checks.plan import EXACT
from etcheck.checks.rungs.straight import DEFAULT_OPTIONS
from etcheck.checks.verdict.design_limits import design_limits
from etcheck.input.mission import load_mission, mission_from_dict
from etcheck.scaling import RPM, scene

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def _limits(results: dict) -> dict:
    return {lim["input"]: lim for lim in results["design_limits"]["limits"]}


def _smallest(results: dict) -> float:
    return min(m["value"] for m in results["margins"] if m["value"] is not None and m["rung"] < 3)


@pytest.fixture(scope="module")
def spun_set():
    return check(set_like(name="spun", spin_rate="0.1041 rpm")).results


@pytest.mark.parametrize("name, field, unit", [("length", "length", "m"), ("current", "current", "A"),
                                               ("spin_rate", "spin_rate", "rpm")])
def test_spun_set_limits_put_the_smallest_margin_at_the_required(spun_set, name, field, unit):
    """SET spinning (rung 1, static pencils): at each limit a check of its own finds the margin required."""
    lim = _limits(spun_set)[name]
    assert lim["status"] == "located" and lim["evaluations"] > 0
    fields = {"spin_rate": "0.1041 rpm", field: f"{lim['limit']!r} {unit}"}
    if name == "length":  # the same section at another length: P = I1 / (A L²)
        fields["rotary_inertia_ratio"] = 0.001 * (100.0 / lim["limit"]) ** 2
    again = check(set_like(name="at the limit", **fields))
    assert _smallest(again.results) == pytest.approx(2.0, rel=10 * lim["relative_error"] + 1e-8)
    assert lim["margin_at_limit"] == pytest.approx(2.0, rel=1e-6)


def test_spun_set_needs_no_tension_and_says_which_margin_governs(spun_set):
    limits = _limits(spun_set)
    assert limits["end_tension"]["status"] == "zero" and limits["end_tension"]["limit"] == 0.0
    assert limits["spin_rate"]["governing"] == "spin margin"
    assert limits["current"]["governing"] == "load margin"  # at 75 A the load margin falls to 2 first


def test_rung0_limits_are_the_closed_forms():
    """Static SET (omega = T = 0): B ∝ I L³ and the static load does not depend on P, so the longest tether is
    L (m / required)^(1/3) and the largest current I m / required."""
    r = check(set_like(name="static")).results
    m, limits = r["margins"][0]["value"], _limits(r)
    assert limits["length"]["limit"] == pytest.approx(100.0 * (m / 2.0) ** (1 / 3), rel=1e-6)
    assert limits["current"]["limit"] == pytest.approx(1.0 * m / 2.0, rel=1e-12)


def test_tape_limits_on_the_exact_determinant_route():
    """The tape tether with one current and its gravity-gradient tension along it (rung 1v): the smallest tension
    located under the smallest tension held constant (the exact determinant's route, a conservative bound) puts a
    check of the tape under that end tension at the required margin; the end masses that give it are the
    mission's times the stated factor; the largest current is exact from rung 1v's own load margin."""
    data = tape(current_profile=False)
    mission = mission_from_dict(data)
    r = check(mission).results
    assert r["plan"]["route"] == "profiles"
    limits = _limits(r)
    tension = limits["end_tension"]
    assert tension["status"] == "located" and 0 < tension["limit"] < r["scene"]["tension_N"]
    assert "smallest tension held constant" in r["design_limits"]["basis"]
    gg = mission.operation.gravity_gradient
    k = tension["end_mass_factor"]
    scaled_gg = replace(gg, upper_mass=k * gg.upper_mass, lower_mass=k * gg.lower_mass)
    assert scaled_gg.minimum == pytest.approx(tension["limit"], rel=1e-10)
    at = check(mission.with_operation(gravity_gradient=None, end_tension=tension["limit"] * mission.operation.end_tension.unit)
               .with_fidelity("draft"))
    assert at.results["plan"]["route"] == EXACT
    assert _smallest(at.results) == pytest.approx(2.0, rel=1e-6)
    current = limits["current"]
    assert current["limit"] == pytest.approx(1.0 * r["margins"][0]["value"] / 2.0, rel=1e-12)
    # under the gravity gradient the tension grows with the length as the load does: no length limit near
    assert limits["length"]["status"] == "none" and limits["length"]["margin_at_limit"] > 2.0
    assert limits["spin_rate"]["status"] == "located" and limits["spin_rate"]["mission_value"] == 0.0


def test_limits_use_the_checks_options_and_a_failing_mission_looks_shorter():
    """A mission already short of the margin: its limits lie below the mission's values."""
    mission = load_mission(MISSIONS / "set-static.toml")
    failing = mission.with_check(required_margin=200.0)
    limits = {lim.input: lim for lim in design_limits(failing, scene(failing), DEFAULT_OPTIONS).limits}
    assert limits["length"].limit < 100.0 and limits["current"].limit < 1.0
    assert limits["length"].margin_at_limit == pytest.approx(200.0, rel=1e-6)


def test_units_of_the_spin_limit_are_rpm(spun_set):
    lim = _limits(spun_set)["spin_rate"]
    assert lim["unit"] == "rpm" and lim["mission_value"] == pytest.approx(0.1041, rel=1e-12)
    assert lim["limit"] == pytest.approx(spun_set["linear"]["critical_spin"]["rpm"] / 2.0, rel=1e-6)  # spin margin
    assert math.isclose(RPM, 60 / (2 * math.pi))


def test_draft_has_no_limits():
    data = copy.deepcopy(tomllib.loads((MISSIONS / "set.toml").read_text(encoding="utf-8")))
    data["check"]["fidelity"] = "draft"
    r = check(data).results
    assert r["design_limits"] is None and r["assumptions"] is None
