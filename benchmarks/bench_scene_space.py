"""Time, peak memory, exit codes and stderr of ``etcheck`` over random valid missions (a measurement, not a test).

    python benchmarks/bench_scene_space.py [--n 40] [--seed 1] [--timeout 120] [--only 3,17] [--keep DIR]
    python benchmarks/bench_scene_space.py --routes 24,48,96,128   # peak memory per route, stated and measured

Draws ``--n`` valid missions (seeded: the same missions for the same seed) over the scene space a user can reach:
lengths 10 m - 30 km, bending stiffness 1e-3 - 1e3 N m2 with R = EI2/EI1 down to 1e-7 (tapes), mass per length,
rotary inertia (a ratio, or a modulus and a section), damping (none, zero, a damping time), spin from 0 to 1000
times the unloaded tether's critical spin, end tension or end masses with an orbit rate, the axial field as a value,
a range or an ``[orbit]`` table (epochs to 2029), loads from 1e-4 to 1e4 times the static critical load (a value or
a range), required margins, tolerances and resolutions, and an ``[uncertainty]`` table in some. Each mission runs
through the command a user runs, in a fresh process: the draft (``--draft --format json``) and the sign-off
(every report: HTML, PDF, JSON). Per run: wall time, peak memory (the largest resident set of the command's
processes, from wait4), exit code, whether results.json is strict JSON, and whether anything reached stderr.

Printed: one line per run, then the distributions (median, 90th percentile, maximum) of wall time, CPU time (of
all the command's processes: on an idle 2-core machine the wall time lies between half of it and all of it, so
it reads a busy machine's run fairly) and peak memory, the runs over the targets (sign-off 10 s, draft 1 s on 2
cores; missions with an ``[uncertainty]`` table are reported apart, their study's time is not part of these
targets), the peak memory per route (the models of a check's margins) and the exit
codes. The missions widen the ranges of tests/scene_missions.py (its TOML writer and
strict JSON reader are reused). A measurement on a shared machine: repeat it before trusting a number.
"""

from __future__ import annotations

import argparse
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from scene_missions import strict_json, write_mission  # noqa: E402

#: f of the clamped rod's static critical load (arXiv:0810.3668, Sec. VI A): omega_c = sqrt(f EI1 / (rho L^4))
F_CLAMPED = 500.5639
#: I B0 [N/m] of the first static critical load of SET (EI = 38, 21 N m2, 100 m): loads are drawn relative to it
SET_IB0 = 1.1135e-2
TARGETS = {"sign-off": 10.0, "draft": 1.0}


def random_mission(rng: np.random.Generator, name: str) -> tuple[dict, str]:
    """A valid mission (nested dicts) and a one-line description of it."""
    L = 10 ** rng.uniform(1.0, math.log10(3e4))
    EI1 = 10 ** rng.uniform(-3.0, 3.0)
    R = float(10 ** rng.uniform(-7.0, 0.0)) if rng.random() < 0.5 else float(rng.choice([1.0, 0.5526, 0.1, 0.01]))
    mass = 10 ** rng.uniform(-3.5, 0.5)
    wc = math.sqrt(F_CLAMPED * EI1 / (mass * L**4))  # reference frequency [rad/s]
    tether, damping = _tether(rng, L, EI1, R, mass, wc)
    spin_factor = float(rng.choice([0.0, 0.0, 0.1, 0.5, 1.0, 3.0, 10.0, 100.0, 1000.0]))
    operation: dict = {"spin_rate": f"{spin_factor * math.sqrt(R) * wc!r} rad/s"}
    data: dict = {"mission": {"name": name, "description": "drawn by benchmarks/bench_scene_space.py"},
                  "tether": tether, "operation": operation, "check": {}}
    field_uT = _field(rng, data, float(rng.choice([30.0, 50.0, 70.0])))
    tension = _tension(rng, data, EI1, L)
    critical = SET_IB0 * math.sqrt(EI1 * EI1 * R / (38.0 * 21.0)) * (100.0 / L) ** 3
    ratio = 10 ** rng.uniform(-4.0, 4.0)
    current = ratio * critical / (field_uT * 1e-6)
    operation["current"] = [f"{0.2 * current!r} A", f"{current!r} A"] if rng.random() < 0.3 else f"{current!r} A"
    profile = _current_profile(rng, operation)
    check = data["check"]
    check["required_margin"] = round(float(rng.uniform(1.2, 3.0)), 2)
    if rng.random() < 0.3:
        check["tolerance"] = float(10 ** rng.uniform(-11.0, -4.0))
    if rng.random() < 0.15:
        check["resolution"] = int(rng.choice([16, 24, 32, 48, 64, 96, 128]))
    if rng.random() < 0.15:
        data["uncertainty"] = {"bending_stiffness": {"distribution": "normal", "sigma": "10 %"},
                               "current": {"distribution": "uniform", "bounds": [f"{0.9 * current!r} A", f"{current!r} A"]}}
    what = (f"L={L:.3g} m R={R:.2g} spin={spin_factor:g}x load={ratio:.2g}x{damping}{tension}{profile}"
            f"{' orbit' if 'orbit' in data else ''}{' N=' + str(check['resolution']) if 'resolution' in check else ''}"
            f"{' [uncertainty]' if 'uncertainty' in data else ''}")
    return data, what


