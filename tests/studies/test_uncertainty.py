"""The uncertainty study (etcheck/studies/uncertainty.py): elasticities against closed forms and
an independent finite difference, probabilities against closed forms and an independent root
find, and the report section."""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest
from scipy import integrate, stats
from scipy.optimize import brentq

from etcheck import check, mission_from_dict
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.damped_critical import damped_critical
from etcheck.scaling import scale, scene
from etcheck.studies.uncertainty import (
    LOAD,
    LOAD0,
    NAMES,
    SPIN,
    failure_probabilities,
    margin_model,
    sensitivities,
    study,
)

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def mission(base: str = "set.toml", uncertainty: dict | None = None, **operation):
    data = tomllib.loads((MISSIONS / base).read_text())
    data["operation"] |= operation
    if uncertainty:
        data["uncertainty"] = uncertainty
    return mission_from_dict(data)


def elasticities(sens, kind):
    s = next(s for s in sens if s.margin == NAMES[kind])
    return {e.input: e.value for e in s.elasticities}


def test_rung0_elasticities_are_the_closed_form_exactly():
    model = margin_model(mission("set-static.toml"))
    e = elasticities(sensitivities(model), LOAD0)
    assert e == {"bending_stiffness": 1.0, "EI1": 0.5, "EI2": 0.5, "torsional_stiffness": 0.0, "mass_per_length": 0.0,
                 "length": -3.0, "current": -1.0, "axial_field": -1.0, "spin_rate": 0.0, "end_tension": 0.0,
                 "damping_time": 0.0}
    # and the margin itself is beta_1^3 sqrt(EI1 EI2) / (I B0 L^3)
    scaled = scale(scene(mission("set-static.toml")))
    critical = critical_loads(scaled.params.R, scaled.params.f, 1)[0] * scaled.scales.load  # I B0 [N/m]
    assert model.margins(model.values())[LOAD0] == pytest.approx(critical / (1.0 * 70e-6), rel=1e-13)


@pytest.mark.parametrize("ends", [["pinned", "pinned"], ["pinned", "welded"]])
def test_margin_model_takes_the_ends(ends):
    """The study's margins are the check's for the mission's ends: rung 0's closed form with their beta_1, and
    the pencils (spin) with their boundary rows."""
    for base, kind, name in (("set-static.toml", LOAD0, "magnetic load |I B0|"),
                             ("set.toml", SPIN, "spin rate at the operating load")):
        data = tomllib.loads((MISSIONS / base).read_text())
        data["tether"]["end_conditions"] = ends
        m = mission_from_dict(data)
        model = margin_model(m)
        got = model.margins(model.values())[kind]
        want = next(x["value"] for x in check(m).results["margins"] if x["name"] == name)
        assert got == pytest.approx(want, rel=1e-7)


def test_finite_differences_of_the_pencils_match_rung0_at_vanishing_spin():
    """With a spin of 1e-3 of omega_c the load margin is rung 0's to O(omega^2): the pencil route
    (no chi shortcut at omega > 0) differentiated numerically must give 1/2, 1/2, -3, -1, -1, 0."""
    m = mission(spin_rate="0.0001 rad/s")
    model = margin_model(m)
    assert model.kinds == (LOAD, SPIN) and scale(scene(m)).params.omega < 3e-3
    e = elasticities(sensitivities(model), LOAD)
    for k, v in {"EI1": 0.5, "EI2": 0.5, "length": -3.0, "current": -1.0, "axial_field": -1.0,
                 "mass_per_length": 0.0, "torsional_stiffness": 0.0, "damping_time": 0.0, "spin_rate": 0.0}.items():
        assert e[k] == pytest.approx(v, abs=2e-5), k


def test_elasticities_match_an_independent_physical_difference():
    """Perturb the mission itself (scene -> scale -> damped_critical) and compare with the chain rule."""
    m = mission()
    e_load = elasticities(sensitivities(margin_model(m)), LOAD)
    e_spin = elasticities(sensitivities(margin_model(m)), SPIN)
    sc = scene(m)
    h = 1e-4

    def margins(s):
        p = scale(s).params
        d = damped_critical(p, tol=1e-12)
        return d.critical_load.value / p.B, d.critical_spin.value / p.omega

    for key, field in (("length", "length"), ("mass_per_length", "mass_per_length"), ("EI2", "EI2")):
        x = getattr(sc, field)
        changes = {field: x * math.exp(h)}
        up = margins(replace(sc, **changes, P=sc.P * math.exp(-2 * h)) if field == "length" else replace(sc, **changes))
        changes = {field: x * math.exp(-h)}
        dn = margins(replace(sc, **changes, P=sc.P * math.exp(2 * h)) if field == "length" else replace(sc, **changes))
        fd = [(math.log(a) - math.log(b)) / (2 * h) for a, b in zip(up, dn)]
        assert e_load[key] == pytest.approx(fd[0], abs=1e-5), key
        assert e_spin[key] == pytest.approx(fd[1], abs=1e-5), key
    # scale invariances hold to the differencing error
    assert (e_load["EI1"] + e_load["EI2"] + e_load["mass_per_length"]) == pytest.approx(1.0, abs=1e-6)
    assert e_spin["mass_per_length"] - 0.5 * e_spin["spin_rate"] == pytest.approx(0.0, abs=1e-12)


