"""Mission <-> dimensionless problem (etcheck/scaling.py, eq. (36))."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from etcheck import load_mission
from etcheck.rod.core.ends import KINDS, Ends
from etcheck.rod.core.parameters import RodParameters
from etcheck.scaling import Scaled, Scales, Scene, scale, scene, unscale, with_length

MISSIONS = Path(__file__).resolve().parent.parent / "missions"


def _cos_cosh_root() -> float:
    """First root of cos a cosh a = 1 (clamped-clamped beam), by bisection here."""
    lo, hi = 4.5, 5.0
    g = lambda a: math.cos(a) * math.cosh(a) - 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


F = _cos_cosh_root() ** 4


def pos(lo, hi):
    return st.floats(min_value=lo, max_value=hi, allow_nan=False, allow_infinity=False)


#: the attachments of the ends: every pair but a swivel at both
ENDS = st.sampled_from([(a, b) for a in KINDS for b in KINDS if (a, b) != ("swivel", "swivel")])


@st.composite
def scenes(draw):
    EI1 = draw(pos(1e-6, 1e5))
    R = draw(pos(1e-4, 1.0))
    return Scene(
        length=draw(pos(1e-2, 1e5)),
        EI1=EI1,
        EI2=EI1 * R,
        GJ=draw(pos(1e-3, 10.0)) * EI1,
        mass_per_length=draw(pos(1e-6, 1e3)),
        P=draw(pos(0.0, 1.0)),
        load=draw(pos(0.0, 1e4)),
        spin_rate=draw(pos(0.0, 1e3)),
        tension=draw(pos(-1e4, 1e4)),
        damping_time=draw(pos(0.0, 1e3)),
        f=draw(st.sampled_from([1.0, F, 12.5, 1e4])),
        ends=draw(ENDS),
    )


@st.composite
def scaleds(draw):
    params = RodParameters(
        P=draw(pos(0.0, 1.0)),
        R=draw(pos(1e-4, 1.0)),
        Gamma=draw(pos(1e-3, 10.0)),
        f=draw(st.sampled_from([1.0, F, 3.0, 1e3])),
        B=draw(pos(0.0, 1e4)),
        omega=draw(pos(0.0, 1e3)),
        T=draw(pos(-1e4, 1e4)),
        gamma=draw(pos(0.0, 1e2)),
        ends=draw(ENDS),
    )
    scales = Scales(
        length=draw(pos(1e-2, 1e5)),
        EI1=draw(pos(1e-6, 1e5)),
        mass_per_length=draw(pos(1e-6, 1e3)),
        f=params.f,
    )
    return Scaled(params=params, scales=scales)


def assert_same(a, b, rel=1e-12):
    da, db = dataclasses.asdict(a), dataclasses.asdict(b)
    assert da.keys() == db.keys()
    for key in da:
        x, y = da[key], db[key]
        if x is None:
            assert y is None, key
        elif isinstance(x, dict):
            for k2 in x:
                assert y[k2] == pytest.approx(x[k2], rel=rel, abs=1e-300), f"{key}.{k2}"
        elif key == "ends":
            assert x == y
        else:
            assert y == pytest.approx(x, rel=rel, abs=1e-300), key


@settings(max_examples=300, deadline=None)
@given(scenes())
def test_unscale_scale_round_trip(s):
    back = unscale(scale(s))
    assert_same(s, back)


@settings(max_examples=300, deadline=None)
@given(scaleds())
def test_scale_unscale_round_trip(scaled):
    again = scale(unscale(scaled))
    assert_same(scaled.params, again.params)
    assert_same(scaled.scales, again.scales)


@settings(max_examples=200, deadline=None)
@given(scenes())
def test_scale_matches_definitions(s):
    """eq. (36) written out again: omega_c = sqrt(f EI1/(rho A L^4)), B = I B0 L^3/(f EI1), ..."""
    p = scale(s).params
    wc = math.sqrt(s.f * s.EI1 / s.mass_per_length) / s.length**2
    assert p.R == pytest.approx(s.EI2 / s.EI1, rel=1e-13)
    assert p.Gamma == pytest.approx(2 * s.GJ / (s.EI1 + s.EI2), rel=1e-13)
    assert p.P == s.P
    assert p.f == s.f
    assert p.B == pytest.approx(s.load * s.length**3 / (s.f * s.EI1), rel=1e-12, abs=1e-300)
    assert p.T == pytest.approx(s.tension * s.length**2 / (s.f * s.EI1), rel=1e-12, abs=1e-300)
    assert p.omega == pytest.approx(s.spin_rate / wc, rel=1e-12, abs=1e-300)
    assert p.gamma == pytest.approx(s.damping_time * wc, rel=1e-12, abs=1e-300)


@settings(max_examples=200, deadline=None)
@given(scenes(), pos(1e-2, 1e2))
def test_length_scaling_laws(s, k):
    """docs/scaling.md: B ∝ L^3, P ∝ L^-2, T ∝ L^2, omega ∝ L^2, gamma ∝ L^-2; R, Gamma, f fixed."""
    p0 = scale(s).params
    p1 = scale(with_length(s, s.length * k)).params
    assert p1.B == pytest.approx(p0.B * k**3, rel=1e-12, abs=1e-300)
    assert p1.P == pytest.approx(p0.P / k**2, rel=1e-12, abs=1e-300)
    assert p1.T == pytest.approx(p0.T * k**2, rel=1e-12, abs=1e-300)
    assert p1.omega == pytest.approx(p0.omega * k**2, rel=1e-12, abs=1e-300)
    assert p1.gamma == pytest.approx(p0.gamma / k**2, rel=1e-12, abs=1e-300)
    assert p1.R == p0.R and p1.Gamma == p0.Gamma and p1.f == p0.f


def test_with_length_keeps_physical_properties():
    s = scene(load_mission(MISSIONS / "set.toml"))
    s2 = with_length(s, 250.0)
    assert s2.length == 250.0
    for name in ("EI1", "EI2", "GJ", "mass_per_length", "load", "spin_rate", "tension", "damping_time", "f"):
        assert getattr(s2, name) == getattr(s, name)


def test_scales_definitions():
    sc = Scales(length=100.0, EI1=38.0, mass_per_length=0.1, f=F)
    assert sc.frequency == pytest.approx(math.sqrt(F * 38.0 / (0.1 * 100.0**4)), rel=1e-14)
    assert sc.force == pytest.approx(F * 38.0 / 100.0**2, rel=1e-14)
    assert sc.load == pytest.approx(F * 38.0 / 100.0**3, rel=1e-14)


def test_f_default_is_first_clamped_root():
    s = scene(load_mission(MISSIONS / "set.toml"))
    assert s.f == pytest.approx(F, rel=1e-13)
    assert s.f == pytest.approx(500.5639, abs=1e-4)


def test_set_dimensionless_numbers():
    m = load_mission(MISSIONS / "set.toml")
    s = scene(m)
    p = scale(s).params
    assert p.R == pytest.approx(21 / 38, rel=1e-14)
    assert p.R == pytest.approx(0.5526, abs=1e-4)
    assert p.Gamma == pytest.approx(1 / 1.3, rel=1e-14)
    assert p.Gamma == pytest.approx(0.76923, abs=1e-5)
    assert p.P == pytest.approx(0.001, rel=1e-14)
    # I = 1 A, B0 = 70 uT, L = 100 m, EI1 = 38 N m2
    assert s.load == pytest.approx(70e-6, rel=1e-14)
    assert p.B == pytest.approx(1.0 * 70e-6 * 100.0**3 / (F * 38.0), rel=1e-12)
    # spin: the paper's omega = 0.25 written as 0.1041 rpm in the mission (4 digits)
    assert p.omega == pytest.approx(0.25, abs=1e-4)
    assert p.T == 0.0
    # no damping_time in set.toml: the paper's gamma = 0.04375 is assumed
    assert p.gamma == pytest.approx(0.04375, rel=1e-12)


def test_ranges_use_worst_case():
    m = load_mission(MISSIONS / "proseds.toml")
    s = scene(m)
    assert s.load == pytest.approx(1.5 * 40e-6, rel=1e-12)
    assert s.length == pytest.approx(5000.0)


@pytest.mark.parametrize("name", ["set.toml", "pmg.toml", "proseds.toml"])
def test_scene_holds_plain_floats(name):
    """Scene is "SI floats": plain Python floats, not numpy scalars (JSON-able downstream); the profiles along the
    tether ride beside them as their own frozen types."""
    s = scene(load_mission(MISSIONS / name))
    for field in dataclasses.fields(s):
        if field.name == "ends":  # the attachment: a pair of words
            assert len(s.ends) == 2 and all(e in KINDS for e in s.ends)
            continue
        if field.name in ("current_profile", "gravity_gradient"):
            continue
        if field.name == "field":  # the field vector: floats too
            assert all(type(v) is float for v in dataclasses.astuple(s.field)), field.name
            continue
        value = getattr(s, field.name)
        assert type(value) is float or (field.name == "axial_stiffness" and value is None), field.name
    for name_, value in dataclasses.asdict(scale(s).params).items():
        assert type(value) is (Ends if name_ == "ends" else float), name_  # Ends: the tuple of the two names
