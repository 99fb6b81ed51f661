"""Rungs 2-3 for users: bifurcation diagrams (etcheck diagram), lift-off, and the
post-buckling section of the check report when the scene needs it."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from helpers import set_like, tension_free

from etcheck.checks.margins.margin import needs_postbuckling
from etcheck.checks.pipeline import check
from etcheck.checks.results.sections_buckled import BuckledOperatingPoint, PostbucklingSection
from etcheck.checks.rungs.buckled import DiagramOptions, bifurcation_diagram
from etcheck.cli.main import main
from etcheck.input.mission import load_mission, mission_from_dict
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled.pitchforks import pitchfork_loads
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.collocation.spectral import divergence_loads
from etcheck.scaling import scale, scene

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def set_scaled():
    return scale(scene(load_mission(ROOT / "missions" / "set.toml")))


def _diagram(scaled, omega, **kw):
    return bifurcation_diagram(scaled.params.with_(omega=omega), scaled.scales, DiagramOptions(**kw))


@pytest.mark.slow  # 14 s: the check's diagram at rest; its pieces are tested in tests/rod (B* at 1.942, shapes at
# measure1 = 0.04, b1 stable up to B*, b12 unstable) and the diagram command below
def test_static_pair_b12_and_stability(set_scaled):
    d = _diagram(set_scaled, 0.0, branches=2, B_max=2.2)
    by = {b["label"]: b for b in d["branches"]}
    assert set(by) == {"b1", "b12", "b2"}
    B1 = critical_loads(set_scaled.params.R, set_scaled.params.f, 1)[0]
    for name in ("b1", "b2"):  # the degenerate pair starts at the analytic load
        assert by[name]["pitchfork_B"] == pytest.approx(B1, rel=1e-6)
    # shapes at measure1 = 0.04 (paper Fig. 7)
    assert by["b1"]["shapes"]["measure1=0.04"]["B"] == pytest.approx(0.595, rel=5e-3)
    assert by["b12"]["shapes"]["measure1=0.04"]["B"] == pytest.approx(0.605, rel=5e-3)
    # b1 stable up to its secondary pitchfork (Sec. VII A: B = 1.942), unstable after; b12 unstable
    brk = [q["B"] for q in by["b1"]["special"] if q["kind"] == "break"]
    assert brk and brk[0] == pytest.approx(1.942, abs=5e-4)
    for B, st in zip(by["b1"]["values"][1:], by["b1"]["stable"][1:]):
        assert st is (B < brk[0])
    assert not any(by["b12"]["stable"][2:-2])
    # the connecting branch has measure2 != 0, the primary ones measure2 = 0
    assert max(abs(v) for v in by["b12"]["measure2"]) > 1e-3
    assert max(abs(v) for v in by["b1"]["measure2"]) < 1e-10
    # physical units: deflection in metres = dimensionless x L
    L = set_scaled.scales.length
    assert np.allclose(by["b1"]["max_deflection_m"], np.asarray(by["b1"]["max_deflection"]) * L)
    json.dumps(d, allow_nan=False)


def test_spin_splits_the_pair_at_the_divergence_loads(set_scaled):
    d = _diagram(set_scaled, 0.25, branches=2, B_max=0.8, stability=False, connect=False)
    loads = {b["label"]: b["pitchfork_B"] for b in d["branches"]}
    div = divergence_loads(set_scaled.params.with_(omega=0.25), n=2)
    assert loads["b1"] == pytest.approx(div[0], rel=1e-8)
    assert loads["b2"] == pytest.approx(div[1], rel=1e-8)
    assert loads["b2"] - loads["b1"] > 1e-2


def test_lifted_off_b1_leaves_the_first_S1_pitchfork_to_b3(set_scaled):
    """The primary branches are started before the lift-off spins are known (as if none had lifted off): at
    omega = 0.75 b1 has lifted off, so the first pitchfork of class S1 is b3's and the range ends past it."""
    p = set_scaled.params.with_(omega=0.75)
    d = _diagram(set_scaled, 0.75, branches=2, stability=False, connect=False)
    assert [x["label"] for x in d["lifted_off"]] == ["b1"]
    by = {b["label"]: b for b in d["branches"]}
    assert list(by) == ["b2", "b3"] and by["b3"]["symmetry"] == "S1" and by["b2"]["symmetry"] == "S2"
    for label, which in (("b3", "S1"), ("b2", "S2")):
        assert by[label]["pitchfork_B"] == pitchfork_loads(p.with_(B=0.0), which, 32, 1).loads[0]
    # with b1 gone, b2's pitchfork is the first divergence load of the spinning straight tether (rung 1)
    assert by["b2"]["pitchfork_B"] == pytest.approx(divergence_loads(p, n=1)[0], rel=1e-8)
    assert d["lifted_off"][0]["liftoff_omega"] < 0.75
    assert d["B_max"] == pytest.approx(1.3 * by["b3"]["pitchfork_B"], rel=1e-9)  # past the highest pitchfork drawn


