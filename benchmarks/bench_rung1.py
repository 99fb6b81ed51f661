"""Rung-1 time and accuracy per model and resolution for the SET scene (a measurement, not a test).

SET: P = 0.001, R = 21/38, Gamma = 1/1.3, f = 4.730040744862704**4, omega = 0.25,
B = 0.00368; damped (gamma = 0.04375) and undamped. One core (BLAS pinned), best
of 3 after a warm-up (operator families and LUs are memoised per process, as in
the check). For each part of the signed-off check:

* static curves: the load roots on 61 spin rows and the spin roots at 60 loads
  from one LU per family (:mod:`etcheck.rod.straight.collocation.static_map`) against the reduced QZ
  pencil of every row and load; error: largest relative distance of the rows'
  first roots to those at N = 48;
* damped rows: classified by crossing directions (no eigenvalue solve);
* Campbell diagram (41 spins, 10 pairs): time and its two-resolution error;
* accuracy table (N = 8..32 against N = 48) and the whole rung-1 answer.

Run:  python benchmarks/bench_rung1.py
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import replace
from functools import partial

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

from etcheck.checks.rungs.straight import linear_stability  # noqa: E402
from etcheck.input.mission import load_mission  # noqa: E402
from etcheck.rod.core.spectrum import check_resolution, spectrum  # noqa: E402
from etcheck.rod.straight.collocation.convergence import accuracy_table  # noqa: E402
from etcheck.rod.straight.collocation.spectral import campbell, straight_family  # noqa: E402
from etcheck.rod.straight.collocation.static_map import stable_rows, static_curves  # noqa: E402
from etcheck.scaling import scale, scene  # noqa: E402

ROWS, LOADS, SPINS = 61, 60, 41


def best(fn, repeats: int = 3):
    """(best time of ``repeats`` calls after one warm-up [s], last result)."""
    out = fn()
    t = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        t = min(t, time.perf_counter() - t0)
    return t, out


def qz_curves(p, B_max, w_max, N):
    """The same points by one reduced QZ per row and per load (the route the map took before)."""
    fam = straight_family(p, N)
    first = []
    for w in np.linspace(0.0, w_max, ROWS):
        r = fam.pencil_roots("B", 0.0, w, p.T)
        first.append(r[r > 0][0] if np.any(r > 0) else math.inf)
    for b in np.linspace(0.0, B_max, LOADS):
        fam.pencil_roots("omega", b, 0.0, p.T)
    return np.array(first)


def first_roots(curves):
    return np.array([r[r > 0][0] if np.any(r > 0) else math.inf for r in curves.loads])


def model(name: str, p, scaled) -> None:
    B_max, w_max = 0.883, 1.193  # the SET map's box (1.6 x the critical values)
    print(f"\n== {name}: gamma = {p.gamma}")
    t, sp = best(lambda: spectrum(p, k=10, tol=1e-8), 1)
    print(f"operating spectrum (auto)   {t * 1e3:8.1f} ms  N = {sp.N}/{sp.N_check}, max error {sp.errors.max():.1e}")
    ref = first_roots(static_curves(p, B_max, w_max, np.linspace(0.0, w_max, ROWS), LOADS, N=48))
    print(f"{'':28s}{'N':>4} {'small W [ms]':>13} {'QZ [ms]':>9} {'rows [ms]':>10} {'first-root error':>17}")
    for N in (16, 24, 32):
        t_w, curves = best(partial(static_curves, p, B_max, w_max, np.linspace(0.0, w_max, ROWS), LOADS, N=N))
        t_qz, qz = best(partial(qz_curves, p, B_max, w_max, N), 1)
        rows = "-"
        if p.gamma > 0:
            rows = f"{best(partial(stable_rows, p, curves, B_max))[0] * 1e3:10.1f}"
        got = first_roots(curves)
        fin = np.isfinite(ref)
        err = float(np.max(np.abs(got[fin] - ref[fin]) / ref[fin]))
        agree = float(np.max(np.abs(got[fin] - qz[fin]) / qz[fin]))
        print(f"static curves ({ROWS} + {LOADS})     {N:4d} {t_w * 1e3:13.1f} {t_qz * 1e3:9.1f} {rows:>10} {err:17.1e}"
              f"   (W vs QZ {agree:.0e})")
    for N in (16, 24, 32):
        t, cd = best(partial(campbell, p, np.linspace(0.0, w_max, SPINS), k=10, N=N), 1)
        print(f"Campbell ({SPINS} spins, 10 pairs) N = {N:2d}/{check_resolution(N):2d}: {t * 1e3:7.1f} ms"
              f"  ({t / (SPINS + 3) * 1e3:.1f} ms per solve), error {cd.error:.1e}")
    t, table = best(lambda: accuracy_table(p), 1)
    print(f"accuracy table               {t * 1e3:8.1f} ms   N   solve [ms]  eig error  B_c error")
    for r in table:
        print(f"{'':41s}{r.N:4d} {r.solve_time * 1e3:10.1f}  {r.eig_error:9.1e}  {r.load_error:9.1e}")
    t, lin = best(lambda: linear_stability(scaled), 1)
    print(f"rung 1 signed off (linear_stability): {t:.3f} s; critical load {lin.critical_load.value:.12g}"
          f" (error {lin.critical_load.error:.1e}), Campbell error {lin.campbell.error:.1e}")


def main() -> None:
    scaled = scale(scene(load_mission("missions/set.toml")))
    with threadpool_limits(limits=1):
        for name, gamma in (("damped", scaled.params.gamma), ("undamped", 0.0)):
            s = replace(scaled, params=scaled.params.with_(gamma=gamma))
            model(name, s.params, s)


if __name__ == "__main__":
    main()
