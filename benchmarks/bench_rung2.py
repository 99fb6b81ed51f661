"""Rung-2 timing and accuracy for the SET scene (not a test).

P = 0.001, R = 21/38, Gamma = 1/1.3, f = 4.730040744862704**4, T = 0.
For each resolution N: trace b1 from BP1 to B = 3, b2 to measure_1 = 0.05,
switch onto b12 at b1's secondary pitchfork and follow it back to BP1; print
time, points, largest residual, a two-resolution error (resolution_check:
every 4th point re-solved at N + max(8, N/2)), and B at measure_1 = 0.04 on
each branch with its difference from the finest N. Then the lift-off spins and
the primary pitchfork loads with their stated errors (two resolutions) against
N = 64, and the rung-2 part of issue 10's target "b1 from its pitchfork to
4 B1 with B* located" (time, stated error, ratio to the 3 s of the whole
target, whose stability part bench_rung3.py adds). One core (BLAS pinned).
Run:  python benchmarks/bench_rung2.py [--targets-only]
"""

from __future__ import annotations

import sys
import time

import numpy as np
from threadpoolctl import threadpool_limits

from etcheck.rod.buckled import branches as br
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled import pitchforks, secondary, symmetry
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.analytic import critical_loads

RESOLUTIONS = (20, 24, 32, 40, 48)


def targets(scene: RodParameters) -> None:
    """Time and stated error of the rung-2 target, and the stated errors of the primary pitchforks."""
    t0 = time.perf_counter()
    start = br.primary_branches(scene, 1, 32)[0]
    b1 = br.continue_branch(scene, start, stop=(0.0, 4.0 * start.load))
    pf = secondary.secondary_pitchfork(scene, 0.0, N=32, N_check=48, branch=b1)
    wall = time.perf_counter() - t0
    print(f"== target: b1 pitchfork -> 4 B1 ({len(b1.states)} states) and B* located: {wall:.2f} s "
          f"(ratio to the 3 s of the whole target {wall / 3.0:.2f}); B* = {pf.B:.10f}, stated error {pf.error:.1e}, "
          f"independent 1.94246251: {abs(pf.B - 1.94246251):.1e}")
    print("== primary pitchforks and lift-off spins: stated error (two resolutions) vs true error (N = 64)")
    for p in (scene, scene.with_(omega=0.3, T=0.5), scene.with_(P=0.05, R=0.1, omega=0.2, T=-0.3)):
        for which in ("S1", "S2"):
            t0 = time.perf_counter()
            est = pitchforks.pitchfork_loads(p, which, 24, 2)
            dt = time.perf_counter() - t0
            true = np.abs(est.loads - pitchforks.class_loads(p, which, 64, 2))
            print(f"  omega {p.omega:4.2f} T {p.T:5.2f} R {p.R:.3f} {which}: B = {np.array2string(est.loads, precision=10)}"
                  f" stated {np.array2string(est.errors, precision=1)} true {np.array2string(true, precision=1)}"
                  f" ({dt * 1e3:.0f} ms)")
        for which in ("b1", "b2"):
            t0 = time.perf_counter()
            w = pitchforks.liftoff_estimate(p, which, 1, N=24)
            dt = time.perf_counter() - t0
            if not np.isfinite(w.omega):
                print(f"  {which} does not lift off below omega = 4")
                continue
            roots = pitchforks.pitchfork_spins(p, symmetry.BRANCH_CLASS[which], 64)
            true = float(np.min(np.abs(roots - w.omega)))
            print(f"  {which} lift-off omega = {w.omega:.12f} stated {w.error:.1e} true {true:.1e} ({dt:.2f} s)")


