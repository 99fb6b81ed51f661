"""Sweep timing and accuracy for SET (a measurement, not a test).

1. The point solver per model and resolution: time of one point and the
   two-resolution error, rung 0 (chi), damped static pencils (rung 1) and the
   undamped spectral scan (rung 1), BLAS on one thread.
2. The 40 x 40 length x spin sweep of the issue (50 m - 5 km log, 0 - 20 rpm)
   and a 40 x 40 sweep over the interesting range (0 - 2 rpm), on every local
   core, without a cache: wall time, points per second per core, largest error.
Run:  python benchmarks/bench_sweep.py
"""

from __future__ import annotations

import os
import time

from threadpoolctl import threadpool_limits

from etcheck.input.mission import load_mission
from etcheck.input.sweep_axes import parse_option
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.damped_critical import LADDER, _first_root, first_root
from etcheck.studies.sweep import SweepOptions, solve_point, sweep

SET = RodParameters(P=1e-3, R=21 / 38, Gamma=0.76923, f=500.5639, gamma=0.04375)


def _time(fn, repeat=3):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def points() -> None:
    print("== one point (best of 3, caches cleared between points by changing P)")
    with threadpool_limits(limits=1):
        for label, p in (("rung 0, omega = T = 0", SET.with_(B=0.3)),
                         ("rung 1 pencils, omega = 0.25", SET.with_(B=0.3, omega=0.25)),
                         ("rung 1 pencils, omega = 0.25, T = 1", SET.with_(B=0.3, omega=0.25, T=1.0)),
                         ("rung 1 scan, undamped, omega = 0.25", SET.with_(B=0.3, omega=0.25, gamma=0.0))):
            k = [0]

            def run(p=p, k=k):
                k[0] += 1
                return solve_point(p.with_(P=p.P * (1 + 1e-9 * k[0])), 1e-8)

            t, r = _time(run, 1 if p.gamma == 0 else 3)
            print(f"{label:40s} {t * 1e3:8.1f} ms  N={r.N}  B_c={r.B_c:.12g} err={r.B_c_error:.1e}  "
                  f"omega_c={r.omega_c:.12g} err={r.omega_c_error:.1e}")
        print("== damped pencil error versus resolution (critical load at omega = 0.25, T = 1; operators cached)")
        p = SET.with_(omega=0.25, T=1.0)
        ref = first_root(p, "B", 1e-14, ladder=(96,)).value
        for N in LADDER[:5]:
            t, r = _time(lambda N=N: _first_root.__wrapped__(p, "B", 1.0, 1.0, (N,), 0.0))
            print(f"N = {N:3d}/{int(1.5 * N):3d}: {t * 1e3:7.1f} ms  error vs N=96: {abs(r.value - ref) / ref:.1e}  "
                  f"two-resolution estimate: {r.error:.1e}")


def sweeps() -> None:
    m = load_mission("missions/set.toml")
    cores = len(os.sched_getaffinity(0))
    for spin in ("0rpm:20rpm:40", "0rpm:2rpm:40"):
        axes = (parse_option("length", "50m:5km:40:log"), parse_option("spin", spin))
        t0 = time.perf_counter()
        r = sweep(m, axes, SweepOptions(cache=None))
        wall = time.perf_counter() - t0
        c, g = r["cost"], r["grid"]
        print(f"== 40 x 40 sweep, length 50m:5km log, spin {spin}, {cores} workers: wall {wall:.1f} s "
              f"(points {c['solve_wall_s'] - sum(x.get('time_s', 0) for x in r['critical_length'] or []) / cores:.1f} s), "
              f"{c['points_per_s_per_core']:.0f} points/s/core, largest error {g['max_error']:.1e}, "
              f"max N {c['max_resolution']}, regions {g['regions']}")
        ok = [x for x in r["critical_length"] if x["status"] == "ok"]
        print(f"   critical lengths located: {len(ok)}, {sum(x['evaluations'] for x in ok)} solves, "
              f"{sum(x['time_s'] for x in ok):.1f} s CPU; at 0 rpm L_c = {ok[0]['length_m']:.9g} m")


if __name__ == "__main__":
    points()
    sweeps()
