"""What-if sweeps: axes, the damped pencil solver against the rung-1 scan, the
sweep against the check, exact critical lengths, files with units, resume
after kill -9, a dask cluster, extremes and bad input."""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from helpers import set_like

from etcheck.checks.pipeline import check
from etcheck.cli.main import main
from etcheck.errors import MissionError
from etcheck.input.mission import load_mission, mission_from_dict
from etcheck.input.sweep_axes import parse_option
from etcheck.report.sweep_files import read_csv, read_netcdf, to_csv, to_netcdf
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.collocation.damped_critical import damped_critical, first_root
from etcheck.rod.straight.collocation.spectral import critical_load, critical_spin
from etcheck.rod.straight.exact.roots import string_limit_load
from etcheck.rod.straight.exact.undamped import MODEL as UNDAMPED_MODEL
from etcheck.scaling import scale, scene
from etcheck.studies.sweep import STATUS_OK, STATUS_OUTSIDE, SweepOptions, solve_point, sweep

ROOT = Path(__file__).resolve().parents[2]
SET = dict(P=1e-3, R=21 / 38, Gamma=0.76923, f=500.5639, gamma=0.04375)


# --- axes ---------------------------------------------------------------------------------------


def test_axis_linear_and_log():
    a = parse_option("length", "50m:5km:3:log")
    assert a.name == "length" and np.allclose(a.values, [50, 500, 5000])
    s = parse_option("spin", "0rpm:2rpm:3")
    assert np.allclose(s.values * 60 / (2 * math.pi), [0, 1, 2]) and s.unit == "rpm"


@pytest.mark.parametrize("option, text, words", [
    ("length", "5s:10s:3", "time"),
    ("length", "5km:50m:3", "below stop"),
    ("length", "0m:5km:3:log", "positive"),
    ("spin", "0rpm:2rpm:1", "points"),
    ("spin", "0rpm:2rpm", "START:STOP:POINTS"),
    ("current", "1A:2A:3:cubic", "spacing"),
    ("field", "nan uT:70uT:3", "finite"),
])
def test_axis_errors_name_the_option(option, text, words):
    with pytest.raises(MissionError) as err:
        parse_option(option, text)
    assert f"--{option}" in str(err.value) and words in str(err.value)


def test_sweep_table_in_mission():
    data = set_like()
    data["sweep"] = {"length": {"from": "50 m", "to": "1 km", "points": 4, "spacing": "log"}}
    m = mission_from_dict(data)
    assert m.studies.sweep[0].name == "length" and m.studies.sweep[0].points == 4
    data["sweep"] = {"length": {"from": "50 s", "to": "1 km", "points": 4}}
    with pytest.raises(MissionError, match=r"sweep\.length"):
        mission_from_dict(data)
    data["sweep"] = {"lenght": {"from": "50 m", "to": "1 km", "points": 4}}
    with pytest.raises(MissionError, match="lenght"):
        mission_from_dict(data)


# --- the damped pencil solver against the rung-1 spectral scan ------------------------------------

SCENES = [pytest.param(dict(omega=0.25), marks=pytest.mark.slow),  # SET itself: in many other tests
          pytest.param(dict(omega=0.5, T=0.01), marks=pytest.mark.slow),  # tension: the last scene has it too
          dict(T=-0.002, omega=0.3), dict(R=1.0, omega=0.4),
          dict(R=0.2, Gamma=1.3, omega=0.2, gamma=0.3), dict(P=1e-5, omega=0.6, T=0.05)]


@pytest.mark.parametrize("kw", SCENES)
def test_damped_pencils_agree_with_spectral_scan(kw):
    p = RodParameters(**(SET | kw))
    d = damped_critical(p.with_(B=0.2))
    assert d.converged
    scan_load = critical_load(p.with_(B=0.0))
    scan_spin = critical_spin(p.with_(B=0.2, omega=0.0))
    assert scan_load.kind == "divergence" and scan_spin.kind == "divergence"
    assert d.critical_load.value == pytest.approx(scan_load.value, rel=1e-8)
    assert d.critical_spin.value == pytest.approx(scan_spin.value, rel=1e-8)
    assert d.stable == (0.2 < d.critical_load.value)


