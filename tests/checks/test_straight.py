"""Rung 1 in the check: planner, margins, report content, solver failures.

Reference values come from tests/independent.py (exact shooting of the
straight rod at lambda = 0), not from the Chebyshev solver under test.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from helpers import set_like
from independent import first_static_load, first_static_spin

from etcheck import check, mission_from_dict
from etcheck.checks.rungs.straight import WhirlOptions
from etcheck.cli.main import main as cli_main

ROOT = Path(__file__).resolve().parents[2]
LIGHT = WhirlOptions(map_points=6, campbell_points=6, accuracy_N=(8, 12))


def mission(spin="0 rpm", tension="0 N", damping=None, fidelity="auto", R_stiff="21 N m2", current="1 A"):
    extra = {} if damping is None else {"damping_time": damping}
    return mission_from_dict(
        set_like(
            name="whirl test",
            check={"fidelity": fidelity},
            bending_stiffness=["38 N m2", R_stiff],
            spin_rate=spin,
            end_tension=tension,
            current=current,
            **extra,
        )
    )


def test_rung1_at_rest_reproduces_rung0():
    r0 = check(mission()).results
    r1 = check(mission(fidelity="linear"), LIGHT).results
    assert r0["plan"]["rung"] == 0 and r1["plan"]["rung"] == 1
    m0, m1 = r0["margins"][0], r1["margins"][0]
    assert m1["rung"] == 1
    assert m1["value"] == pytest.approx(m0["value"], rel=1e-8)
    assert r1["linear"]["critical_load"]["value"] == pytest.approx(r0["straight_rod"]["critical_loads"][0]["B"], rel=1e-8)


@pytest.mark.parametrize(
    "spin, tension, R_stiff",
    [("0.05 rpm", "0 N", "21 N m2"), ("0 rpm", "0.4 N", "11 N m2"), ("0.08 rpm", "-0.05 N", "30 N m2")],
)
def test_margins_against_shooting(spin, tension, R_stiff):
    result = check(mission(spin=spin, tension=tension, R_stiff=R_stiff), LIGHT)
    r = result.results
    p = r["scaled"]
    assert r["plan"]["rung"] == 1
    # the 50-digit shooting under tension is slow: a scan of (0, 1.1 x the check's value] on 12 points (the
    # static loads of R < 1 are simple and more than twice the first apart: a lower one would show), then Brent
    B_max = 2.5 if p["T"] == 0 else 1.1 * r["linear"]["critical_load"]["value"]
    B_c = first_static_load(p["P"], p["R"], p["f"], p["omega"], p["T"], B_max=B_max, n=2000 if p["T"] == 0 else 12)
    load = r["margins"][0]
    assert load["value"] == pytest.approx(B_c / p["B"], rel=1e-8)
    assert load["critical"] == pytest.approx(B_c * r["scales"]["load_N_per_m"], rel=1e-8)
    if p["omega"] > 0:
        w_c = first_static_spin(p["P"], p["R"], p["f"], p["B"], p["T"], w_max=2.0)
        spin_margin = r["margins"][1]
        assert spin_margin["value"] == pytest.approx(w_c / p["omega"], rel=1e-8)
        assert spin_margin["unit"] == "rpm"
    else:
        assert len(r["margins"]) == 1  # no spin margin without spin
    json.dumps(r, allow_nan=False)


def test_spin_above_critical_with_damping_fails_at_any_load():
    # omega = 0.75 (above sqrt(R) = 0.743...): with damping no stable straight state (Sec. VII B)
    wc = 0.043613  # rad/s, omega_c of this tether
    spin = f"{0.75 * wc * 60 / (2 * 3.141592653589793)} rpm"
    result = check(mission(spin=spin), LIGHT)
    load = result.results["margins"][0]
    assert result.results["linear"]["critical_load"]["kind"] == "unstable at start"
    assert load["verdict"] == "fail" and load["value"] == 0
    assert result.exit_code == 1


def test_undamped_windows_are_reported():
    # without damping the straight SET rod at B = 0 re-stabilises above its critical spin
    result = check(mission(spin="0.05 rpm", damping="0 s", current="0 A"), LIGHT)
    windows = result.results["linear"]["spin_windows"]
    assert len(windows) >= 2, windows
    assert windows[0]["omega"][0] == 0.0
    assert windows[0]["omega"][1] == pytest.approx(first_static_spin(0.001, 21 / 38, 4.730040744862704**4, 0.0, 0.0, w_max=1.0), rel=1e-8)


def test_report_shows_campbell_and_map(tmp_path):
    from etcheck.report import render

    r = check(mission(spin="0.05 rpm"), LIGHT).results
    out = render(r, ("html", "pdf"))
    html = out["html"].decode()
    for text in ("Campbell diagram", "Stability of the straight tether in the plane of magnetic load and spin rate",
                 "rung 1 (linear spectral)", "Speed and accuracy of rung 1", "operating point"):
        assert text in html, text
    assert html.count("<svg") + html.count("<img") >= 4  # the figures, inline SVG or PNG
    assert out["pdf"].startswith(b"%PDF-")


def test_unconverged_operating_spectrum_is_shown_not_fatal(tmp_path, monkeypatch, capsys):
    """An operating spectrum that misses its tolerance is reported as such (its message), and the
    margins, which do not depend on it, are still answered: no exit 3."""
    import etcheck.checks.rungs.straight as whirl

    real = whirl.spectrum

    def not_converged(*args, **kwargs):
        s = real(*args, **kwargs)
        return type(s)(**{**s.__dict__, "converged": False, "message": "forced for the test"})

    monkeypatch.setattr(whirl, "spectrum", not_converged)
    path = tmp_path / "m.toml"
    path.write_text((ROOT / "missions" / "set.toml").read_text())
    rc = cli_main([str(path), "--out", str(tmp_path / "out"), "--format", "json"])
    err = capsys.readouterr().err
    assert rc == 0 and "Traceback" not in err
    results = json.loads((tmp_path / "out" / "set" / "results.json").read_text())
    assert results["linear"]["operating_spectrum"]["message"].startswith("NOT CONVERGED")
    assert "forced for the test" in results["linear"]["operating_spectrum"]["message"]


@pytest.mark.parametrize("error, outcome", [(3e-8, "kept"), (0.5, "not located")])
def test_unconverged_critical_value_carries_its_error_or_is_not_located(monkeypatch, error, outcome):
    """A critical value whose error estimate misses the tolerance: reported with that estimate (the margin
    carries it and says so) while it is small, "not located" (an incomplete margin) past REPORTABLE."""
    import etcheck.checks.rungs.straight as whirl
    from etcheck.rod.straight.collocation.damped_critical import PencilRoot

    real = whirl.pencil_or_exact

    def rough(*args, **kwargs):
        dc = real(*args, **kwargs)
        load = dc.critical_load
        bad = PencilRoot(load.axis, load.value, error, 128, False, load.model)
        return type(dc)(**{**dc.__dict__, "critical_load": bad, "converged": False})

    monkeypatch.setattr(whirl, "pencil_or_exact", rough)
    # 0.2 A at 0.6 rpm: the load margin alone decides the verdict once the spin margin passes
    results = check(mission(spin="0.06 rpm", damping="1 s", current="0.2 A"), LIGHT).results
    load = results["margins"][0]
    assert load["name"].startswith("magnetic load")
    if outcome == "kept":  # judged on the pessimistic side, with the estimate in the margin
        assert load["verdict"] in ("pass", "fail") and load["error"] == pytest.approx(error)
        assert "missed its tolerance" in results["linear"]["critical_load"]["message"]
        assert results["linear"]["critical_load"]["within_tolerance"] is False
        assert "missed its tolerance" in load["why"]
    else:
        assert load["verdict"] == "incomplete" and "was not located" in load["why"]
        assert results["linear"]["critical_load"]["value"] is None
        assert results["verdict"] in ("incomplete", "fail")


@pytest.mark.parametrize("beside", [True, False])
def test_the_accuracy_table_beside_the_spectra_or_after_them(monkeypatch, beside, forks_allowed):
    """With ``accuracy_beside`` the table goes to a helper (``ahead``) while the spectra are computed; without it
    (the CLI while its report process loads the report stack: the table's solves are timed) it is computed here,
    after the rest. The same table either way, times aside."""
    from dataclasses import replace

    import etcheck.checks.pipeline as pipeline

    started = []
    real = pipeline.ahead
    monkeypatch.setattr(pipeline, "ahead", lambda fn: started.append(fn) or real(fn))
    table = check(mission(spin="0.05 rpm"), replace(LIGHT, accuracy_beside=beside)).results["accuracy"]
    assert len(started) == (1 if beside else 0)
    assert [row["N"] for row in table] == [8, 12]
    reference = check(mission(spin="0.05 rpm"), replace(LIGHT, accuracy_beside=not beside)).results["accuracy"]
    for a, b in zip(table, reference):
        assert (a["eigenvalue_error"], a["load_error"]) == (b["eigenvalue_error"], b["load_error"])
