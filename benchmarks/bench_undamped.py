"""Undamped straight tether: the exact undamped determinant against the spectral scans (not a test).

For each scene: the critical load at the operating spin, the critical spin
at the operating load and the stable spin windows from
:func:`etcheck.rod.straight.exact.undamped.undamped_critical` (rung 1u), their
time, and the largest difference from the spectral scans of
:mod:`etcheck.rod.straight.collocation.spectral` (``critical_load``, ``scan_line`` over the
same spin range, bisected to 1e-10; their own error estimates are printed
with them). One core (BLAS pinned); timings on a shared machine are noisy.

Then a 40 x 40 length x spin sweep of SET without damping (the mission with
``damping_time = "0 s"``), as ``etcheck sweep missions/set.toml --length
50m:5km:40:log --spin 0rpm:20rpm:40``, on two worker processes.

Run:  python benchmarks/bench_undamped.py [--no-sweep] [--no-scan] [--sweep-only]
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

from threadpoolctl import threadpool_limits

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.spectral import critical_load, scan_line
from etcheck.rod.straight.exact.undamped import undamped_critical

SET = dict(P=1e-3, R=21 / 38, Gamma=0.76923)

#: (name, parameters): SET-like, isotropic, thin and strongly anisotropic, tension, low P,
#: spin far above critical, zero spin; flutter windows in the SET spin line
SCENES = [
    ("SET, omega = 0.25, B = 0.3 (flutter windows)", RodParameters(**SET, omega=0.25, B=0.3)),
    ("R = 1, omega = 0.3, B = 0.2", RodParameters(P=1e-3, R=1.0, Gamma=0.76923, omega=0.3, B=0.2)),
    ("R = 0.01, omega = 0.05, B = 0.02", RodParameters(P=1e-3, R=0.01, Gamma=0.76923, omega=0.05, B=0.02)),
    ("R = 0.05, omega = 0.1, B = 0.05", RodParameters(P=1e-3, R=0.05, Gamma=0.76923, omega=0.1, B=0.05)),
    ("SET, T = 2, omega = 0.3, B = 0.2", RodParameters(**SET, T=2.0, omega=0.3, B=0.2)),
    ("P = 1e-6, R = 0.3, omega = 0.2, B = 0.1", RodParameters(P=1e-6, R=0.3, Gamma=0.76923, omega=0.2, B=0.1)),
    ("SET, omega = 3 (far above critical), B = 0.1", RodParameters(**SET, omega=3.0, B=0.1)),
    ("SET, omega = 0, B = 0.3", RodParameters(**SET, omega=0.0, B=0.3)),
]


def _rel(a: float, b: float) -> float:
    if math.isnan(a) and math.isnan(b):
        return 0.0
    return abs(a - b) / max(abs(b), 1e-3)


def compare(name: str, p: RodParameters, scan: bool) -> float:
    t0 = time.perf_counter()
    u = undamped_critical(p)
    dt = time.perf_counter() - t0
    print(f"\n{name}: {dt * 1e3:.0f} ms, {u.evaluations} evaluations, stable = {u.stable}")
    print(f"  load {u.critical_load.value:.12g} ({u.critical_load.kind}, error {u.critical_load.error:.1e})")
    print(f"  spin {u.critical_spin.value:.12g} ({u.critical_spin.kind}, error {u.critical_spin.error:.1e})")
    print("  windows " + ", ".join(f"[{a:.10g}, {b:.10g}]" for a, b in u.windows))
    if not scan:
        return dt
    t0 = time.perf_counter()
    load = critical_load(p.with_(B=0.0))
    spin, windows, _ = scan_line(p.with_(omega=0.0), "omega", hi=u.scanned_to)
    ds = time.perf_counter() - t0
    worst = max(_rel(u.critical_load.value, load.value), _rel(u.critical_spin.value, spin.value))
    same = len(windows) == len(u.windows)
    if same:
        worst = max([worst] + [_rel(x, y) for w, v in zip(u.windows, windows) for x, y in zip(w, v)])
    print(f"  scans: {ds:.1f} s; load {load.value:.12g} ({load.kind}, error {load.error:.1e}), "
          f"spin {spin.value:.12g} ({spin.kind}, error {spin.error:.1e})")
    print(f"  largest relative difference {worst:.1e}" + ("" if same else f"; WINDOWS DIFFER: {windows}"))
    return dt


def sweep_undamped() -> None:
    import tomllib

    from etcheck.input.mission import mission_from_dict
    from etcheck.input.sweep_axes import parse_option
    from etcheck.studies.sweep import SweepOptions, sweep

    root = Path(__file__).resolve().parents[1]
    data = tomllib.loads((root / "missions" / "set.toml").read_text())
    data["tether"]["damping_time"] = "0 s"
    mission = mission_from_dict(data, "set-undamped")
    axes = (parse_option("length", "50m:5km:40:log"), parse_option("spin", "0rpm:20rpm:40"))
    t0 = time.perf_counter()
    res = sweep(mission, axes, SweepOptions(workers=2, chunk=8))
    wall = time.perf_counter() - t0
    g = res["grid"]
    print(f"\nSET undamped sweep 40 x 40: {wall:.1f} s wall on 2 workers (target < 60 s), "
          f"{res['cost']['cpu_s_solved_points']:.1f} CPU s, counts {g['counts']}, regions {g['regions']}, "
          f"largest error estimate {g['max_error']}")


def main() -> None:
    scan = "--no-scan" not in sys.argv
    if "--sweep-only" not in sys.argv:
        with threadpool_limits(limits=1):
            times = [compare(name, p, scan) for name, p in SCENES]
        print(f"\nundamped critical load + critical spin + windows: median "
              f"{sorted(times)[len(times) // 2] * 1e3:.0f} ms, max {max(times) * 1e3:.0f} ms (target < 300 ms)")
    if "--no-sweep" not in sys.argv:
        sweep_undamped()


if __name__ == "__main__":
    main()