def test_damped_pencil_reproduces_rung0_and_the_ray():
    p = RodParameters(**SET)
    assert damped_critical(p).critical_load.value == pytest.approx(critical_loads(p.R, p.f, 1)[0], rel=1e-12)
    # the pencil (not the chi shortcut) at tiny tension tends to the chi root
    B_T = first_root(p.with_(T=1e-9), "B").value
    assert B_T == pytest.approx(critical_loads(p.R, p.f, 1)[0], rel=1e-6)
    # along the ray (t B, sqrt(t) omega) the first root is where the rod loses stability
    q = p.with_(B=0.3, omega=0.4)
    t = first_root(q, "ray").value
    at = damped_critical(q.with_(B=t * 0.3, omega=math.sqrt(t) * 0.4))
    assert at.critical_load.value == pytest.approx(t * 0.3, rel=1e-7)


def test_undamped_rejected_by_pencils():
    with pytest.raises(ValueError, match="gamma > 0"):
        damped_critical(RodParameters(**(SET | {"gamma": 0.0})))


# --- the sweep against the check --------------------------------------------------------------------


def _spin_mission(**fields):
    return mission_from_dict(set_like(spin_rate="0.1041 rpm", **fields))


def test_sweep_point_equals_check_margins():
    m = _spin_mission()
    res = sweep(m, (parse_option("length", "100m:200m:2"),), SweepOptions(workers=1))
    chk = check(m).results
    g = res["grid"]
    lin = chk["linear"]
    assert g["critical_load_N_per_m"][0] == pytest.approx(lin["critical_load"]["IB0_N_per_m"], rel=1e-8)
    assert g["critical_spin_rpm"][0] == pytest.approx(lin["critical_spin"]["rpm"], rel=1e-8)
    margins = {mm["name"]: mm["value"] for mm in chk["margins"]}
    assert g["load_margin"][0] == pytest.approx(margins["magnetic load |I B0| at the operating spin and tension"],
                                                rel=1e-8)


def test_sweep_takes_the_ends_of_the_mission():
    """[tether] end_conditions reaches every point of a sweep unchanged: a point equals the check of the same
    mission, and without spin the critical length is the closed form of those ends (B ~ L^3)."""
    ends = ["welded", "pinned"]
    m = _spin_mission(end_conditions=ends)
    res = sweep(m, (parse_option("length", "100m:200m:2"),), SweepOptions(workers=1))
    chk = check(m).results
    assert res["grid"]["critical_load_N_per_m"][0] == pytest.approx(chk["linear"]["critical_load"]["IB0_N_per_m"],
                                                                     rel=1e-8)
    welded = check(_spin_mission()).results["linear"]["critical_load"]["IB0_N_per_m"]
    assert res["grid"]["critical_load_N_per_m"][0] < 0.9 * welded
    m = mission_from_dict(set_like(end_conditions=ends))
    res = sweep(m, (parse_option("length", "100m:2km:6:log"),), SweepOptions(workers=1))
    sc = scene(m)
    B1 = critical_loads(sc.EI2 / sc.EI1, sc.f, 1, tuple(ends))[0]
    assert res["critical_length"][0]["length_m"] == pytest.approx(sc.length * (B1 / scale(sc).params.B) ** (1 / 3),
                                                                  rel=1e-7)


def test_critical_length_without_spin_is_analytic():
    m = mission_from_dict(set_like())
    res = sweep(m, (parse_option("length", "100m:2km:6:log"),), SweepOptions(workers=1))
    sc = scene(m)
    B1 = critical_loads(sc.EI2 / sc.EI1, sc.f, 1)[0]
    L_c = sc.length * (B1 / scale(sc).params.B) ** (1 / 3)
    row = res["critical_length"][0]
    assert row["status"] == "ok" and row["length_m"] == pytest.approx(L_c, rel=1e-7)
    assert res["grid"]["model"][0] == "rung 0 (chi roots)"


