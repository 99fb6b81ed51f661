"""The check of a tether with its current and tension along it (rung 1v): plan, margins that name the kind of
instability, damping honestly (the map when the mission does not fix it, the given value when it does), the
uniform smallest tension as a bound, no coil after flutter, results that validate, and sweeps that carry the
profiles and recompute the gravity-gradient tension at every length."""

from __future__ import annotations

import copy
import math

import pytest

from etcheck.checks.pipeline import check
from etcheck.input.mission import mission_from_dict
from etcheck.rod.straight.varying.circulatory import critical
from etcheck.scaling import scale, scene, with_length

BASE = {
    "mission": {"name": "small bare"},
    "tether": {"length": "200 m", "bending_stiffness": ["38 N m2", "21 N m2"], "poisson_ratio": 0.3,
               "mass_per_length": "0.1 kg/m", "rotary_inertia_ratio": 0.001, "end_masses": ["50 kg", "50 kg"]},
    "operation": {"current": "1 A", "axial_field": "30 uT", "orbit_altitude": "400 km",
                  "current_profile": {"at": [0, 0.3, 1], "fraction": [1, 0.8, 0]}},
}


def _mission(**changes):
    d = copy.deepcopy(BASE)
    for table, fields in changes.items():
        d[table] = {k: v for k, v in (d.get(table, {}) | fields).items() if v is not None}
    return mission_from_dict(d)


@pytest.fixture(scope="module")
def bare() -> dict:
    return check(_mission()).results


def test_a_mission_with_profiles_goes_to_rung_1v(bare):
    assert bare["plan"]["route"] == "profiles" and bare["linear"]["route"] == "profiles"
    pr = bare["profiles"]
    assert pr["circulatory"] and pr["current"]["fraction"][0] == 1.0 and pr["current"]["fraction"][-1] == 0.0
    assert max(pr["tension"]["tension_N"]) > min(pr["tension"]["tension_N"])
    margin = bare["margins"][0]
    assert "flutter" in margin["why"] and margin["model"].startswith("rung 1v")
    assert bare["linear"]["critical_load"]["kind"] == "flutter"


def test_the_verdict_takes_the_least_favourable_damping_and_says_so(bare):
    pr = bare["profiles"]
    damping = pr["damping"]
    assert not damping["fixed"] and len(damping["map"]) == 5 and "least favourable" in damping["why"]
    values = [q["B"] for q in damping["map"]] + [pr["undamped"]["value"]]
    assert bare["linear"]["critical_load"]["value"] == pytest.approx(min(values), rel=1e-12)
    # each map point is the rung's own answer at that damping (Ziegler: small damping lowers the threshold)
    q = damping["map"][0]
    t = scale(scene(_mission())).tether.with_(gamma=q["gamma"])
    assert critical(t, mode=False).value == pytest.approx(q["B"], rel=1e-6)
    assert q["destabilised"] == (q["B"] < pr["undamped"]["value"])


def test_a_fixed_damping_is_used_with_the_undamped_threshold_beside_it(bare):
    fixed = check(_mission(tether={"damping_time": "2 s"})).results
    pr = fixed["profiles"]
    assert pr["damping"]["fixed"] and pr["damping"]["map"] == [] and "fixes the damping" in pr["damping"]["why"]
    assert pr["undamped"]["value"] == pytest.approx(bare["profiles"]["undamped"]["value"], rel=1e-8)
    gamma = pr["damping"]["gamma"]
    t = scale(scene(_mission(tether={"damping_time": "2 s"}))).tether
    assert t.params.gamma == pytest.approx(gamma)
    assert fixed["linear"]["critical_load"]["value"] == pytest.approx(critical(t, mode=False).value, rel=1e-8)


def test_the_uniform_smallest_tension_is_a_bound(bare):
    bound = bare["profiles"]["uniform_tension_bound"]
    assert bound is not None and bound["value"] < bare["linear"]["critical_load"]["value"]


def test_flutter_draws_no_coil(bare):
    assert "no coil is drawn" in bare["profiles"]["post_buckling"]
    post = bare["postbuckling"]
    assert post is None or (not post["computed"] and "flutter" in post["reason"])
    # past the threshold the rungs of the coil are not run
    heavy = check(_mission(operation={"current": "30 A"})).results
    assert heavy["postbuckling"]["computed"] is False and "flutter" in heavy["postbuckling"]["reason"]