def test_a_guessed_branch_that_fails_is_not_needed_when_it_lifted_off(set_scaled, monkeypatch):
    """The primary branches are started before the lift-off spins are known: at omega = 0.75 the guess (b1, the
    first S1 pitchfork) is not needed (b1 lifted off; the diagram's branch is b2), so its failure costs nothing."""
    from etcheck.checks.rungs import buckled

    real = buckled.class_starts

    def s1_fails(params, which, ks, N):
        if which == "S1":
            raise ValueError("no pitchfork in class S1")
        return real(params, which, ks, N)

    monkeypatch.setattr(buckled, "class_starts", s1_fails)  # where the diagram starts a class's branches
    d = _diagram(set_scaled, 0.75, branches=1, B_max=0.6, stability=False, connect=False)
    assert [b["label"] for b in d["branches"]] == ["b2"] and [x["label"] for x in d["lifted_off"]] == ["b1"]


def test_eigenvalue_paths_only_along_the_branches_asked_for(set_scaled):
    d = _diagram(set_scaled, 0.25, branches=2, B_max=0.65, connect=False, paths=("b2",))
    assert d["paths_computed"] == ["b2"]
    assert ["eigenvalue_paths" in b for b in d["branches"]] == [False, True]
    assert all(b["stable"] for b in d["branches"])  # the stability of every state, paths or not
    assert not DiagramOptions(stability=False).with_paths("b1") and DiagramOptions(paths=None).with_paths("b7")


@pytest.mark.slow  # 4 s; the command on valid scenes: tests/cli/test_subcommand_properties.py
def test_diagram_command_writes_reports(tmp_path):
    code = main(["diagram", "missions/set.toml", "--spin", "0.25", "--branches", "1", "--B-max", "0.9",
                 "--no-stability", "--out", str(tmp_path)])
    assert code == 0
    folder = tmp_path / "set" / "diagram-w0.25"
    data = json.loads((folder / "diagram.json").read_text())
    assert data["diagram"]["branches"][0]["label"] == "b1"
    html = (folder / "diagram.html").read_text()
    assert "b1" in html and "against the maximum lateral deflection of the tether" in html  # figure caption
    assert (folder / "diagram.pdf").stat().st_size > 0


@pytest.mark.parametrize("args", [["--spin", "5 s"], ["--R", "2"], ["--branches", "0"], ["--spin", "-1"],
                                  ["--paths", "b1,x"]])