def test_critical_length_with_spin_is_the_boundary():
    m = _spin_mission()
    res = sweep(m, (parse_option("length", "50m:400m:5:log"), parse_option("spin", "0.05rpm:0.5rpm:3")),
                SweepOptions(workers=1))
    for row in res["critical_length"]:
        assert row["status"] == "ok"
        L = row["length_m"]
        for f, stable in ((1 - 1e-6, True), (1 + 1e-6, False)):
            p = scale(scene_with(m, L * f, row["other"])).params
            assert solve_point(p, 1e-8).stable is stable


def test_undamped_critical_length_at_the_onset_of_a_real_pair():
    """Undamped SET at 2 rpm: the unloaded tether gains a real pair of eigenvalues at about 93 m, where the load
    margin drops from ~200 to 0 in a jump; located by bisection of that onset, checked on both sides."""
    import astropy.units as u

    from etcheck.studies.sweep import critical_length

    m = load_mission(ROOT / "missions" / "set.toml").with_tether(damping_time=0 * u.s)
    sc, spin = scene(m), 2 * 2 * math.pi / 60
    row = critical_length(sc, {"spin_rate": spin}, 50.0, 160.0, 1e-8)
    assert row["status"] == "ok" and "real pair" in row["reason"]
    for f, stable in ((1 - 1e-6, True), (1 + 1e-6, False)):
        p = scale(scene_with(m, row["length_m"] * f, spin)).params
        assert solve_point(p, 1e-8).stable is stable


def scene_with(m, length, spin):
    from etcheck.studies.sweep import point_scene

    return point_scene(scene(m), {"length": length, "spin_rate": spin})


# --- files --------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def small():
    m = _spin_mission()
    return sweep(m, (parse_option("length", "50m:2km:6:log"), parse_option("spin", "0rpm:0.6rpm:4")),
                 SweepOptions(workers=1))


def test_files_load_back_with_units(small, tmp_path):
    import astropy.units as u

    (tmp_path / "s.csv").write_bytes(to_csv(small))
    (tmp_path / "s.nc").write_bytes(to_netcdf(small))
    c = read_csv(tmp_path / "s.csv")
    assert c["length [m]"].unit == u.m and c["critical_load [N/m]"].unit == u.N / u.m
    assert c["spin_rate [rpm]"].to_value(u.rad / u.s) == pytest.approx(c["spin_rate [rad/s]"].value)
    flat = np.ravel(np.array(small["grid"]["critical_load_N_per_m"], dtype=float))
    assert np.allclose(c["critical_load [N/m]"].value, flat, rtol=0, atol=0, equal_nan=True)
    ds = read_netcdf(tmp_path / "s.nc")
    assert ds["critical_load"].attrs["units"] == "N/m" and ds["length"].attrs["units"] == "m"
    assert ds["critical_load"].shape == (6, 4)
    assert np.array_equal(ds["critical_load"].values.ravel(), flat, equal_nan=True)
    assert list(ds["status"].values.ravel()) == list(np.ravel(small["grid"]["status"]))
    # no spin: an unlimited margin is inf, never NaN
    assert np.isinf(ds["spin_margin"].values[:, 0]).all()
    json.dumps(small, allow_nan=False)


def test_no_nan_in_reports(small):
    from etcheck.report import render

    out = render(small, ("html", "json"), kind="sweep")
    text = re.sub(rb"data:[^\"')\s]+", b"", out["html"])  # embedded images are base64, not numbers
    assert b"NaN" not in out["json"] and not re.search(rb"\bnan\b", text.lower())  # a number, not "determinant"


# --- extremes ---------------------------------------------------------------------------------------------


def test_short_tether_is_outside_validated_range():
    r = solve_point(RodParameters(**(SET | {"P": 0.5})), 1e-8)
    assert r.status == STATUS_OUTSIDE and "P = 0.5" in r.reason


def _sign_change_at(g, x, rel=1e-6, below: int = 40) -> bool:
    """g changes sign across x (+-rel) and not on a coarse grid below it (first root)."""
    lo, hi = g(x * (1 - rel)), g(x * (1 + rel))
    grid = np.linspace(1e-6 * x, x * (1 - rel), below)
    d = np.sign([g(v) for v in grid])
    return lo * hi < 0 and bool(np.all(d == d[0]))