def test_a_round_wire_with_a_varying_current_never_passes_undamped():
    wire = _mission(tether={"bending_stiffness": "38 N m2", "damping_time": "0 s"})
    results = check(wire).results
    assert results["linear"]["critical_load"]["value"] == 0.0
    assert results["linear"]["critical_load"]["kind"] == "flutter" and results["verdict"] == "fail"


def test_a_uniform_current_with_end_masses_is_conservative():
    """One current, the gravity-gradient tension along the tether: rung 1v at the mission's damping, no map; the
    tension profile gives a higher critical load than its smallest value held constant."""
    results = check(_mission(operation={"current_profile": None})).results
    pr = results["profiles"]
    assert not pr["circulatory"] and pr["current"] is None and pr["damping"]["map"] == [] and pr["undamped"] is None
    assert results["linear"]["critical_load"]["kind"] == "divergence"
    assert pr["uniform_tension_bound"]["value"] < results["linear"]["critical_load"]["value"]


def test_a_length_sweep_recomputes_the_gravity_gradient_tension():
    """The end bodies and the tether's own mass pull harder on a longer tether: the tension at 400 m is not the
    200 m tension (nor its dimensionless value scaled as L^2)."""
    base = scene(_mission())
    long = with_length(base, 400.0)
    gg = long.gravity_gradient
    assert gg.length == 400.0 and long.tension == gg.minimum > 1.9 * base.tension
    assert scale(long).tether.params.T > 4 * scale(base).tether.params.T  # T-bar grows faster than L^2


def test_a_sweep_point_with_profiles_is_solved_by_rung_1v():
    from etcheck.studies.sweep import point_key, solve_point

    sc = scale(scene(_mission()))
    r = solve_point(sc.params, 1e-8, tether=sc.tether, damping_fixed=False)
    assert r.model.startswith("rung 1v") and r.status == "ok"
    assert math.isclose(r.B_c, min(critical(sc.tether.with_(gamma=g), mode=False).value
                                      for g in (0.0, 1e-3 * sc.params.gamma, sc.params.gamma)), rel_tol=1e-8)
    uniform = scale(scene(_mission(operation={"current_profile": None})))
    assert point_key(sc.params, 1e-8, tether=sc.tether) != point_key(uniform.params, 1e-8, tether=uniform.tether)


def test_an_undamped_round_wire_with_a_tension_profile_is_stable_at_every_spin_below_its_load_at_rest():
    """One current (conservative), R = 1, undamped, spun: below the static load at rest no spin destabilises it,
    whatever the tension along it (a hyperbolic gyroscopic pencil); the spin margin is unlimited."""
    wire = _mission(tether={"bending_stiffness": "38 N m2", "damping_time": "0 s"},
                    operation={"current_profile": None, "spin_rate": "0.05 rpm"})
    results = check(wire).results
    spin = results["linear"]["critical_spin"]
    assert spin["kind"] == "never" and "every spin" in spin["message"]
    margin = next(g for g in results["margins"] if g["name"].startswith("spin"))
    assert margin["verdict"] == "pass" and margin["value"] is None


def test_a_draft_of_a_tether_that_flutters_at_any_load_undamped_skips_the_map():
    """Undamped, a round wire with a varying current flutters at any load: no damping can be less favourable, so a
    draft computes no damping map; the verdict (0, on two meshes) is the sign-off's."""
    wire = _mission(tether={"bending_stiffness": "38 N m2"})
    draft = check(wire.with_fidelity("draft")).results
    signoff = check(wire).results
    assert draft["profiles"]["damping"]["map"] == [] and "not computed in a draft" in draft["profiles"]["damping"]["why"]
    assert len(signoff["profiles"]["damping"]["map"]) == 5
    for r in (draft, signoff):
        assert r["linear"]["critical_load"]["value"] == 0.0 and r["verdict"] == "fail"


