"""Gravity-gradient tension (issue 16 item 2): the profile against hand-computed cases and an
independent discrete sum, the parser's errors naming their fields, and the shipped missions."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from etcheck import MissionError, load_mission, mission_from_dict
from etcheck.checks.pipeline import scene_section
from etcheck.input.gravity_gradient import MU_EARTH, R_EARTH, GravityGradient, apogee_rate, circular_rate
from etcheck.scaling import scene

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def test_massless_tether_has_one_tension_by_hand():
    """Two end masses on a massless tether: the centre of mass divides L as m_l : m_u and the tension is
    3 Omega^2 m_u (L - h_c) = 3 Omega^2 m_l h_c = 3 Omega^2 m_u m_l L / (m_u + m_l) everywhere."""
    g = GravityGradient(20.0, 1.5, 1000.0, 0.0, 1.1e-3)
    assert g.centre_of_mass == pytest.approx(20.0 * 1000.0 / 21.5, rel=1e-15)  # 930.23 m above the lower end
    T = 3 * 1.1e-3**2 * 20.0 * 1.5 * 1000.0 / 21.5  # = 5.0651e-3 N
    assert T == pytest.approx(5.0651162790697674e-3, rel=1e-12)
    for value in (g.upper_end, g.lower_end, g.minimum, g.maximum, g.at(0.0), g.at(500.0), g.at(1000.0)):
        assert value == pytest.approx(T, rel=1e-13)


def test_heavy_tether_with_one_free_end_by_hand():
    """m_u = 10 kg, no lower body, 1000 m of 0.01 kg/m (10 kg): h_c = (10*1000 + 0.01*1000^2/2)/20 = 750 m;
    upper end 3 W^2 * 10 * 250, free lower end 0, centre 3 W^2 (10*250 + 0.01*250^2/2) = 3 W^2 * 2812.5."""
    W = 1.2e-3
    g = GravityGradient(10.0, 0.0, 1000.0, 0.01, W)
    assert g.centre_of_mass == pytest.approx(750.0, rel=1e-15)
    assert g.upper_end == pytest.approx(3 * W**2 * 2500.0, rel=1e-14)
    assert g.lower_end == 0.0 and g.minimum == 0.0 and g.minimum_at == "lower end"
    assert g.maximum == pytest.approx(3 * W**2 * 2812.5, rel=1e-14)
    # below the centre of mass the far side is the tether below: 3 W^2 * 0.01 * h (750 - h/2)
    assert g.at(300.0) == pytest.approx(3 * W**2 * 0.01 * 300.0 * (750.0 - 150.0), rel=1e-13)


@pytest.mark.parametrize("m_u, m_l, mu", [(950.0, 20.0, 8e-3), (20.0, 950.0, 3.05e-3), (12.0, 12.0, 2.7e-3), (0.5, 3.0, 0.02)])
def test_profile_against_a_discrete_sum(m_u, m_l, mu):
    """Independent: the tether as n equal point masses at cell midpoints (the first moment of each cell is
    exact for a linear integrand); tension at a cell boundary = 3 W^2 * sum over the far side of m (x - x_c)."""
    L, W, n = 5000.0, 1.14e-3, 4000
    g = GravityGradient(m_u, m_l, L, mu, W)
    x = np.concatenate([[0.0], (np.arange(n) + 0.5) * L / n, [L]])
    m = np.concatenate([[m_l], np.full(n, mu * L / n), [m_u]])
    xc = float(np.sum(m * x) / np.sum(m))
    assert g.centre_of_mass == pytest.approx(xc, rel=1e-12)
    for k in (0, 1, 800, 2000, 3999, 4000):  # boundary between cell k-1 and k: height k L / n
        h = k * L / n
        above = x > h if k < n else x >= L
        T = 3 * W**2 * float(np.sum(m[above] * (x[above] - xc)))
        assert g.at(h) == pytest.approx(T, rel=1e-10, abs=1e-15)
    # largest at the centre of mass, smallest at the end farther from it
    hs = np.linspace(0.0, L, 1001)
    Ts = np.array([g.at(h) for h in hs])
    assert g.maximum == pytest.approx(g.at(g.centre_of_mass), rel=1e-15) and Ts.max() <= g.maximum * (1 + 1e-14)
    assert Ts.min() == pytest.approx(g.minimum, rel=1e-13)
    far = "upper end" if L - g.centre_of_mass >= g.centre_of_mass else "lower end"
    assert g.minimum_at == far or g.upper_end == pytest.approx(g.lower_end, rel=1e-12)


def test_orbit_rates():
    """Circular mean motion by hand at 350 km, the apogee rule, and the constants of etcheck.orbit."""
    from etcheck.orbit import elements

    assert (MU_EARTH, R_EARTH) == (elements.MU_EARTH, elements.R_EARTH)
    assert circular_rate(350e3) == pytest.approx(math.sqrt(3.986004418e14 / 6728137.0**3), rel=1e-15)
    assert circular_rate(350e3) == pytest.approx(1.14400e-3, rel=1e-5)
    assert apogee_rate(400e3, 400e3) == pytest.approx(circular_rate(400e3), rel=1e-15)
    # PMG, 192 x 850 km: e = 0.047687, 3 W^2 = (3 - e) mu / r_a^3 -> W = 1.0192e-3 rad/s (the mission file's value)
    ra, e = R_EARTH + 850e3, 658e3 / (2 * R_EARTH + 1042e3)
    assert apogee_rate(192e3, 850e3) == pytest.approx(math.sqrt((3 - e) * MU_EARTH / (3 * ra**3)), rel=1e-14)
    assert apogee_rate(192e3, 850e3) == pytest.approx(1.0192e-3, rel=5e-5)
    assert apogee_rate(192e3, 850e3) < circular_rate(850e3)  # below even the circular rate at apogee


def _base() -> dict:
    return {
        "mission": {"name": "gg"},
        "tether": {"length": "1000 m", "bending_stiffness": "1e-3 N m2", "poisson_ratio": 0.3,
                   "mass_per_length": "0.01 kg/m", "rotary_inertia_ratio": 1e-9, "end_masses": ["10 kg", "2 kg"]},
        "operation": {"current": "1 A", "axial_field": "30 uT", "orbit_rate": "1.1e-3 rad/s"},
    }


def test_mission_tension_is_the_profile_with_the_minimum_as_a_bound():
    m = mission_from_dict(_base())
    g = GravityGradient(10.0, 2.0, 1000.0, 0.01, 1.1e-3, "operation.orbit_rate")
    assert m.operation.gravity_gradient == g
    assert m.operation.end_tension.to_value("N") == g.minimum > 0
    assert m.echo().operation.gravity_gradient.minimum_N == g.minimum
    assert m.echo().operation.gravity_gradient.used == "profile"
    assert any("uses this profile" in n and "as a bound" in n for n in m.provenance.notes)
    s = np.linspace(0.0, 1.0, 11)
    assert np.allclose(g.shape()(s) * g.maximum, [g.at(x * g.length) for x in s], rtol=1e-13)
    d = _base()
    d["operation"] = {"current": "1 A", "axial_field": "30 uT", "orbit_altitude": "350 km"}
    assert mission_from_dict(d).operation.gravity_gradient.orbit_rate == pytest.approx(circular_rate(350e3), rel=1e-15)


def _error(change) -> MissionError:
    d = _base()
    change(d)
    with pytest.raises(MissionError) as exc:
        mission_from_dict(d)
    return exc.value


@pytest.mark.parametrize("change, field, words", [
    (lambda d: d["operation"].update(end_tension="0.2 N"), "operation.end_tension", "both"),
    (lambda d: d["operation"].pop("orbit_rate"), "operation.orbit_rate", "without the orbit rate"),
    (lambda d: d["operation"].update(orbit_altitude="350 km"), "operation.orbit_altitude", "both"),
    (lambda d: d["tether"].pop("end_masses"), "operation.orbit_rate", "without tether.end_masses"),
    (lambda d: d["tether"].update(end_masses=["10 kg", "-2 kg"]), "tether.end_masses", ">= 0"),
    (lambda d: d["tether"].update(end_masses=["nan kg", "2 kg"]), "tether.end_masses", "finite"),
    (lambda d: d["tether"].update(end_masses=["10 kg"]), "tether.end_masses", "two masses"),
    (lambda d: d["tether"].update(end_masses="10 kg"), "tether.end_masses", "two masses"),
    (lambda d: d["tether"].update(end_masses=["10 m", "2 kg"]), "tether.end_masses", "a mass"),
    (lambda d: d["tether"].update(end_masses=[10, 2]), "tether.end_masses", "no unit"),
    (lambda d: d["operation"].update(orbit_rate="0 rad/s"), "operation.orbit_rate", "positive"),
    (lambda d: d["operation"].update(orbit_rate="3 N"), "operation.orbit_rate", "expected"),
    (lambda d: (d["operation"].pop("orbit_rate"), d["operation"].update(orbit_altitude="10 km")),
     "operation.orbit_altitude", "between"),
    (lambda d: d["tether"].update(end_mass=["1 kg", "1 kg"]), "tether.end_mass", "end_masses"),
])
def test_errors_name_the_field(change, field, words):
    exc = _error(change)
    assert exc.field == field and exc.exit_code == 2
    assert words in str(exc), str(exc)


@pytest.mark.parametrize("name, at, lo, hi", [
    ("pmg", "lower end", 0.030, 0.031),        # 950 kg stage above a 20 kg end package, 1.0192e-3 rad/s
    ("proseds", "upper end", 0.37, 0.39),      # 20 kg endmass above a 950 kg stage, 360 km circular
])
def test_shipped_missions_carry_gravity_gradient_tension(name, at, lo, hi):
    m = load_mission(MISSIONS / f"{name}.toml")
    g = m.operation.gravity_gradient
    assert g is not None and g.minimum_at == at and lo < m.operation.end_tension.to_value("N") == g.minimum < hi
    assert g.maximum > g.minimum
    sd = scene_section(scene(m))
    assert sd.tension_N == g.minimum and sd.tension_profile.minimum_N == g.minimum


def test_tape_tether_mission_takes_its_rate_from_the_orbit():
    """The tape mission's [orbit] (600 km circular) gives the rate; equal 12 kg ends: 0.01056 N at each end."""
    m = load_mission(MISSIONS / "tape-tether.toml")
    g = m.operation.gravity_gradient
    assert g.orbit_rate == pytest.approx(circular_rate(600e3), rel=1e-12) and "[orbit]" in g.rate_source
    assert g.minimum == pytest.approx(3 * circular_rate(600e3) ** 2 * 12.0 * 250.0, rel=1e-14)
    assert m.operation.end_tension.to_value("N") == pytest.approx(0.010558, rel=1e-4)
    EI1, EI2 = (x.to_value("N m2") for x in m.tether.bending_stiffness)
    assert EI2 / EI1 == pytest.approx(2.56e-6, rel=1e-2)


def test_orbit_table_and_a_rate_are_refused_together():
    with open(MISSIONS / "tape-tether.toml", "rb") as fh:
        d = tomllib.load(fh)
    d["operation"]["orbit_rate"] = "1.1e-3 rad/s"
    with pytest.raises(MissionError) as exc:
        mission_from_dict(d)
    assert exc.value.field == "operation.orbit_rate" and "[orbit]" in str(exc.value)
