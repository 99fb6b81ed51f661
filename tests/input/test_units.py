"""The unit edge (etcheck/units.py): strings, astropy and pint -> astropy in SI."""

from __future__ import annotations

import math

import astropy.units as u
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from etcheck.input.units import KINDS, QuantityProblem, to_quantity

pint = pytest.importorskip("pint")
ureg = pint.UnitRegistry()

finite = st.floats(min_value=-1e12, max_value=1e12, allow_nan=False, allow_infinity=False).filter(
    lambda x: x == 0 or abs(x) > 1e-12
)
positive = st.floats(min_value=1e-9, max_value=1e12, allow_nan=False, allow_infinity=False)


def fmt(x: float) -> str:
    return repr(float(x))


# --- property tests: unit prefixes and conversions ------------------------------------


@settings(max_examples=200, deadline=None)
@given(finite)
def test_km_is_1000_m(x):
    q = to_quantity(f"{fmt(x)} km", "length")
    assert q.unit == u.m
    assert q.value == pytest.approx(1000.0 * x, rel=1e-14, abs=1e-300)


@settings(max_examples=200, deadline=None)
@given(finite)
def test_string_round_trip_in_si(x):
    for kind, (unit, _what, _example) in KINDS.items():
        q = to_quantity(f"{fmt(x)} {unit.to_string()}", kind)
        assert q.unit == unit
        assert q.value == pytest.approx(x, rel=1e-14, abs=1e-300)


@settings(max_examples=200, deadline=None)
@given(finite)
def test_prefixed_units(x):
    assert to_quantity(f"{fmt(x)} uT", "field").value == pytest.approx(x * 1e-6, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} mA", "current").value == pytest.approx(x * 1e-3, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} GPa", "pressure").value == pytest.approx(x * 1e9, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} mm2", "area").value == pytest.approx(x * 1e-6, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} g / m", "mass_per_length").value == pytest.approx(x * 1e-3, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} N cm2", "bending_stiffness").value == pytest.approx(x * 1e-4, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} ms", "time").value == pytest.approx(x * 1e-3, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} kN", "force").value == pytest.approx(x * 1e3, rel=1e-14, abs=1e-300)


@settings(max_examples=200, deadline=None)
@given(finite)
def test_spin_rates(x):
    two_pi = 2 * math.pi
    assert to_quantity(f"{fmt(x)} rpm", "angular_rate").value == pytest.approx(x * two_pi / 60, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} Hz", "angular_rate").value == pytest.approx(x * two_pi, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} rad / s", "angular_rate").value == pytest.approx(x, rel=1e-14, abs=1e-300)
    assert to_quantity(f"{fmt(x)} deg / s", "angular_rate").value == pytest.approx(
        x * math.pi / 180, rel=1e-14, abs=1e-300
    )


@settings(max_examples=100, deadline=None)
@given(finite)
def test_astropy_quantities_pass_through(x):
    q = to_quantity(x * u.km, "length")
    assert q.unit == u.m and q.value == pytest.approx(1000 * x, rel=1e-14, abs=1e-300)
    q = to_quantity(x * u.uT, "field")
    assert q.unit == u.T and q.value == pytest.approx(1e-6 * x, rel=1e-14, abs=1e-300)


@settings(max_examples=100, deadline=None)
@given(finite)
def test_pint_round_trip(x):
    assert to_quantity(ureg.Quantity(x, "km"), "length").value == pytest.approx(1000 * x, rel=1e-14, abs=1e-300)
    assert to_quantity(ureg.Quantity(x, "microtesla"), "field").value == pytest.approx(1e-6 * x, rel=1e-14, abs=1e-300)
    assert to_quantity(ureg.Quantity(x, "N * m**2"), "bending_stiffness").value == pytest.approx(
        x, rel=1e-14, abs=1e-300
    )
    assert to_quantity(ureg.Quantity(x, "rpm"), "angular_rate").value == pytest.approx(
        x * 2 * math.pi / 60, rel=1e-12, abs=1e-300
    )
    assert to_quantity(ureg.Quantity(x, "Hz"), "angular_rate").value == pytest.approx(
        x * 2 * math.pi, rel=1e-12, abs=1e-300
    )


# --- examples -------------------------------------------------------------------------


