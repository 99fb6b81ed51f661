"""Rung-1 timing and accuracy for the SET scene (not a test).

P = 0.001, R = 21/38, Gamma = 0.76923, f = 4.730040744862704**4; omega in
{0, 0.25, 0.75}, gamma in {0, 0.04375}, B = 0. One core (BLAS pinned).
Run:  python benchmarks/bench_rung1.py
"""

from __future__ import annotations

import time

from threadpoolctl import threadpool_limits

from etcheck.rod.convergence import accuracy_table
from etcheck.rod.parameters import RodParameters
from etcheck.rod.spectrum import spectrum
from etcheck.rod.stability import critical_load, divergence_loads


def main() -> None:
    scene = RodParameters(P=0.001, R=21 / 38, Gamma=0.76923)
    with threadpool_limits(limits=1):
        for omega in (0.0, 0.25, 0.75):
            for gamma in (0.0, 0.04375):
                p = scene.with_(omega=omega, gamma=gamma)
                print(f"== omega = {omega}, gamma = {gamma}")
                spectrum(p)  # warm caches
                t0 = time.perf_counter()
                sp = spectrum(p, k=10, tol=1e-8)
                t_auto = time.perf_counter() - t0
                t0 = time.perf_counter()
                sp24 = spectrum(p, k=10, N=24, tol=1e-8)
                t_24 = time.perf_counter() - t0
                print(f"spectrum(auto): {t_auto * 1e3:7.1f} ms  N={sp.N}/{sp.N_check} "
                      f"converged={sp.converged} max err={sp.errors.max():.1e} "
                      f"max Re={sp.max_real:+.3e}")
                print(f"spectrum(N=24): {t_24 * 1e3:7.1f} ms  N={sp24.N}/{sp24.N_check} "
                      f"converged={sp24.converged} max err={sp24.errors.max():.1e}")
                t0 = time.perf_counter()
                d = divergence_loads(p, n=4)
                t_d = time.perf_counter() - t0
                print(f"divergence_loads(n=4): {t_d * 1e3:7.1f} ms  {d}")
                t0 = time.perf_counter()
                c = critical_load(p)
                t_c = time.perf_counter() - t0
                print(f"critical_load: {t_c:6.2f} s  {c.kind} {c.value:.12g} err {c.error:.1e}")
                print("     N   solve[s]   eig err   B_c err")
                for row in accuracy_table(p):
                    print(f"  {row.N:4d}  {row.solve_time:8.4f}  {row.eig_error:8.1e}  {row.load_error:8.1e}")


if __name__ == "__main__":
    main()