@pytest.mark.parametrize("kw", [dict(P=1e-8, omega=0.5), dict(R=0.01, omega=0.05), dict(R=0.01),
                                dict(B=1e4, omega=0.3), dict(omega=7.5),
                                pytest.param(dict(T=100.0), marks=pytest.mark.slow),  # 6 s: strong tension against
                                # independent shooting also in tests/rod/test_exact_straight.py and tests/checks
                                pytest.param(dict(R=0.05, T=3.0, omega=2.0), marks=pytest.mark.slow)])  # 6 s: tension and spin together also in tests/rod/test_exact_straight.py
def test_extremes_converge_and_agree_with_exact_shooting(kw):
    """Independent values: the exact (matrix-exponential, 50-digit under tension) static determinant."""
    from independent import static_determinant

    p = RodParameters(**(SET | kw))
    r = solve_point(p, 1e-8)
    assert r.status == STATUS_OK
    if p.omega == 0 and p.T == 0:  # double zero of chi: rung 0 is the reference
        assert r.B_c == pytest.approx(critical_loads(p.R, p.f, 1)[0], rel=1e-12)
        return
    args = (p.P, p.R, p.f)
    if r.B_c == 0.0:  # spinning past the unloaded critical spin: unstable without load
        assert r.stable is False and p.omega >= r.omega_rest
        assert _sign_change_at(lambda w: static_determinant(0.0, *args, w, p.T), r.omega_rest)
    else:
        assert _sign_change_at(lambda b: static_determinant(b, *args, p.omega, p.T), r.B_c)


def test_strong_tension_is_answered_by_the_exact_determinant():
    """T = 1e4: boundary layers of 1e-3 L, beyond collocation at N = 128 (once a failed point);
    the planner hands it to the exact determinant, which meets the string limit with its corrections."""
    p = RodParameters(**(SET | {"T": 1e4}))
    r = solve_point(p, 1e-8)
    assert r.status == STATUS_OK and "exact determinant" in r.model and r.stable is True
    assert r.B_c == pytest.approx(string_limit_load(p, order=2), rel=1e-6)
    assert abs(r.B_c / (2 * np.pi * p.T) - 1) > 5e-4  # the boundary-layer correction (6.7e-4) is really there


def test_long_and_short_lengths_in_one_sweep():
    m = _spin_mission()
    res = sweep(m, (parse_option("length", "1m:100km:6:log"),), SweepOptions(workers=1))
    g = res["grid"]
    assert g["status"][0] == STATUS_OUTSIDE  # 1 m: P = 10
    assert all(s == STATUS_OK for s in g["status"][1:])
    assert g["region"][-1] == "straight-unstable" and g["load_margin"][-1] == 0.0  # 100 km spins far past critical


def test_undamped_points_use_the_exact_undamped_determinant():
    m = _spin_mission(damping_time="0 s")
    res = sweep(m, (parse_option("spin", "0.05rpm:0.1rpm:2"),), SweepOptions(workers=1))
    assert set(np.ravel(res["grid"]["model"])) == {UNDAMPED_MODEL}
    assert all(s == STATUS_OK for s in res["grid"]["status"])


# --- CLI, resume and distributed -------------------------------------------------------------------------------


def _cli(*args, **kw):
    return subprocess.run([sys.executable, "-m", "etcheck", *args], capture_output=True, text=True, cwd=ROOT, **kw)


@pytest.mark.parametrize("args, words", [
    (["--length", "5s:10s:3"], "--length"),
    (["--length", "50m:1km:3", "--spin", "0rpm:1rpm:3", "--current", "1A:2A:3"], "one or two"),
    ([], "no sweep axes"),
    (["--length", "50m:1km:3", "--workers", "0"], "--workers"),
])
def test_cli_bad_sweep_input_exits_2(args, words, tmp_path):
    err = io.StringIO()  # in this process: a refusal before any solve (the subprocess path is tested above)
    with contextlib.redirect_stderr(err):
        try:
            code = main(["sweep", str(ROOT / "missions" / "set.toml"), "--out", str(tmp_path), *args])
        except SystemExit as exc:  # argparse
            code = exc.code
    assert code == 2, err.getvalue()
    assert words in err.getvalue() and "Traceback" not in err.getvalue()