def _current_profile(rng: np.random.Generator, operation: dict) -> str:
    """A current along the tether (a bare tether's) for a quarter of the missions: rising or falling linearly,
    or rising to a kink and flat past it; its words."""
    if rng.random() >= 0.25:
        return ""
    shape = int(rng.integers(3))
    if shape == 0:
        operation["current_profile"] = {"at": [0.0, 1.0], "fraction": [0.0, 1.0]}
    elif shape == 1:
        operation["current_profile"] = {"at": [0.0, 1.0], "fraction": [1.0, round(float(rng.uniform(0.0, 0.5)), 3)]}
    else:
        kink = round(float(rng.uniform(0.2, 0.8)), 3)
        operation["current_profile"] = {"at": [0.0, kink, 1.0], "fraction": [0.0, 1.0, 1.0]}
    return f" current-profile({'rising falling kinked'.split()[shape]})"


def _tether(rng: np.random.Generator, L: float, EI1: float, R: float, mass: float, wc: float) -> tuple[dict, str]:
    """The [tether] table (rotary inertia as a ratio or a section, damping none, zero or a time) and its damping."""
    tether: dict = {"length": f"{L!r} m", "bending_stiffness": [f"{EI1!r} N m2", f"{EI1 * R!r} N m2"],
                    "mass_per_length": f"{mass!r} kg/m", "poisson_ratio": round(float(rng.uniform(0.2, 0.45)), 3)}
    if rng.random() < 0.5:
        tether["rotary_inertia_ratio"] = float(10 ** rng.uniform(-10.0, -2.0))
    else:  # a section of a metal or a composite: P = EI1 / (E A L^2)
        tether["youngs_modulus"] = f"{float(rng.choice([70.0, 117.0, 132.0])):g} GPa"
        tether["cross_section_area"] = f"{10 ** rng.uniform(-1.0, 1.5):.4g} mm2"
    damping = int(rng.integers(4))
    if damping == 1:
        tether["damping_time"] = "0 s"
    elif damping == 2:
        tether["damping_time"] = f"{10 ** rng.uniform(-4.0, 0.0) / wc!r} s"  # gamma 1e-4 .. 1
    return tether, {0: "", 1: " undamped", 2: " damped", 3: ""}[damping]


def _field(rng: np.random.Generator, data: dict, field_uT: float) -> float:
    """The axial field: an [orbit] table (epochs 2020-2029), a range or a value; its largest value [uT]."""
    if rng.random() < 0.25:
        year = int(rng.integers(2020, 2030))
        data["orbit"] = {"altitude": f"{rng.uniform(300.0, 1500.0):.0f} km", "inclination": f"{rng.uniform(0, 100):.1f} deg",
                         "epoch": f"{year}-{int(rng.integers(1, 13)):02d}-15T00:00:00",
                         "duration": str(rng.choice(["1 h", "6 h", "1 d"]))}
        return 50.0
    if rng.random() < 0.3:
        data["operation"]["axial_field"] = [f"{0.3 * field_uT:g} uT", f"{field_uT:g} uT"]
    else:
        data["operation"]["axial_field"] = f"{field_uT:g} uT"
    return field_uT


def _tension(rng: np.random.Generator, data: dict, EI1: float, L: float) -> str:
    """No end tension, an end tension (T-bar 0.3, 30 or 1000) or end masses on an orbit; its words."""
    tension = rng.integers(3)
    if tension == 1:
        data["operation"]["end_tension"] = f"{float(rng.choice([0.3, 30.0, 1000.0])) * F_CLAMPED * EI1 / L**2!r} N"
        return " tension"
    if tension == 2:
        data["tether"]["end_masses"] = [f"{10 ** rng.uniform(0, 3):.3g} kg", f"{10 ** rng.uniform(-1, 2):.3g} kg"]
        if "orbit" not in data:
            data["operation"]["orbit_altitude"] = f"{rng.uniform(300.0, 1500.0):.0f} km"
        return " end-masses"
    return ""