def test_sampled_probability_against_the_lognormal_closed_form():
    """Rung 0 with lognormal EI1, EI2 and field: ln margin is normal with
    sigma^2 = s1^2/4 + s2^2/4 + sB^2, so P = Phi((ln req - ln m0) / sigma)."""
    m = mission("set-static.toml", {"EI1": {"distribution": "lognormal", "sigma": 0.2},
                                     "EI2": {"distribution": "lognormal", "sigma": 0.1},
                                     "axial_field": {"distribution": "lognormal", "sigma": "10 %"}})
    m = replace(m, required_margin=100.0)
    model = margin_model(m)
    (p,) = failure_probabilities(model, m.uncertainty)
    m0 = model.margins(model.values())[LOAD0]
    exact = stats.norm.cdf((math.log(100.0) - math.log(m0)) / math.sqrt(0.04 / 4 + 0.01 / 4 + 0.01))
    assert 5e-4 < exact < 2e-3
    assert p.settled and p.relative_half_width <= 0.1
    assert p.low <= exact <= p.high
    assert p.value == pytest.approx(exact, rel=0.1)


def test_sampled_probability_with_a_uniform_field_against_quadrature():
    m = mission("set-static.toml", {"bending_stiffness": {"distribution": "normal", "sigma": "20 %"},
                                     "axial_field": "±30 %"})
    m = replace(m, required_margin=130.0)
    model = margin_model(m)
    (p,) = failure_probabilities(model, m.uncertainty, target=0.05)
    m0 = model.margins(model.values())[LOAD0]
    lam = stats.truncnorm(-5.0, math.inf, loc=1.0, scale=0.2)

    def fail_given_field(b):  # margin = m0 * lam / b < req  <=>  lam < req b / m0
        return lam.cdf(130.0 * b / m0)

    exact = integrate.quad(fail_given_field, 0.7, 1.3, epsabs=1e-14)[0] / 0.6
    assert p.low <= exact <= p.high
    assert p.value == pytest.approx(exact, rel=0.05)


def test_pencil_probability_against_an_independent_root_find():
    """Spinning SET, normal stiffness factor only: the spin margin falls short below the factor
    lam* where it equals the required margin (found here by brentq on damped_critical)."""
    m = mission(uncertainty={"bending_stiffness": {"distribution": "normal", "sigma": "15 %"}})
    sc = scene(m)

    def spin_margin(lam):
        s = replace(sc, EI1=sc.EI1 * lam, EI2=sc.EI2 * lam, GJ=sc.GJ * lam)
        p = scale(s).params
        return damped_critical(p).critical_spin.value / p.omega

    lam_star = brentq(lambda x: spin_margin(x) - 2.0, 0.3, 1.0, xtol=1e-12)
    lam = stats.truncnorm(-1 / 0.15, math.inf, loc=1.0, scale=0.15)
    model = margin_model(m)
    probs = {p.margin: p for p in failure_probabilities(model, m.uncertainty, workers=1)}
    p = probs[NAMES[SPIN]]
    assert p.conditioned_on == "bending_stiffness" and p.samples == 1
    assert p.value == pytest.approx(lam.cdf(lam_star), rel=1e-6)


def test_undamped_spinning_mission_is_not_answered():
    data = tomllib.loads((MISSIONS / "set.toml").read_text())
    data["tether"]["damping_time"] = "0 s"
    data["uncertainty"] = {"axial_field": "±30 %"}
    m = mission_from_dict(data)
    model = margin_model(m)
    probs = failure_probabilities(model, m.uncertainty, sens=())
    assert probs and all(p.value is None and "undamped" in p.method for p in probs)


def test_report_section_renders():
    from etcheck.checks.pipeline import check
    from etcheck.report.html import render_html
    from etcheck.studies.uncertainty import attach, summary_lines

    m = mission("set-static.toml", {"bending_stiffness": "±15 %", "axial_field": {"distribution": "lognormal", "sigma": "30 %"}})
    results = attach(check(m).results, m)
    u = results["uncertainty"]
    assert [p["margin"] for p in u["probabilities"]] == [NAMES[LOAD0]]
    html = render_html(results)
    assert "Which input the margins hinge on" in html and "Tornado chart" in html
    section = html.split("Which input the margins hinge on", 1)[1]
    assert '<img src="data:image/png;base64,' in section.split("Tornado chart", 1)[0]  # the chart, drawn inline
    assert summary_lines(results)[0].startswith("  P(magnetic load |I B0| < 2) = ")


def test_study_without_table_gives_sensitivities_only():
    st = study(mission("set-static.toml"))
    assert st.probabilities == () and st.sensitivities[0].swings == ()