def test_cli_sweep_writes_every_format(tmp_path):
    code = main(["sweep", "missions/set.toml", "--length", "50m:1km:5:log", "--spin", "0rpm:0.4rpm:3",
                 "--out", str(tmp_path), "--workers", "1"])
    assert code == 0
    folder = tmp_path / "set" / "sweep"
    for name in ("sweep.html", "sweep.pdf", "sweep.json", "sweep.csv", "sweep.nc"):
        assert (folder / name).stat().st_size > 0
    html = (folder / "sweep.html").read_text()
    # the figures are inline PNG (legends drawn into them): the captions say what the marks are
    assert "critical length" in html.lower() and "star: the mission's operating point" in html
    assert html.count("<img src=\"data:image/png") >= 2


def test_kill_and_resume_gives_identical_data(tmp_path, monkeypatch, capsys):
    args = ["sweep", "missions/set.toml", "--length", "40m:3km:8:log", "--spin", "0rpm:1.2rpm:6",
            "--format", "csv,nc", "--workers", "2"]
    monkeypatch.chdir(ROOT)  # the reference and the resumed run in this process: only the killed one needs its own
    here = [*args[:-1], "1"]  # ... and its workers (the data do not depend on their number)
    assert main([*here, "--out", str(tmp_path / "ref"), "--no-cache"]) == 0
    out = tmp_path / "run"
    cache = out / "set" / "sweep" / "cache"
    proc = subprocess.Popen([sys.executable, "-m", "etcheck", *args, "--out", str(out)], cwd=ROOT,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    while time.time() < deadline and (not cache.exists() or len(list(cache.glob("*.json"))) < 12):
        time.sleep(0.005)
    children = _children(proc.pid)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    done = len(list(cache.glob("*.json")))
    time.sleep(1.5)
    assert children and not any(Path(f"/proc/{c}").exists() and "etcheck" in _cmdline(c) for c in children), \
        "workers outlived the killed sweep"
    assert 12 <= done < 8 * 6, "the kill must land mid-sweep"
    assert not (out / "set" / "sweep" / "sweep.csv").exists()
    capsys.readouterr()
    assert main([*here, "--out", str(out)]) == 0
    said = capsys.readouterr()
    assert "from the cache" in said.err + said.out
    for name in ("sweep.csv", "sweep.nc"):
        assert (out / "set" / "sweep" / name).read_bytes() == (tmp_path / "ref" / "set" / "sweep" / name).read_bytes()


def _children(pid: int) -> list[int]:
    deadline = time.time() + 10
    while time.time() < deadline:
        kids = [int(c) for t in Path(f"/proc/{pid}/task").iterdir()
                for c in (t / "children").read_text().split()]
        if kids:
            return kids
        time.sleep(0.01)
    return []


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace")
    except OSError:
        return ""


def test_sigint_stops_cleanly_and_says_how_to_resume(tmp_path):
    proc = subprocess.Popen([sys.executable, "-m", "etcheck", "sweep", "missions/set.toml", "--length",
                             "40m:3km:30:log", "--spin", "0rpm:1.2rpm:30", "--format", "json", "--out", str(tmp_path)],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            # Ctrl-C as at a terminal, even where pytest itself runs with SIGINT ignored (a background job)
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    cache = tmp_path / "set" / "sweep" / "cache"
    deadline = time.time() + 60
    while time.time() < deadline and (not cache.exists() or len(list(cache.glob("*.json"))) < 5):
        time.sleep(0.005)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "resume" in err and "Traceback" not in err


@pytest.mark.slow  # 6 s: a local dask cluster; the scheduler path's errors are tested below, the chunks are the local ones
def test_dask_local_cluster_gives_the_same_data():
    distributed = pytest.importorskip("distributed")
    m = _spin_mission()
    axes = (parse_option("length", "50m:1km:5:log"), parse_option("spin", "0rpm:0.5rpm:4"))
    local = sweep(m, axes, SweepOptions(workers=1))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        remote = sweep(m, axes, SweepOptions(scheduler=lc.scheduler_address))
    assert to_csv(remote) == to_csv(local)
    assert remote["cost"]["workers"].startswith("dask")


def test_unreachable_scheduler_is_a_clear_error():
    m = _spin_mission()
    with pytest.raises(MissionError, match="scheduler"):
        sweep(m, (parse_option("spin", "0rpm:0.5rpm:2"),), SweepOptions(scheduler="tcp://127.0.0.1:9",
                                                                                   connect_timeout=0.5))


def test_mission_sweep_table_drives_the_command(tmp_path):
    text = (ROOT / "missions" / "set.toml").read_text() + (
        '\n[sweep]\nlength = { from = "50 m", to = "500 m", points = 3, spacing = "log" }\n')
    path = tmp_path / "m.toml"
    path.write_text(text)
    assert load_mission(path).studies.sweep[0].points == 3
    code = main(["sweep", str(path), "--out", str(tmp_path), "--format", "json", "--workers", "1"])
    assert code == 0
    data = json.loads((tmp_path / "set" / "sweep" / "sweep.json").read_text())
    assert data["axes"][0]["name"] == "length" and data["grid"]["shape"] == [3]


def test_buckled_option_labels_coiled_points_like_the_check():
    """--buckled: a straight-unstable point whose coiled state on b1 is stable is buckled-stable, and its
    deflection is the one the check reports for the same mission (set-600m)."""
    m = load_mission(ROOT / "missions" / "set-600m.toml")
    res = sweep(m, (parse_option("length", "600m:1000m:2"),), SweepOptions(workers=1, buckled=True))
    g = res["grid"]
    assert g["region"] == ["buckled-stable", "straight-unstable"]  # 1000 m: past b1's secondary pitchfork
    from etcheck.checks.rungs.buckled import operating_state

    sc = scale(scene(m))
    post = operating_state(sc.params, sc.scales, N=32)  # what the check reports for this mission
    assert g["buckled_deflection_m"][0] == pytest.approx(post["max_deflection_m"], rel=1e-6)
    assert res["grid"]["regions"]["buckled-stable"] == 1


def test_headline_counts_the_points_that_meet_the_required_margin(small):
    """The headline's numbers are sweep.json's: points that pass (stable, both margins met, within the model's
    validity), those that meet the margin but bow past the limit, and those stable but short of it; each
    point's verdict follows its margins and its bow."""
    from etcheck.checks.verdict.validity import BOW_LIMIT, mid_span_bow
    from etcheck.report import render

    g = small["grid"]
    verdict = np.array(g["verdict"], dtype=object)
    region = np.array(g["region"], dtype=object)
    load, spin = (np.array(g[k], dtype=object) for k in ("load_margin", "spin_margin"))
    bow = np.array(g["bow_over_length"], dtype=float)
    req = small["required_margin"]
    meets = (region == "straight-stable") & np.array([(a is None or a >= req) and (b is None or b >= req)
                                                     for a, b in zip(load.ravel(), spin.ravel())]).reshape(load.shape)
    assert g["meet_margin"] == int(meets.sum()) and g["stable_short"] == int(((region == "straight-stable") & ~meets).sum())
    assert g["verdicts"]["pass"] == int((meets & (bow <= BOW_LIMIT)).sum()) == int((verdict == "pass").sum())
    assert g["verdicts"]["outside"] == int((bow > BOW_LIMIT).sum())
    assert sum(g["verdicts"].values()) == small["cost"]["points"]
    # a point's bow is the check's formula at its length, current and tension (the mission's field across it)
    L = np.array(small["axes"][0]["values"])
    assert bow[:, 0] == pytest.approx([mid_span_bow(1.0 * 70e-6, x, 0.0, 21.0) / x for x in L], rel=1e-12)
    html = render(small, ("html",), kind="sweep")["html"].decode()
    assert f"{g['verdicts']['pass']} of {small['cost']['points']} points meet the required margin" in html
    assert f"{g['stable_short']} are straight-stable but short of the required margin" in html