@dataclass
class Run:
    mission: int
    kind: str
    what: str
    code: int
    seconds: float
    cpu: float
    peak_mb: float
    strict: bool | None
    stderr: str
    models: tuple[str, ...]
    uncertain: bool


def run(path: Path, kind: str, out: Path, timeout: float) -> tuple[int, float, float, float, str]:
    """(exit code, wall s, CPU s of all its processes, peak MB of the largest one, stderr) of one command; killed
    past ``timeout``."""
    args = [sys.executable, "-m", "etcheck", "check", str(path), "--out", str(out)]
    args += ["--draft", "--format", "json"] if kind == "draft" else []
    err = tempfile.TemporaryFile("w+")
    t0 = time.perf_counter()
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=err, start_new_session=True, cwd=out)
    deadline = t0 + timeout
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        if time.perf_counter() > deadline:
            os.killpg(proc.pid, signal.SIGKILL)
        time.sleep(0.01)
    seconds = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    err.seek(0)
    return proc.returncode, seconds, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0, err.read()


def measure(i: int, data: dict, what: str, kind: str, folder: Path, timeout: float) -> Run:
    path = write_mission(data, folder, f"m{i}")
    out = folder / f"out-{i}-{kind}"
    out.mkdir()
    code, seconds, cpu, peak, err = run(path, kind, out, timeout)
    strict, models = None, ()
    results = next(out.rglob("results.json"), None)
    if results is not None:
        try:
            r = strict_json(results.read_text())
            strict, models = True, tuple(sorted({m["model"] for m in r["margins"]}))
        except ValueError:
            strict = False
    return Run(i, kind, what, code, seconds, cpu, peak, strict, err, models, "uncertainty" in data)


def noise(stderr: str) -> list[str]:
    """The lines of stderr that are not etcheck's own message (a refusal says "etcheck: error: ..."): a
    dependency's warning, a traceback."""
    return [line for line in stderr.splitlines() if line.strip() and not line.startswith("etcheck")]


def _dist(values: list[float]) -> str:
    if not values:
        return "-"
    q = np.quantile(values, [0.5, 0.9])
    return f"median {q[0]:.2f}, p90 {q[1]:.2f}, max {max(values):.2f}"


def report(runs: list[Run]) -> None:
    print("\n== distributions (time [s]; peak memory of the largest process [MB])")
    for kind in ("draft", "sign-off"):
        for uncertain in (False, True):
            sel = [r for r in runs if r.kind == kind and r.uncertain == uncertain]
            if not sel:
                continue
            label = f"{kind}{' with [uncertainty]' if uncertain else ''}"
            over = [r for r in sel if r.seconds > TARGETS[kind]]
            print(f"{label:30s} n={len(sel):3d}  wall: {_dist([r.seconds for r in sel])}  "
                  f"CPU: {_dist([r.cpu for r in sel])}  memory: {_dist([r.peak_mb for r in sel])}  "
                  f"wall over {TARGETS[kind]:g} s: {len(over)}, CPU over it: "
                  f"{sum(r.cpu > TARGETS[kind] for r in sel)}")
            for r in over:
                print(f"    #{r.mission} {r.seconds:.1f} s wall, {r.cpu:.1f} s CPU, exit {r.code}: {r.what}")
    print("\n== exit codes")
    for kind in ("draft", "sign-off"):
        codes: dict[int, int] = {}
        for r in runs:
            if r.kind == kind:
                codes[r.code] = codes.get(r.code, 0) + 1
        print(f"{kind:10s} " + ", ".join(f"{c}: {n}" for c, n in sorted(codes.items())))
    noisy = [r for r in runs if noise(r.stderr)]
    bad = [r for r in runs if r.strict is False]
    print(f"runs with anything but etcheck's own message on stderr: {len(noisy)}; "
          f"results.json not strict JSON: {len(bad)}")
    for r in noisy:
        print(f"    #{r.mission} {r.kind} exit {r.code}: {noise(r.stderr)[0][:160]}")
    print("\n== peak memory per route (sign-off runs whose margins use the route) [MB]")
    routes = sorted({m for r in runs for m in r.models})
    for route in routes:
        peaks = [r.peak_mb for r in runs if r.kind == "sign-off" and route in r.models]
        print(f"  {route[:90]:90s} n={len(peaks):3d}  {_dist(peaks)}")


