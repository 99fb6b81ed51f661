"""Rung 1v (current and tension along the tether) timing and accuracy per resolution (not a test).

Part 1, per middle resolution N of the graded collocation (the ladder's rungs): the time of one search for the
first crossing along the load on one mesh (scan, bracket, Brent with the tracked eigenvalue) and its distance to
a reference (uniform profiles: the exact determinant; profiles: the finest mesh), for

* the shipped tape with a uniform current (layers of 6e-5 L, R = 2.6e-6), damped: against the exact determinant;
* the tape with its current falling linearly from the lower end, undamped (flutter) and damped (gamma = 0.04375,
  Ziegler's slow flutter);
* a 200 m SET-like tether with a kinked current and its gravity-gradient tension, damped.

Part 2: whole checks (sign-off and draft; the median of three runs, each from nothing) of missions with profiles
(PMG, the tape, ProSEDS) and of a uniform mission (SET; unchanged: it does not enter rung 1v), with the time of each
part of rung 1v as this process sees it: the damping policy (the undamped threshold and the damping map's survey,
one of them on the other core where there is one, and the verdict's crossing on two meshes), then, at the verdict's
damping, its crossing under a conservative load, the critical spin, the uniform-tension bound and the margins under
the other attachment of the ends, shared between the two cores ("together"), and the mode. Also the tape and ProSEDS
without end masses and without tension (end_tension = 0 N, their collected current kept): each must end in
seconds, located or said not located. BLAS on one thread.

Run:  python benchmarks/bench_profiles.py [--quick] [--checks] [--serial]   (--checks: part 2 only; --serial: one core)
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from threadpoolctl import threadpool_limits

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.profile import Profile
from etcheck.rod.straight.exact.roots import exact_critical
from etcheck.rod.straight.varying.circulatory import critical, forget
from etcheck.rod.straight.varying.profiles import Tether, mesh

ROOT = Path(__file__).resolve().parents[1]
TAPE = RodParameters(P=2.0857142857142857e-10, R=2.556164383561644e-06, Gamma=7.671213267830194e-06,
                     B=3.3796980016942935, T=1.4446060436451282, gamma=0.04375)
FALLING = Profile.piecewise_linear([0.0, 1.0], [1.0, 0.0])
SMALL = RodParameters(P=1e-3, R=0.5526315789473685, Gamma=0.7692307692307692, B=0.0126, T=0.0404, gamma=0.04375)
KINK = Profile.piecewise_linear([0.0, 0.3, 1.0], [1.0, 0.8, 0.0])
PARABOLA = Profile.from_function(lambda s: 1.0 - 0.15 * (2 * s - 1) ** 2 + 0.15, degree=2)

SCENES = [
    ("tape, uniform, damped", Tether(TAPE), "exact"),
    ("tape, falling current, undamped", Tether(TAPE.with_(gamma=0.0), FALLING), None),
    ("tape, falling current, damped", Tether(TAPE, FALLING), None),
    ("200 m, kinked current, tension profile, damped", Tether(SMALL, KINK, PARABOLA), None),
]
LADDER = (16, 24, 32, 48, 64)


def one_mesh(t: Tether, N: int) -> tuple[float, float]:
    forget()
    t0 = time.perf_counter()
    c = critical(t, ladder=(N,), mode=False, check=False)
    return c.value, time.perf_counter() - t0


def part1() -> None:
    print("one search on one mesh, per middle resolution N (points per field of the graded mesh)")
    print(f"{'scene':48s} {'N':>4s} {'points':>7s} {'time [s]':>9s} {'critical B':>20s} {'rel. error':>11s}")
    for name, t, ref in SCENES:
        rows = [(N, mesh(t.with_(B=3 * t.params.B), N).size, *one_mesh(t, N)) for N in LADDER]
        best = exact_critical(t.params).critical_load.value if ref == "exact" else rows[-1][2]
        for N, size, value, dt in rows:
            err = abs(value - best) / best
            print(f"{name:48s} {N:4d} {size:7d} {dt:9.3f} {value:20.14g} {err:11.2e}")
        print()


#: The parts of rung 1v's check timed in part 2 (functions of etcheck.checks.rungs.profiles, as this process sees them:
#: work on the other core is not seen apart): the whole of rung 1v, its damping policy, the verdict's mode and the
#: stability map (a sign-off's extra); the rest of rung 1v is the work shared between the cores at the verdict's
#: damping.
PARTS = ("profile_stability", "_damping_policy", "crossing_mode", "stability_map")
RUNS = 3


def _timed_parts() -> dict[str, float]:
    """Wrap the parts of etcheck.checks.rungs.profiles so that each call adds its time to the returned dict."""
    import etcheck.checks.rungs.profiles as checks_profiles

    spent: dict[str, float] = {}
    for name in PARTS:
        fn = getattr(checks_profiles, name)

        def timed(*args, _fn=fn, _name=name, **kwargs):
            t0 = time.perf_counter()
            try:
                return _fn(*args, **kwargs)
            finally:
                spent[_name] = spent.get(_name, 0.0) + time.perf_counter() - t0
        setattr(checks_profiles, name, timed)
    return spent


def _tension_free(name: str):
    """The shipped mission without end masses and without tension (its collected current kept)."""
    import tomllib

    from etcheck.input.mission import mission_from_dict

    d = tomllib.loads((ROOT / "missions" / name).read_text())
    d["tether"].pop("end_masses", None)
    d["operation"].pop("orbit_altitude", None)
    d["operation"]["end_tension"] = "0 N"
    d["mission"]["assumed"] = [a for a in d["mission"].get("assumed", []) if a != "tether.end_masses"]
    return mission_from_dict(d, source=f"{name} without tension")


def part2(quick: bool) -> None:
    from etcheck.checks.pipeline import check
    from etcheck.input.mission import load_mission

    spent = _timed_parts()
    names = ["set.toml", "pmg.toml", "tape-tether.toml"] + ([] if quick else ["proseds.toml"])
    missions = [(n, load_mission(ROOT / "missions" / n)) for n in names]
    missions += [(f"{n} T = 0", _tension_free(n)) for n in ("tape-tether.toml", "proseds.toml")]
    print(f"whole checks, the median of {RUNS} runs; rung 1v's parts [s] as this process sees them: all of it, the "
          "damping policy, the work at the verdict's damping shared between the cores, the mode")
    print(f"{'mission':24s} {'fidelity':9s} {'time [s]':>9s} {'rung 1v':>8s} {'policy':>7s} {'together':>9s} "
          f"{'mode':>6s} {'map':>6s} {'verdict':8s} margins")
    for name, mission in missions:
        for fidelity in ("auto", "draft"):
            m = mission.with_fidelity(fidelity)
            runs = []
            for _ in range(RUNS):
                spent.clear()
                forget()  # each check from nothing (the memo of crossings would carry the sign-off's to the draft)
                t0 = time.perf_counter()
                r = check(m).results
                runs.append((time.perf_counter() - t0, dict(spent)))
            dt, parts = sorted(runs, key=lambda x: x[0])[RUNS // 2]
            margins = ", ".join(f"{g['value']:.10g}" if g["value"] is not None else f"- ({g['why'][:60]})"
                                for g in r["margins"])
            whole, policy, mode, smap = (parts.get(p, 0.0) for p in PARTS)
            together = max(whole - policy - mode, 0.0)
            print(f"{name:24s} {fidelity:9s} {dt:9.2f} {whole:8.2f} {policy:7.2f} {together:9.2f} {mode:6.2f} "
                  f"{smap:6.2f} {r['verdict']:8s} {margins}")


if __name__ == "__main__":
    from etcheck.runtime.parallel import serial

    with threadpool_limits(limits=1), serial("--serial" in sys.argv):  # --serial: one core, every part in turn
        if "--checks" not in sys.argv:
            part1()
        part2("--quick" in sys.argv)