def test_a_draft_takes_a_tension_profile_under_one_current_at_its_smallest_value():
    """PMG (one current, its gravity-gradient tension along it): a draft answers on the uniform routes under the
    smallest tension held constant, the conservative bound the sign-off reports beside its profile's margin (the
    committed example's, located there by rung 1v); a current along the tether is never taken so (the tape's draft
    stays on rung 1v)."""
    import json
    from pathlib import Path

    from etcheck.checks.plan import DRAFT_BOUND, PROFILES
    from etcheck.input.mission import load_mission

    root = Path(__file__).resolve().parents[2]
    signed = json.loads((root / "reports" / "pmg" / "results.json").read_text())
    bound = signed["profiles"]["uniform_tension_bound"]["value"] / signed["scaled"]["B"]
    draft = check(load_mission(root / "missions" / "pmg.toml").with_fidelity("draft")).results
    assert draft["plan"]["route"] != PROFILES and DRAFT_BOUND in draft["plan"]["reason"]
    assert draft["margins"][0]["value"] == pytest.approx(bound, rel=1e-6)
    assert draft["margins"][0]["value"] < signed["margins"][0]["value"]  # conservative
    tape = check(load_mission(root / "missions" / "tape-tether.toml").with_fidelity("draft")).results
    assert tape["plan"]["route"] == PROFILES


@pytest.mark.parametrize("fidelity", ["auto", "draft"])
def test_a_check_with_profiles_on_two_cores_answers_as_on_one(bare, fidelity):
    """Rung 1v shares its parts between two cores (the damping map's survey beside the undamped threshold, the
    uniform-tension bound beside the margins under the other attachment): the same answers as one core computing
    them in turn, each located margin within its error."""
    from etcheck.rod.straight.varying.circulatory import forget
    from etcheck.runtime.parallel import serial

    mission = _mission().with_fidelity(fidelity)
    forget()
    two = bare if fidelity == "auto" else check(mission).results
    forget()
    with serial():
        one = check(mission).results
    for a, b in zip(one["margins"], two["margins"], strict=True):
        assert a["verdict"] == b["verdict"]
        assert b["value"] == pytest.approx(a["value"], rel=1e-6)
        for x, y in zip(a["alternatives"], b["alternatives"], strict=True):
            assert y["value"] == pytest.approx(x["value"], rel=1e-6)
    assert [q["B"] for q in one["profiles"]["damping"]["map"]] == \
        pytest.approx([q["B"] for q in two["profiles"]["damping"]["map"]], rel=1e-8)
    bounds = [r["profiles"]["uniform_tension_bound"] for r in (one, two)]
    assert (bounds[0] is None) == (bounds[1] is None) == (fidelity == "draft")
    if bounds[0] is not None:
        assert bounds[1]["value"] == pytest.approx(bounds[0]["value"], rel=1e-6)


def test_a_sign_off_with_profiles_maps_the_load_and_spin_plane_on_rung_1v(bare):
    """The stability map of a tether with profiles: MAP_ROWS spin rows at the verdict's damping, each stable from zero
    load up to rung 1v's own first crossing at that spin (at zero spin the verdict's); none in a draft."""
    from etcheck.checks.rungs.profiles import MAP_ROWS

    sm = bare["linear"]["stability_map"]
    rows = sm["stable_rows"]
    assert len(rows) == MAP_ROWS == len(sm["omega"]) and sm["max_growth"] is None
    load = bare["scales"]["load_N_per_m"]
    verdict = bare["linear"]["critical_load"]["value"]
    assert rows[0]["omega"] == 0.0 and rows[0]["IB0_N_per_m"] == [[0.0, pytest.approx(verdict * load, rel=1e-12)]]
    gamma = bare["profiles"]["damping"]["gamma"]
    t = scale(scene(_mission())).tether.with_(gamma=gamma)
    for row in (rows[1], rows[-2], rows[-1]):
        own = critical(t.with_(omega=row["omega"]), hi=sm["B"][-1], mode=False, check=False)
        if own.kind == "unstable at start" or own.value == 0:  # past the critical spin at zero load
            assert row["IB0_N_per_m"] == []
        else:
            end = row["IB0_N_per_m"][0][1] / load
            assert end == pytest.approx(min(own.value, sm["B"][-1]), rel=1e-6)
    draft = check(_mission().with_fidelity("draft")).results
    assert draft["linear"]["stability_map"] is None