def routes(Ns: list[int]) -> None:
    """Stated against measured (tracemalloc) peak memory and the time of each route's largest step per resolution,
    for SET's operating point (dense QZ: with damping 0.2, where the Kelvin-Voigt cluster is among the wanted
    eigenvalues)."""
    import tracemalloc

    from etcheck.rod.core.parameters import RodParameters
    from etcheck.rod.core.spectrum import lowest_eigenvalues, solve_bytes
    from etcheck.rod.straight.collocation.spectral import StraightFamily, family_bytes
    from etcheck.rod.straight.exact.roots import exact_critical

    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, B=0.3, omega=0.25, T=0.0, gamma=0.04375)

    def measured(fn, *args) -> tuple[float, float]:
        tracemalloc.start()
        t0 = time.perf_counter()
        before = tracemalloc.get_traced_memory()[0]
        fn(*args)
        peak = tracemalloc.get_traced_memory()[1] - before
        tracemalloc.stop()
        return peak, time.perf_counter() - t0

    def family(N: int) -> None:
        fam = StraightFamily(p, N)
        fam.pencil_roots("B", 0.0, p.omega, 0.0)
        fam.eigenvalues(p.B, p.omega, 0.0, 28)

    print("\n== peak memory per route, stated (what the budget is charged) and measured (tracemalloc), MB; time s")
    print(f"{'route':52s} {'N':>4s} {'stated':>8s} {'measured':>9s} {'time':>7s}")
    rows = [("collocation family: static pencils and its parts", lambda N: family_bytes(N), family),
            ("eigenvalues by shift-invert (ARPACK)", lambda N: solve_bytes(N, False),
             lambda N: lowest_eigenvalues(p, None, N, 28)),
            ("eigenvalues by dense QZ (heavy damping, fast spin)", lambda N: solve_bytes(N, True),
             lambda N: lowest_eigenvalues(p.with_(gamma=0.2), None, N, 28))]
    for name, stated, fn in rows:
        for N in Ns:
            if "QZ" in name and N > 96:  # minutes on a busy machine
                continue
            peak, seconds = measured(fn, N)
            print(f"{name:52s} {N:4d} {stated(N) / 1e6:8.1f} {peak / 1e6:9.1f} {seconds:7.2f}", flush=True)
    peak, seconds = measured(exact_critical, p.with_(P=0.0010001))
    print(f"{'exact determinant (damped critical values)':52s} {'-':>4s} {'-':>8s} {peak / 1e6:9.1f} {seconds:7.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=40, help="missions drawn (default 40)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=120.0, help="a run is killed after this many seconds")
    ap.add_argument("--uncertainty-timeout", type=float, default=30.0,
                    help="the same for a mission with an [uncertainty] table (its study's time is not targeted here)")
    ap.add_argument("--only", default="", help="comma-separated mission numbers to run (default: all)")
    ap.add_argument("--kinds", default="draft,sign-off")
    ap.add_argument("--keep", default=None, help="keep the missions and outputs in this folder")
    ap.add_argument("--routes", default="", help="only the peak memory per route at these resolutions, e.g. 24,48,96")
    a = ap.parse_args()
    if a.routes:
        routes([int(x) for x in a.routes.split(",")])
        return
    rng = np.random.default_rng(a.seed)
    missions = [random_mission(rng, f"scene {i}") for i in range(a.n)]
    only = {int(x) for x in a.only.split(",") if x.strip()}
    print(f"cores: {len(os.sched_getaffinity(0))}, seed {a.seed}, {a.n} missions")
    folder = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="etcheck-scenes-"))
    folder.mkdir(parents=True, exist_ok=True)
    runs = []
    for i, (data, what) in enumerate(missions):
        if only and i not in only:
            continue
        for kind in a.kinds.split(","):
            r = measure(i, data, what, kind, folder, a.uncertainty_timeout if "uncertainty" in data else a.timeout)
            runs.append(r)
            flag = "  STDERR" if noise(r.stderr) else ""
            print(f"#{i:3d} {kind:8s} exit {r.code:3d} {r.seconds:7.2f} s {r.cpu:7.2f} s CPU {r.peak_mb:6.0f} MB  "
                  f"{what}{flag}", flush=True)
    report(runs)


if __name__ == "__main__":
    main()