def test_diagram_bad_input_exits_2(args, tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        code = main(["diagram", "missions/set.toml", "--out", str(tmp_path), *args])
        raise SystemExit(code)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and any(x in err for x in ("--spin", "--R", "--branches", "--paths"))


# --- the check report gains a post-buckling section only when needed ---------------------------------


def test_needs_postbuckling_rule():
    assert needs_postbuckling(0.6, 0.5853, 2.0)
    assert needs_postbuckling(0.3, 0.5853, 2.0)  # within the required margin
    assert not needs_postbuckling(0.2, 0.5853, 2.0)
    assert not needs_postbuckling(0.0, 0.5853, 2.0)


def test_far_from_critical_has_no_postbuckling_section():
    res = check(ROOT / "missions" / "set-static.toml").results
    assert res["postbuckling"] is None
    from etcheck.report import render

    assert b"buckled tether (rungs" not in render(res, ("html",))["html"]


@pytest.fixture(scope="module")
def coiled():
    return check(ROOT / "missions" / "set-600m.toml").results


def test_past_critical_reports_the_buckled_state(coiled):
    res = coiled
    post = res["postbuckling"]
    assert post["computed"] and post["load_ratio"] > 1
    op = post["operating"]
    assert op["available"] and op["stable"]
    assert op["max_deflection_m"] == pytest.approx(op["max_deflection"] * res["scales"]["length_m"])
    assert op["deflection_error_m"] < 1e-3
    p = scale(scene(load_mission(ROOT / "missions" / "set-600m.toml"))).params
    shape = op["shape"]
    assert shape["s"][0] == 0.0
    margins = {m["name"]: m for m in res["margins"]}
    buckled = margins["buckled tether (b1): load to its secondary pitchfork"]
    assert buckled["verdict"] == "pass" and buckled["value"] == pytest.approx(1.9424625 / p.B, rel=1e-6)
    # the straight tether does buckle (its load margin fails), and the untensioned 600 m tether bows far past the
    # straight model's limit under a field across it as large as the one along it: outside the model's validity
    assert [m["verdict"] for m in res["margins"] if m["rung"] < 3] == ["fail"]
    assert res["verdict"] == "outside" and res["model_validity"]["lateral"]["bow_over_length"] > 1
    from etcheck.report import render

    html = render(res, ("html",))["html"].decode()
    assert "The buckled tether (rungs 2–3)" in html and "maximum lateral deflection at the operating load" in html


def test_operating_state_is_resolution_independent():
    from etcheck.checks.rungs.buckled import operating_state
    from etcheck.rod.buckled.branches import continue_branch, primary_branches, state_at

    sc = scale(scene(load_mission(ROOT / "missions" / "set-600m.toml")))
    p = sc.params
    a = operating_state(p, sc.scales, N=32)
    # the same state at N = 44: b1 continued from its pitchfork to the operating load (its stability and spectra are
    # not compared)
    start = next(s for s in primary_branches(p.with_(B=0.0), 1, 44) if s.which == "S1")
    b1 = continue_branch(p, start, stop=(0.0, p.B * (1 + 1e-9)), N=44, max_points=800)
    fine = eq.measures(state_at(b1, p.B))
    assert a["max_deflection_m"] == pytest.approx(fine.max_deflection * sc.scales.length, rel=1e-8)
    moment = sc.scales.force * sc.scales.length
    assert np.allclose(a["end_moment_N_m"]["s=0"], np.asarray(fine.M0) * moment, rtol=1e-7, atol=1e-12)
    assert a["max_deflection_m"] > 0.1 * sc.scales.length  # really buckled, not the straight state


def test_within_margin_but_straight():
    m = mission_from_dict(set_like(length="480 m", rotary_inertia_ratio=1e-3 * (100 / 480) ** 2))
    res = check(m).results
    post = res["postbuckling"]
    assert post["computed"] and post["load_ratio"] < 1 and post["operating"] is None
    assert post["diagram"]["branches"][0]["pitchfork_B"] == pytest.approx(post["B_c"], rel=1e-8)


def test_many_coils_are_not_attempted(tmp_path):
    res = check(tension_free(ROOT / "missions" / "pmg.toml", tmp_path)).results
    post = res["postbuckling"]
    assert post is not None and post["computed"] is False and "many coils" in post["reason"]
    assert math.isfinite(post["load_ratio"])


# --- rung 3 for users: the damping map (cf. Fig. 19) ------------------------------------------


@pytest.mark.slow  # 5 s; the command's properties: tests/studies/test_damping_map_properties.py
def test_damping_map_command(tmp_path):
    code = main(["damping-map", "missions/set.toml", "--points", "3x2", "--B-max", "2.4", "--spin-max", "0.5",
                 "--gammas", "0.01,0.04375", "--out", str(tmp_path)])
    assert code == 0
    folder = tmp_path / "set" / "damping-map"
    s = json.loads((folder / "damping.json").read_text())["study"]
    assert s["unstable_points"] == 0
    # the secondary pitchfork at rest is the paper's 1.942, and spin pushes it up (Sec. VIII)
    assert s["secondary_pitchfork_B"][0] == pytest.approx(1.942, abs=5e-4)
    assert s["secondary_pitchfork_B"][1] > s["secondary_pitchfork_B"][0]
    zeta = np.array(s["damping_ratio"], dtype=float)
    ok = np.isfinite(zeta)
    assert ok.any() and (zeta[ok] > 0).all()
    assert np.nanmin(zeta[1]) > np.nanmin(zeta[0])  # more damping, larger damping ratio
    assert s["spin_paths"]["max_re"] < 0  # b1 followed in spin: no mode crosses (no Hopf)
    assert (folder / "damping.html").stat().st_size > 0 and (folder / "damping.pdf").stat().st_size > 0


@pytest.mark.parametrize("args", [["--gammas", "0,1"], ["--points", "3"], ["--B-max", "-1"]])
def test_damping_map_bad_input_exits_2(args, tmp_path):
    with pytest.raises(SystemExit) as exc:
        main(["damping-map", "missions/set.toml", "--out", str(tmp_path), *args])
    assert exc.value.code == 2


def test_design_answer_for_a_coiled_tether(coiled):
    """Region, margins in N/m and rpm, and damping sensitivity in the check of a tether past BP1."""
    res = coiled
    post = res["postbuckling"]
    reg = post["region"]
    rows = reg["rows"]
    assert rows[0]["secondary_B"] == pytest.approx(1.94246, rel=1e-4)
    assert all(b["secondary_B"] > a["secondary_B"] for a, b in zip(rows[:-1], rows[1:]))  # spin raises B* (Sec. VIII)
    assert reg["lowest_stable_spin_rpm"] == 0.0  # B = 0.795 < B*(0): stable down to rest
    sens = post["operating"]["damping_sensitivity"]
    assert [d["factor"] for d in sens] == [0.25, 0.5, 1.0, 2.0, 4.0]
    ratios = [d["damping_ratio"] for d in sens]
    assert all(d["stable"] for d in sens) and ratios == sorted(ratios)
    assert sens[2]["damping_ratio"] == pytest.approx(post["operating"]["least_damped"]["damping_ratio"], rel=1e-6)
    from etcheck.report import render

    html = render(res, ("html",))["html"].decode()
    assert "Stable region of the coiled tether" in html and "How the damping moves the answer" in html


def _post(**kw) -> PostbucklingSection:
    """A postbuckling section with the operating state stable on b1 and no secondary pitchfork found."""
    fields = dict(B_c=1.0, load_ratio=1.5, computed=True, secondary_pitchfork_B=None,
                  secondary_pitchfork_error=None, secondary_pitchfork_IB0_N_per_m=None,
                  secondary_pitchfork_reason="no secondary pitchfork on b1 in the computed range",
                  b1_stable_to_B=None, b1_stable_to_IB0_N_per_m=None,
                  operating=BuckledOperatingPoint(available=True, stable=True))
    return PostbucklingSection(**fields | kw)


@pytest.mark.parametrize("bound, verdict", [(None, "incomplete"), (3.0, "pass"), (1.5, "incomplete")])
def test_buckled_margin_from_a_stable_b1_without_pitchfork(bound, verdict):
    """No secondary pitchfork on b1 and every state past the operating load stable: the margin is a lower
    bound (the end of b1's computed range): a pass where it reaches the required margin, else not answered
    (with the bound in the reason); never a fail. An unstable operating state is a fail whatever B* is."""
    from types import SimpleNamespace

    from etcheck.checks.margins.margin import buckled_margins

    sc = SimpleNamespace(load=1.0)
    (m,) = buckled_margins(_post(b1_stable_to_IB0_N_per_m=bound), sc, None, 2.0)
    assert m.verdict == verdict
    if bound == 3.0:
        assert m.value == 3.0 and "lower bound" in m.why
    if bound == 1.5:
        assert m.value is None and "at least 1.5" in m.why
    (m,) = buckled_margins(_post(operating=BuckledOperatingPoint(available=True, stable=False)), sc, None, 2.0)
    assert m.verdict == "fail" and m.value == 0.0


@pytest.mark.slow  # 15 s
def test_stable_coil_without_pitchfork_passes_on_its_lower_bound():
    """R = 0.1, 81 m, just past its critical load: b1 stays stable far past the search range (its secondary
    pitchfork lies at ~32 times its start); with required margin 2 the lower bound proves the buckled margin
    (it was "not answered")."""
    data = {"mission": {"name": "stable-coil", "description": "found by the scene-space exploration"},
            "tether": {"length": "80.88328726056459 m",
                       "bending_stiffness": ["0.0018555265566972173 N m2", "0.00018555265566972174 N m2"],
                       "poisson_ratio": 0.3, "mass_per_length": "0.00624847300886438 kg/m",
                       "rotary_inertia_ratio": 0.001},
            "operation": {"current": "0.014584528459017611 A", "axial_field": "30.0 uT",
                          "spin_rate": "5.8933035972854645e-05 rad/s", "end_tension": "0 N"},
            "check": {"required_margin": 2, "fidelity": "auto"}}
    results = check(mission_from_dict(data)).results
    buckled = next(m for m in results["margins"] if m["name"].startswith("buckled"))
    assert buckled["verdict"] == "pass" and buckled["value"] >= 2 and "lower bound" in buckled["why"]
    assert results["postbuckling"]["b1_stable_to_B"] is not None


def test_special_points_carry_the_measures_of_their_located_state(set_scaled):
    """The figures mark a special point at its own measures: those of the located state (the nearer end of its final
    bracket), in the units of the branch's own arrays."""
    from etcheck.checks.rungs import buckled

    dg = buckled.diagram(set_scaled.params.with_(omega=0.25), set_scaled.scales,
                         DiagramOptions(branches=1, B_max=2.2, stability=False, connect=False))
    d, kept = dg.record, dg.branches
    (brk,) = [q for q in d["branches"][0]["special"] if q["kind"] == "break"]
    (q,) = [q for q in kept["b1"].special if q.kind == "break"]
    ms = eq.measures(q.state)
    L = set_scaled.scales.length
    assert brk["B"] == q.value and brk["measure1"] == ms.measure1 == q.measure1
    assert brk["measure2"] == ms.measure2 and brk["max_deflection_m"] == ms.max_deflection * L
