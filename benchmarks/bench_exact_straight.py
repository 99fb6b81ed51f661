"""Rung 1x (exact determinant) timing and accuracy for three tethers (not a test).

For each scene: the damped critical values (exact_critical: compressive
limit when compressed, spin at rest, static load, load at the operating
spin, spin at the operating load), the time per critical value, and the
error of the critical load against an mpmath exponential-basis determinant
(50 digits, bisected on its sign). One core (BLAS pinned).

Scenes: SET (Table of the paper, Sec. 7); a 500 m aluminium tape, EI1 =
3.65 N m^2, EI2 = 9.3e-6 N m^2, 2.7 g/m, 0.18 N, I B0 = 30e-6 N/m
(boundary layers of 7 mm); a 20 km tether of the same tape at 5 N.
Run:  python benchmarks/bench_exact_straight.py
"""

from __future__ import annotations

import math
import time

import mpmath as mp
from threadpoolctl import threadpool_limits

from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.rod.straight.exact.roots import exact_critical, string_limit_load


def tape(L: float, tension: float, IB0: float = 30e-6, EI1: float = 3.65, EI2: float = 9.3e-6,
         rho_A: float = 2.7e-3, E: float = 70e9, rho: float = 2700.0) -> RodParameters:
    """Dimensionless parameters of an aluminium tape (eq. (36) of the paper)."""
    A = rho_A / rho
    P = EI1 / E / A / L**2  # I1 / (A L^2)
    return RodParameters(P=P, R=EI2 / EI1, Gamma=1 / 1.33, T=tension * L**2 / (F_CLAMPED * EI1),
                         B=IB0 * L**3 / (F_CLAMPED * EI1), gamma=0.01)


def reference_load(p: RodParameters, guess: float, rel: float = 1e-6) -> float:
    """Root of the mpmath determinant in [guess (1 - rel), guess (1 + rel)], bisected."""
    def det(B):
        with mp.workdps(50):
            B, P, R, f, w, T = (mp.mpf(x) for x in (B, p.P, p.R, p.f, p.omega, p.T))
            a, b, w2 = T + P * R * w**2, T + P * w**2, w**2
            c = [R / f**2, -(R * b + a) / f, a * b - w2 * (R + 1) / f, w2 * (a + b) + B**2, w2**2]
            static = w2 == 0
            ks = [s * mp.sqrt(q) for q in mp.polyroots(c[:4] if static else c, maxsteps=400, extraprec=200)
                  for s in (1, -1)]
            ks.sort(key=lambda z: (float(mp.re(z)), float(mp.im(z))))
            cols = []
            for k in ks:
                Pu, Pv = R / f * k**4 - a * k**2 - w2, k**4 / f - b * k**2 - w2
                g1, g2 = (B * k, Pu), (Pv, -B * k)
                cols.append((k, g1 if abs(g1[0]) + abs(g1[1]) >= abs(g2[0]) + abs(g2[1]) else g2))
            if static:
                cols += [(mp.mpf(0), (1, 0)), (mp.mpf(0), (0, 1))]
            M = mp.matrix(8, 8)
            for j, (k, (u, v)) in enumerate(cols):
                sh = 1 if mp.re(k) > 0 else 0
                for i, s in enumerate((0, 1)):
                    e = mp.exp(k * (s - sh))
                    M[4 * i, j], M[4 * i + 1, j], M[4 * i + 2, j], M[4 * i + 3, j] = u * e, u * k * e, v * e, v * k * e
            return mp.det(M)

    lo, hi = guess * (1 - rel), guess * (1 + rel)
    d_lo = det(lo)
    if not mp.re(d_lo / det(hi)) < 0:
        return math.nan
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if mp.re(det(mid) / d_lo) < 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def main() -> None:
    scenes = {
        "SET, omega = 0.25, B = 0.3": RodParameters(P=0.001, R=21 / 38, Gamma=0.76923, omega=0.25, B=0.3,
                                                     gamma=0.04375),
        "500 m tape, 0.18 N, I B0 = 30e-6 N/m": tape(500.0, 0.18),
        "20 km tape, 5 N, I B0 = 30e-6 N/m": tape(20e3, 5.0),
    }
    with threadpool_limits(limits=1):
        for name, p in scenes.items():
            exact_critical(p)  # warm up
            n = 5
            t0 = time.perf_counter()
            for _ in range(n):
                c = exact_critical(p)
            dt = (time.perf_counter() - t0) / n
            roots = [r for r in (c.critical_load, c.critical_spin, c.spin_at_rest) if math.isfinite(r.value)]
            load = c.critical_load
            ref = reference_load(p.with_(omega=0.0) if p.omega == 0 else p, load.value)
            err = abs(load.value - ref) / ref if math.isfinite(ref) else math.nan
            print(f"== {name}  (T f = {p.T * p.f:.3g}, R = {p.R:.3g})")
            print(f"   exact_critical: {dt * 1e3:7.2f} ms for {len(roots)} critical values "
                  f"({dt * 1e3 / len(roots):.2f} ms each)  stable={c.stable}  converged={c.converged}")
            print(f"   critical load B = {load.value:.15g}  estimate {load.error:.1e}  "
                  f"error vs mpmath {err:.1e}  ({load.model})")
            print(f"   spin at rest {c.spin_at_rest.value:.12g}  critical spin {c.critical_spin.value:.12g}")
            if p.T > 0:
                for order in (1, 2):
                    s = string_limit_load(p, order)
                    print(f"   string limit, order {order}: {s:.12g}  (relative {abs(s - load.value) / load.value:.1e})")


if __name__ == "__main__":
    main()
