"""operation.current_profile: points along the tether, or orbital-motion-limited collection; clear errors naming
the field for bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from etcheck.errors import MissionError
from etcheck.input.current_profile import E_CHARGE, M_ELECTRON, OMLCollection, oml_current
from etcheck.input.mission import mission_from_dict


def _base(**operation) -> dict:
    return {
        "mission": {"name": "bare"},
        "tether": {"length": "500 m", "bending_stiffness": ["3.65 N m2", "9.33e-6 N m2"],
                   "torsional_stiffness": "1.4e-5 N m2", "mass_per_length": "2.7e-3 kg/m",
                   "cross_section_area": "1 mm2", "youngs_modulus": "70 GPa"},
        "operation": {"current": "1 A", "axial_field": "20 uT"} | operation,
    }


def _without_section(d: dict) -> None:
    """The tether's P given directly: no cross_section_area to take the conductive area from."""
    d["tether"].pop("cross_section_area")
    d["tether"].pop("youngs_modulus")
    d["tether"]["rotary_inertia_ratio"] = 1e-9


def test_points_are_read_as_given():
    m = mission_from_dict(_base(current_profile={"at": [0, 0.3, 1], "fraction": [0, 0.8, 1]}))
    cp = m.operation.current_profile
    assert cp.model == "given" and cp.at == (0.0, 0.3, 1.0) and cp.fraction == (0.0, 0.8, 1.0)
    assert cp.profile(np.array([0.15, 0.65])) == pytest.approx([0.4, 0.9])
    echo = m.echo().operation.current_profile
    assert echo.at == (0.0, 0.3, 1.0) and echo.collection is None
    assert any("piecewise linear" in n for n in m.provenance.notes)
    assert mission_from_dict(_base()).operation.current_profile is None  # no profile: one current, as before


@pytest.mark.parametrize("profile, field, words", [
    ({"at": [0, 0.5, 1], "fraction": [0, 1]}, "operation.current_profile.fraction", "2 fractions for 3 points"),
    ({"at": [0, 0.7, 0.5, 1], "fraction": [0, 1, 1, 1]}, "operation.current_profile.at", "rise strictly"),
    ({"at": [0.1, 1], "fraction": [0, 1]}, "operation.current_profile.at", "from 0 (the lower end)"),
    ({"at": [0, 1], "fraction": [0, 1.2]}, "operation.current_profile.fraction", "in [0, 1]"),
    ({"at": [0, 1], "fraction": [-0.1, 1]}, "operation.current_profile.fraction", "in [0, 1]"),
    ({"at": [0, 1], "fraction": [0, math.nan]}, "operation.current_profile.fraction", "finite"),
    ({"at": [0, 1], "fraction": [0, 0.5]}, "operation.current_profile.fraction", "largest fraction is 0.5"),
    ({"at": [0, 1], "fraction": ["0", "1"]}, "operation.current_profile.fraction", "plain numbers"),
    ({"at": [0, 1]}, "operation.current_profile.fraction", "missing"),
    ({"at": [0, 1], "fraction": [0, 1], "where": 1}, "operation.current_profile.where", "unknown key"),
    ("linear", "operation.current_profile", "unknown profile"),
    (3, "operation.current_profile", "expected a table"),
])
def test_bad_points_name_the_field(profile, field, words):
    with pytest.raises(MissionError) as exc:
        mission_from_dict(_base(current_profile=profile))
    assert exc.value.field == field and words in str(exc.value)


COLLECTION = {"plasma_density": "1e11 m-3", "motional_field": "0.15 V/m", "conductivity": "3.5e7 S/m",
              "perimeter": "50.08 mm"}


