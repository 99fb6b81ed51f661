"""The [uncertainty] table (etcheck/input/uncertainty.py): tolerances and distributions in SI,
and every bad entry a MissionError naming uncertainty.FIELD."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest
from scipy import stats

from etcheck import MissionError, load_mission, mission_from_dict

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def with_uncertainty(table: dict, base: str = "set.toml") -> dict:
    data = tomllib.loads((MISSIONS / base).read_text())
    data["uncertainty"] = table
    return data


def test_shipped_mission_parses():
    m = load_mission(MISSIONS / "set-tolerances.toml")
    bs, field = m.studies.uncertainty.get("bending_stiffness"), m.studies.uncertainty.get("axial_field")
    assert (bs.shape, bs.factor, bs.a, bs.b, bs.lower) == ("normal", True, 1.0, 0.15, 0.0)
    assert field.shape == "lognormal" and field.b == 0.3 and math.isclose(math.exp(field.a), 70e-6)
    assert any("truncated at 0" in n for n in m.provenance.notes)


def test_tolerance_is_uniform_band_in_si():
    m = mission_from_dict(with_uncertainty({"length": "±0.5 m", "current": "±10 %"}))
    L, current = m.studies.uncertainty.get("length"), m.studies.uncertainty.get("current")
    assert (L.shape, L.a, L.b, L.unit) == ("uniform", 99.5, 100.5, "m")
    assert (current.a, current.b) == pytest.approx((0.9, 1.1))
    assert L.interval() == (99.5, 100.5)


def test_current_range_tolerance_is_around_the_worst_case():
    data = with_uncertainty({"current": {"distribution": "normal", "sigma": "10 %"}})
    data["operation"]["current"] = ["0.2 A", "1.5 A"]
    d = mission_from_dict(data).studies.uncertainty.get("current")
    assert (d.a, d.b) == pytest.approx((1.5, 0.15))


def test_truncated_normal_and_tails():
    d = mission_from_dict(with_uncertainty(
        {"end_tension": {"distribution": "normal", "sigma": "0.2 N", "bounds": ["-0.1 N", "0.5 N"]}})).studies.uncertainty.get("end_tension")
    z = stats.norm.cdf(2.5) - stats.norm.cdf(-0.5)
    assert d.cdf(0.0) == pytest.approx((0.5 - stats.norm.cdf(-0.5)) / z, rel=1e-12)
    assert d.ppf(0.0) == -0.1 and d.ppf(1.0) == 0.5
    f = mission_from_dict(with_uncertainty({"axial_field": {"distribution": "lognormal", "sigma": 0.3}})).studies.uncertainty.get("axial_field")
    assert f.sf(70e-6 * math.exp(0.3 * 6)) == pytest.approx(stats.norm.sf(6), rel=1e-9)  # far tail, no cancellation


def test_default_damping_accepts_relative_only():
    d = mission_from_dict(with_uncertainty({"damping_time": {"distribution": "log-uniform", "factor": 10}}))
    u = d.studies.uncertainty.get("damping_time")
    assert u.factor and (u.a, u.b) == pytest.approx((0.1, 10.0))


@pytest.mark.parametrize("table, field, words", [
    ({"lenght": "±1 %"}, "uncertainty.lenght", "did you mean 'length'"),
    ({"length": "10 %"}, "uncertainty.length", "±10 %"),
    ({"length": "±-1 %"}, "uncertainty.length", "positive"),
    ({"length": "±1 kg"}, "uncertainty.length", "expected a length"),
    ({"length": "±100 %"}, "uncertainty.length", "positive"),
    ({"length": 5}, "uncertainty.length", "expected a tolerance"),
    ({"axial_field": {"distribution": "gauss", "sigma": "1 %"}}, "uncertainty.axial_field", "not known"),
    ({"axial_field": {"distribution": "normal", "sigam": "1 %"}}, "uncertainty.axial_field", "did you mean 'sigma'"),
    ({"axial_field": {"distribution": "lognormal", "sigma": -0.1}}, "uncertainty.axial_field", "positive"),
    ({"axial_field": {"distribution": "lognormal", "sigma": float("nan")}}, "uncertainty.axial_field", "positive"),
    ({"length": {"distribution": "uniform", "bounds": ["90 m", "99 m"]}}, "uncertainty.length", "do not contain"),
    ({"length": {"distribution": "uniform"}}, "uncertainty.length", "needs bounds"),
    ({"torsional_stiffness": "±1 %"}, "uncertainty.torsional_stiffness", "poisson_ratio"),
    ({"damping_time": "±0.1 s"}, "uncertainty.damping_time", "relative"),
    ({"bending_stiffness": "±1 N m2"}, "uncertainty.bending_stiffness", "relative"),
    ({"bending_stiffness": "±1 %", "EI1": "±1 %"}, "uncertainty.bending_stiffness", "either"),
    ({"end_tension": "±5 %"}, "uncertainty.end_tension", "zero"),
])
def test_bad_entries_name_the_field(table, field, words):
    with pytest.raises(MissionError) as exc:
        mission_from_dict(with_uncertainty(table))
    assert exc.value.field == field
    assert words in str(exc.value)


def test_entries_are_echoed_as_written():
    m = mission_from_dict(with_uncertainty({"bending_stiffness": {"distribution": "normal", "sigma": "15 %"},
                                            "length": "±0.5 m",
                                            "end_tension": {"distribution": "normal", "sigma": "0.2 N",
                                                            "bounds": ["-0.1 N", "0.5 N"]},
                                            "damping_time": {"distribution": "log-uniform", "factor": 10}}))
    assert [d.written for d in m.studies.uncertainty.echo().inputs] == [
        '{ distribution = "normal", sigma = "15 %" }', "±0.5 m",
        '{ distribution = "normal", sigma = "0.2 N", bounds = ["-0.1 N", "0.5 N"] }',
        '{ distribution = "log-uniform", factor = 10 }']


@pytest.mark.parametrize("table, key", [
    ({"bending_stiffness": {"distribution": "normal", "sigma": "15 %"}}, "bending_stiffness"),  # truncated at 0
    ({"axial_field": {"distribution": "lognormal", "sigma": "30 %", "bounds": ["-50 %", "+200 %"]}}, "axial_field"),
    ({"length": "±2 %"}, "length"),
    ({"damping_time": {"distribution": "log-uniform", "factor": 10}}, "damping_time"),
])
def test_standard_normal_coordinate_is_exact_into_the_far_tails(table, key):
    """Phi(z) = F(x) from both tails against mpmath at 40 digits (F from the distribution's definition), and
    from_normal inverts to_normal: to 1e-7 out to +-6 (where x, a float within 1e-9 of a bound, carries no more),
    to 1e-9 to +-8 where the distribution is not cut there."""
    import mpmath as mp

    mp.mp.dps = 40
    d = mission_from_dict(with_uncertainty(table)).studies.uncertainty.get(key)

    def F(x):  # the truncated distribution function, from its definition, at 40 digits
        x = mp.mpf(x)
        if d.shape == "uniform":
            return (x - mp.mpf(d.a)) / (mp.mpf(d.b) - mp.mpf(d.a))
        if d.shape == "log-uniform":
            return mp.log(x / mp.mpf(d.a)) / mp.log(mp.mpf(d.b) / mp.mpf(d.a))
        s = (mp.log(x) if d.shape == "lognormal" else x) - mp.mpf(d.a)
        base = lambda v: mp.ncdf(((mp.log(v) if d.shape == "lognormal" else v) - mp.mpf(d.a)) / mp.mpf(d.b))  # noqa: E731
        lo = base(mp.mpf(d.lower)) if math.isfinite(d.lower) and (d.lower > 0 or d.shape == "normal") else 0
        hi = base(mp.mpf(d.upper)) if math.isfinite(d.upper) else 1
        return (mp.ncdf(s / mp.mpf(d.b)) - lo) / (hi - lo)

    far = (-8.0, 7.5) if key == "bending_stiffness" else ()
    for z in (*far, -6.0, -2.0, -1e-3, 0.7, 4.0, 6.0):
        x = float(d.from_normal(z))
        p = F(x)
        want = float(mp.sqrt(2) * mp.erfinv(2 * p - 1)) if z < 0 else -float(mp.sqrt(2) * mp.erfinv(1 - 2 * p))
        tol = 1e-9 if z in far else 1e-7
        assert float(d.to_normal(x)) == pytest.approx(want, rel=tol, abs=1e-12), (z, x)
        assert float(d.to_normal(x)) == pytest.approx(z, rel=tol, abs=1e-9)  # the round trip
