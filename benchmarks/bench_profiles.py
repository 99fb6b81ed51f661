"""Rung 1v (current and tension along the tether) timing and accuracy per resolution (not a test).

Part 1, per middle resolution N of the graded collocation (the ladder's rungs): the time of one search for the
first crossing along the load on one mesh (scan, bracket, Brent with the tracked eigenvalue) and its distance to
a reference (uniform profiles: the exact determinant; profiles: the finest mesh), for

* the shipped tape with a uniform current (layers of 6e-5 L, R = 2.6e-6), damped: against the exact determinant;
* the tape with its current falling linearly from the lower end, undamped (flutter) and damped (gamma = 0.04375,
  Ziegler's slow flutter);
* a 200 m SET-like tether with a kinked current and its gravity-gradient tension, damped.

Part 2: whole checks (sign-off and draft) of missions with profiles (PMG, the tape, ProSEDS, the 200 m tether)
and of uniform missions (SET; unchanged: they do not enter rung 1v). One core (BLAS pinned).

Run:  python benchmarks/bench_profiles.py [--quick]
"""

from __future__ import annotations

import dataclasses
import sys
import time
from pathlib import Path

from threadpoolctl import threadpool_limits

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.profile import Profile
from etcheck.rod.straight.circulatory import critical
from etcheck.rod.straight.exact import exact_critical
from etcheck.rod.straight.profiles import Tether, mesh

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


def part2(quick: bool) -> None:
    from etcheck.checks.pipeline import check
    from etcheck.input.mission import load_mission

    missions = ["set.toml", "pmg.toml", "tape-tether.toml"] + ([] if quick else ["proseds.toml"])
    print("whole checks (one core)")
    print(f"{'mission':20s} {'fidelity':9s} {'time [s]':>9s} {'verdict':8s} margins")
    for name in missions:
        for fidelity in ("auto", "draft"):
            m = dataclasses.replace(load_mission(ROOT / "missions" / name), fidelity=fidelity)
            t0 = time.perf_counter()
            r = check(m).results
            dt = time.perf_counter() - t0
            margins = ", ".join(f"{g['value']:.4g}" if g["value"] is not None else "-" for g in r["margins"])
            print(f"{name:20s} {fidelity:9s} {dt:9.2f} {r['verdict']:8s} {margins}")


if __name__ == "__main__":
    with threadpool_limits(limits=1):
        part1()
        part2("--quick" in sys.argv)