def test_oml_characteristic_length_is_the_papers():
    """L*^3 = 9 pi^2 m_e sigma^2 h^2 E_m / (128 e^3 N_e^2) for a tape of thickness h (A / p = h / 2)."""
    h, w = 40e-6, 25e-3
    c = OMLCollection(1e11, 0.15, 3.5e7, 2 * (w + h), w * h, 500.0)
    h_eq = 2 * c.conductive_area / c.perimeter
    ref = (9 * math.pi**2 * M_ELECTRON * 3.5e7**2 * h_eq**2 * 0.15 / (128 * E_CHARGE**3 * 1e22)) ** (1 / 3)
    assert c.characteristic_length == pytest.approx(ref, rel=1e-14)


def test_oml_short_tether_limit():
    """L << L*: the ohmic drop is negligible, the bias falls linearly and the current is
    i(xi) = (xi_L^(3/2) - (xi_L - xi)^(3/2)) / 2."""
    xi_L = 1e-3
    i, phi_a = oml_current(xi_L)
    x = np.linspace(0.0, 1.0, 11)
    ref = 0.5 * (xi_L**1.5 - (xi_L * (1 - x)) ** 1.5)
    assert phi_a == pytest.approx(xi_L, rel=1e-3)
    assert np.allclose(i(xi_L * x), ref, rtol=2e-3, atol=1e-12)


def test_oml_long_tether_saturates():
    """L >> L*: the current approaches the short-circuit current sigma E_m A over most of the tether."""
    i, _ = oml_current(30.0)
    assert 0.9 < float(i(30.0)) < 1.0
    assert float(i(15.0)) / float(i(30.0)) > 0.95


def test_oml_profile_in_a_mission():
    m = mission_from_dict(_base(current_profile="OML", collection=COLLECTION))
    cp = m.operation.current_profile
    assert cp.model == "orbital-motion-limited collection"
    assert cp.profile(np.array([0.0]))[0] == pytest.approx(1.0, abs=1e-9)  # largest at the lower (cathodic) end
    assert abs(cp.profile(np.array([1.0]))[0]) < 1e-9  # zero at the upper (anodic) end
    assert np.all(np.diff(cp.profile(np.linspace(0, 1, 201))) < 1e-12)  # falls towards the anode
    xi_L = 500.0 / cp.collection.characteristic_length
    i, _ = oml_current(xi_L)
    s = np.linspace(0.0, 1.0, 9)
    assert np.allclose(cp.profile(s), i(xi_L * (1 - s)) / i(xi_L), atol=1e-9)
    echo = m.echo().operation.current_profile.collection
    assert echo.length_ratio == pytest.approx(xi_L) and echo.anode_end == "upper"
    assert any("OML predicts a largest current" in n for n in m.provenance.notes)
    lower = mission_from_dict(_base(current_profile="OML", collection=COLLECTION | {"anode_end": "lower"}))
    assert np.allclose(lower.operation.current_profile.profile(s), cp.profile(1 - s), atol=1e-9)


@pytest.mark.parametrize("change, field, words", [
    (lambda d: d["operation"]["collection"].pop("plasma_density"), "operation.collection.plasma_density", "missing"),
    (lambda d: d["operation"]["collection"].update(motional_field="0.15 V"), "operation.collection.motional_field",
     "electric field"),
    (lambda d: d["operation"]["collection"].update(perimeter="-5 mm"), "operation.collection.perimeter", "positive"),
    (lambda d: d["operation"]["collection"].update(anode_end="top"), "operation.collection.anode_end", "upper"),
    (lambda d: d["operation"]["collection"].update(sheath="1 m"), "operation.collection.sheath", "unknown field"),
    (lambda d: d["operation"].pop("collection"), "operation.collection", "missing"),
    (lambda d: d["operation"].update(current_profile={"at": [0, 1], "fraction": [1, 0]}), "operation.collection",
     "without current_profile"),
    (_without_section, "operation.collection.conductive_area", "missing"),
])
def test_bad_collection_names_the_field(change, field, words):
    d = _base(current_profile="OML", collection=dict(COLLECTION))
    change(d)
    with pytest.raises(MissionError) as exc:
        mission_from_dict(d)
    assert exc.value.field == field and words in str(exc.value)