def main() -> None:
    scene = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3)
    Bc = critical_loads(scene.R, scene.f, 1)[0]
    rows = {}
    with threadpool_limits(limits=1):
        br.primary_branches(scene, 1, 16)  # warm imports and caches
        targets(scene)
        if "--targets-only" in sys.argv[1:]:
            return
        for N in RESOLUTIONS:
            t0 = time.perf_counter()
            s1, s2 = br.primary_branches(scene, 1, N)
            t_start = time.perf_counter() - t0
            t0 = time.perf_counter()
            b1 = br.continue_branch(scene, s1, stop=(0.0, 3.0))
            t_b1 = time.perf_counter() - t0
            t0 = time.perf_counter()
            b2 = br.continue_branch(scene, s2, stop=(0.0, 1.0), max_measure1=0.05)
            t_b2 = time.perf_counter() - t0
            t0 = time.perf_counter()
            b12 = br.connecting_branch(b1, stop=(0.0, 3.0))
            t_b12 = time.perf_counter() - t0
            chk = br.resolution_check(b1)
            brk = [q.value for q in b1.special if q.kind == "break"]
            m04 = {name: br.locate(b, eq.measure1, 0.04)[0] for name, b in (("b1", b1), ("b2", b2), ("b12", b12))}
            rows[N] = dict(brk=brk[0] if brk else float("nan"), m04=m04, end=b1.measure1[-1])
            print(f"== N = {N}")
            print(f"  pitchforks (restricted pencils): {t_start * 1e3:6.1f} ms  "
                  f"rel. error vs analytic {abs(s1.load - Bc) / Bc:.1e} (S1), {abs(s2.load - Bc) / Bc:.1e} (S2)")
            print(f"  b1  BP1 -> B = 3: {t_b1:6.2f} s  {len(b1.values):3d} points  max residual {b1.residual:.1e}  "
                  f"two-resolution error (N={chk.N_check}): measure1 {chk.measure1_error:.1e}, "
                  f"deflection {chk.deflection_error:.1e}")
            print(f"  b2  to measure1 0.05: {t_b2:6.2f} s  {len(b2.values):3d} points  max residual {b2.residual:.1e}")
            print(f"  b12 break -> BP1:  {t_b12:6.2f} s  {len(b12.values):3d} points  max residual {b12.residual:.1e}")
            print(f"  secondary pitchfork on b1: B = {rows[N]['brk']:.12f}")
            print("  B at measure1 = 0.04: " + "  ".join(f"{k} {v:.12f}" for k, v in m04.items()))
        ref = rows[RESOLUTIONS[-1]]
        print(f"== differences from N = {RESOLUTIONS[-1]}")
        for N in RESOLUTIONS[:-1]:
            r = rows[N]
            d = "  ".join(f"{k} {abs(r['m04'][k] - ref['m04'][k]):.1e}" for k in ref["m04"])
            print(f"  N = {N:3d}: break {abs(r['brk'] - ref['brk']):.1e}  measure1(B=3) {abs(r['end'] - ref['end']):.1e}"
                  f"  B(measure1 = 0.04): {d}")
        print("== lift-off spins (straight-rod linear theory: pitchfork reaches B = 0)")
        for which in ("b1", "b2"):
            for P in (0.001, 0.0):
                t0 = time.perf_counter()
                vals = [pitchforks.liftoff_spin(scene.with_(P=P), which, N=N) for N in (24, 32)]
                dt = time.perf_counter() - t0
                print(f"  {which} P = {P}: omega = {vals[1]:.10f}  (N 24 vs 32: {abs(vals[0] - vals[1]):.1e})"
                      f"  {dt:5.2f} s")
        p = scene.with_(omega=0.25)
        s1, s2 = br.primary_branches(p, 1, 32)
        b = br.continue_branch(p, s1, stop=(0.0, 3.0))
        b2 = br.continue_branch(p, s2, stop=(0.0, 1.0))
        t0 = time.perf_counter()
        b12 = br.connecting_branch(b, stop=(0.0, 3.0))
        t_b12 = time.perf_counter() - t0
        brk = [q.value for q in b.special if q.kind == "break"]
        brk2 = [q.value for q in b2.special if q.kind == "break"]
        end = [q.value for q in b12.special if q.kind == "bp"]
        nan = float("nan")
        print(f"== omega = 0.25 (N = 32): pitchforks b1 {s1.load:.10f}, b2 {s2.load:.10f}; secondary pitchforks "
              f"on b1 B = {brk[0] if brk else nan:.10f}, on b2 B = {brk2[0] if brk2 else nan:.10f}; b12 "
              f"({t_b12:.2f} s, {len(b12.values)} points) ends at a branch point B = {end[0] if end else nan:.10f}")
        for name, br_ in (("b1", b), ("b2", b2)):
            print(f"  {name}: B at measure1 = 0.04: {br.locate(br_, eq.measure1, 0.04)[0]:.10f}")


if __name__ == "__main__":
    main()