@pytest.mark.parametrize(
    "value, kind, si",
    [
        ("100 m", "length", 100.0),
        ("5 km", "length", 5000.0),
        ("38 N m2", "bending_stiffness", 38.0),
        ("38 N m^2", "bending_stiffness", 38.0),
        ("70 uT", "field", 70e-6),
        ("0.7 G", "field", 70e-6),
        ("2 rpm", "angular_rate", 2 * 2 * math.pi / 60),
        ("0.2 rad/s", "angular_rate", 0.2),
        ("1 Hz", "angular_rate", 2 * math.pi),
        ("0.1 kg/m", "mass_per_length", 0.1),
        ("132 GPa", "pressure", 132e9),
        ("3.1 mm2", "area", 3.1e-6),
        ("20 ms", "time", 0.02),
        ("1 mA", "current", 1e-3),
        ("5 N", "force", 5.0),
        ("  100   m ", "length", 100.0),
    ],
)
def test_examples(value, kind, si):
    q = to_quantity(value, kind)
    assert q.unit == KINDS[kind][0]
    assert q.value == pytest.approx(si, rel=1e-14)


@pytest.mark.parametrize(
    "value, si",
    [("100 m", 100.0), ("0.1 km", 100.0), ("2 rpm", 0.20944), ("1 Hz", 2 * math.pi)],
)
def test_pint_examples(value, si):
    kind = "angular_rate" if ("rpm" in value or "Hz" in value) else "length"
    q = to_quantity(ureg(value), kind)
    assert q.unit == KINDS[kind][0]
    assert q.value == pytest.approx(si, rel=1e-5)


def test_pint_rad_per_s_is_not_cycles():
    assert to_quantity(ureg("1 rad/s"), "angular_rate").value == pytest.approx(1.0, rel=1e-14)
    assert to_quantity(ureg("60 deg/s"), "angular_rate").value == pytest.approx(math.pi / 3, rel=1e-14)


# --- refusals -------------------------------------------------------------------------


@pytest.mark.parametrize(
    "value, kind",
    [
        ("100 s", "length"),
        ("3 m", "field"),
        ("3 V", "current"),
        ("38 N", "bending_stiffness"),
        ("1 rad", "angular_rate"),
        ("2 m", "angular_rate"),
        ("5 kg", "force"),
        ("100 m m", "length"),
        ("1 m / m", "length"),
    ],
)
def test_wrong_dimension(value, kind):
    with pytest.raises(QuantityProblem) as exc:
        to_quantity(value, kind)
    assert KINDS[kind][1] in str(exc.value)  # says what was expected


@pytest.mark.parametrize(
    "value, kind",
    [
        (ureg("3 s"), "length"),
        (ureg("1 V"), "current"),
        (ureg("38 N m"), "bending_stiffness"),
        (ureg("2 m"), "angular_rate"),
        (ureg("3"), "length"),
    ],
)
def test_pint_wrong_dimension(value, kind):
    with pytest.raises(QuantityProblem):
        to_quantity(value, kind)


@pytest.mark.parametrize("value", [100, 100.0, True, np.float64(3.0), "100", "1e3", " 2 "])
def test_bare_numbers_refused(value):
    with pytest.raises(QuantityProblem, match="no unit"):
        to_quantity(value, "length")


@pytest.mark.parametrize(
    "value",
    ["nan m", "inf m", "-inf m", "1e999 m", "nan", "inf", float("nan") * u.m, float("inf") * u.m, math.nan, math.inf],
)
def test_non_finite_refused(value):
    with pytest.raises(QuantityProblem):
        to_quantity(value, "length")


def test_pint_non_finite_refused():
    with pytest.raises(QuantityProblem):
        to_quantity(ureg.Quantity(float("nan"), "m"), "length")
    with pytest.raises(QuantityProblem):
        to_quantity(ureg.Quantity(float("inf"), "m"), "length")


@pytest.mark.parametrize("value", ["", "m", "abc", "1,5 m", "1 furlongz", None, [1, 2], {"a": 1}])
def test_unreadable_refused(value):
    with pytest.raises(QuantityProblem):
        to_quantity(value, "length")


def test_arrays_refused():
    with pytest.raises(QuantityProblem):
        to_quantity([1.0, 2.0] * u.m, "length")
    with pytest.raises(QuantityProblem):
        to_quantity(ureg.Quantity(np.array([1.0, 2.0]), "m"), "length")
