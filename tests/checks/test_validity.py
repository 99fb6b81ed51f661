"""The model's validity (etcheck/checks/verdict/validity.py): the bow of a tensioned beam under a uniform lateral load
against an independent boundary-value solve and its two limits, the verdict "outside" with its reason past
a limit, and where the field across the tether comes from."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from helpers import set_like
from scipy.integrate import solve_bvp

from etcheck import check
from etcheck.checks.pipeline import EXIT_CODES
from etcheck.checks.verdict.validity import BOW_LIMIT, mid_span_bow, tension_for_bow
from etcheck.errors import MissionError
from etcheck.input.mission import load_mission, mission_from_dict

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def _bvp_bow(q: float, L: float, T: float, EI: float, clamped: bool) -> float:
    """EI w'''' - T w'' = q, w = w' = 0 (clamped) or w = w'' = 0 (pinned) at both ends, by collocation."""

    def rhs(x, y):
        return np.vstack([y[1], y[2], y[3], (q + T * y[2]) / EI])

    def bc(a, b):
        k = 1 if clamped else 2
        return np.array([a[0], a[k], b[0], b[k]])

    x = np.linspace(0.0, L, 201)
    sol = solve_bvp(rhs, bc, x, np.zeros((4, x.size)), tol=1e-10, max_nodes=200000)
    assert sol.success, sol.message
    return float(sol.sol(L / 2)[0])


@pytest.mark.parametrize("clamped", [True, False])
@pytest.mark.parametrize("T", [1e-4, 0.05, 2.0])
def test_bow_against_a_boundary_value_solve(T, clamped):
    q, L, EI = 3e-5, 100.0, 0.5  # kL/4 from 0.35 to 50
    assert mid_span_bow(q, L, T, EI, clamped) == pytest.approx(_bvp_bow(q, L, T, EI, clamped), rel=1e-6)


def test_bow_limits_string_and_beam():
    q, L, EI = 2e-5, 500.0, 1e-5
    assert mid_span_bow(q, L, 10.0, EI) == pytest.approx(q * L**2 / 80.0, rel=2e-3)  # taut string
    assert mid_span_bow(q, L, 0.0, EI) == q * L**4 / (384 * EI)
    assert mid_span_bow(q, L, 0.0, EI, clamped=False) == 5 * q * L**4 / (384 * EI)
    # the series and the closed form meet where the bracket switches (kL/4 = 0.1 clamped, kL/2 = 0.1 pinned)
    for clamped, y in ((True, 0.1), (False, 0.1)):
        T = (y * (4 if clamped else 2) / L) ** 2 * EI
        lo, hi = (mid_span_bow(q, L, T * f, EI, clamped) for f in (1 - 1e-12, 1 + 1e-12))
        assert hi == pytest.approx(lo, rel=1e-9)
    string = q * L / (8 * 0.02)  # the taut string's; the layers at the welded ends take 4 / (kL) off
    assert tension_for_bow(q, L, EI, 0.02 * L) == pytest.approx(string * (1 - 4 / (L * math.sqrt(string / EI))),
                                                               rel=1e-6)
    T = tension_for_bow(q, L, EI, 0.02 * L)
    assert mid_span_bow(q, L, T, EI) == pytest.approx(0.02 * L, rel=1e-9)


def test_tape_is_outside_with_its_reason_and_exit_1():
    r = check(MISSIONS / "tape-tether.toml")
    mv = r.results["model_validity"]
    assert r.verdict == "outside" and r.exit_code == 1 == EXIT_CODES["outside"]
    assert [m["verdict"] for m in r.results["margins"]] == ["fail"]  # its collected current: flutter (rung 1v)
    (reason,) = mv["reasons"]
    assert "bows" in reason and "lateral Lorentz load" in reason
    lat = mv["lateral"]
    # the field across the tether from the orbit: below the worst field along it, and more than the sampled minimum
    assert 0 < lat["cross_field_T"] < 70e-6 and "orbit" in lat["cross_field_source"]
    assert lat["bow_over_length"] > BOW_LIMIT
    # what would bring it within the limit brings it to the limit
    assert mid_span_bow(lat["load_N_per_m"], 500.0, lat["tension_for_limit_N"], lat["stiffness_N_m2"]) == \
        pytest.approx(BOW_LIMIT * 500.0, rel=1e-8)


def test_a_stated_cross_field_decides_and_zero_is_the_papers_scene():
    """Static SET at 37 A (margin 4.3) with the default field across it (the worst axial, 70 µT) bows 32 m:
    outside; with the field along the tether only (cross_field 0) it passes; a stated one sets the bow."""
    data = set_like(name="near", current="37 A")
    assert check(data).verdict == "outside"
    data["operation"]["cross_field"] = "0 uT"
    r = check(data).results
    assert r["verdict"] == "pass" and r["model_validity"]["lateral"]["bow_m"] == 0.0
    data["operation"]["cross_field"] = "1 uT"
    lat = check(data).results["model_validity"]["lateral"]
    assert lat["cross_field_source"] == "operation.cross_field" and lat["cross_field_T"] == pytest.approx(1e-6)
    assert lat["bow_m"] == pytest.approx(37 * 1e-6 * 100.0**4 / (384 * 21.0), rel=1e-12)


def test_short_thick_tether_is_outside_rod_theory():
    data = set_like(name="stub", rotary_inertia_ratio=0.3, current="0.01 A")
    data["operation"]["cross_field"] = "0 uT"
    r = check(data)
    assert r.verdict == "outside" and "rod theory" in r.results["model_validity"]["reasons"][0]


def test_stretched_tether_is_outside_the_inextensible_model():
    data = set_like(name="stretched", end_tension="2 kN", check={"fidelity": "draft"})
    del data["tether"]["rotary_inertia_ratio"]
    data["tether"] |= {"youngs_modulus": "70 GPa", "cross_section_area": "1 mm2"}  # strain 2e3 / 7e4 = 2.9 %
    r = check(data).results
    strain = next(c for c in r["model_validity"]["checks"] if c["name"] == "inextensible")
    assert strain["value"] == pytest.approx(2e3 / 7e4, rel=1e-12) and strain["within"] is False
    assert r["verdict"] == "outside"


def test_cross_field_with_an_orbit_is_refused():
    assert load_mission(MISSIONS / "tape-tether.toml").orbit is not None  # its [orbit] gives the field across it
    raw = tomllib.loads((MISSIONS / "tape-tether.toml").read_text(encoding="utf-8"))
    raw["operation"]["cross_field"] = "20 uT"
    with pytest.raises(MissionError, match="operation.cross_field"):
        mission_from_dict(raw)
