"""``etcheck accuracy MISSION.toml``: the speed/accuracy trade of rung 1, measured.

Prints, for the mission's scene, the time of one solve and the error of the
lowest eigenvalue pairs and of the first static load B_c versus the Chebyshev
resolution N (against a reference at N = 96), and the time of one automatic
stability solve as the check runs it. A measurement, not a test.
"""

from __future__ import annotations

import argparse
import sys
import time

from .errors import EtcheckError


def _ints(text: str) -> tuple[int, ...]:
    try:
        values = tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated integers, got {text!r}") from None
    if not values or any(n < 4 or n > 80 for n in values):
        raise argparse.ArgumentTypeError("each N must lie in [4, 80]")
    return values


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(
        prog="etcheck accuracy",
        description="Measure time and accuracy of the linear (rung 1) solver versus resolution N "
        "for a mission's scene.",
    )
    parser.add_argument("mission", help="mission file (TOML)")
    parser.add_argument("--N", type=_ints, default=(8, 12, 16, 24, 32, 48, 64),
                        help="comma-separated resolutions (default 8,12,16,24,32,48,64)")
    parser.add_argument("--pairs", type=int, default=10, help="eigenvalue pairs compared (default 10)")
    parser.add_argument("--rung2", action="store_true",
                        help="also measure rung 2: time and error of tracing the first post-buckling branch b1")
    args = parser.parse_args(argv)
    if not 1 <= args.pairs <= 30:
        parser.error("--pairs must lie in [1, 30]")
    try:
        from .mission import load_mission
        from .rod.spectrum import spectrum
        from .scaling import scale, scene
        from .whirl import accuracy

        mission = load_mission(args.mission)
        scaled = scale(scene(mission))
        rows = accuracy(scaled, args.N, k=args.pairs)
        best = float("inf")
        for _ in range(3):
            t0 = time.perf_counter()
            auto = spectrum(scaled.params, k=args.pairs)
            best = min(best, time.perf_counter() - t0)
    except EtcheckError as exc:
        print(f"etcheck: error: {exc}", file=sys.stderr)
        return exc.exit_code
    p = scaled.params
    print(f"etcheck accuracy: {mission.name}: P={p.P:.4g} R={p.R:.6g} Gamma={p.Gamma:.6g} "
          f"B={p.B:.6g} omega={p.omega:.6g} T={p.T:.6g} gamma={p.gamma:.6g} f={p.f:.7g}")
    print(f"lowest {args.pairs} eigenvalue pairs and first static load B_c vs N (reference N = 96, one BLAS thread)")
    print(f"{'N':>4} {'time/solve [ms]':>16} {'eigenvalue error':>17} {'B_c error':>11}")
    for r in rows:
        print(f"{r['N']:>4} {r['solve_time_s'] * 1e3:>16.2f} {r['eigenvalue_error']:>17.2e} {r['load_error']:>11.2e}")
    state = "converged" if auto.converged else "NOT converged"
    print(f"automatic stability solve (two resolutions, N = {auto.N_check} and {auto.N}): "
          f"{best * 1e3:.1f} ms, {state}, max error estimate {max(auto.errors, default=float('nan')):.1e}")
    if args.rung2:
        _rung2(p)
    return 0


def _rung2(p) -> None:
    """Rung 2: trace b1 from its pitchfork to 4 x that load at several N (errors against N = 48)."""
    import math

    from .numerics.eigen import single_blas_thread
    from .rod import branches as br

    @single_blas_thread
    def trace(N):
        t0 = time.perf_counter()
        start = next(s for s in br.primary_branches(p.with_(B=0.0), 1, N) if s.which == "S1")
        b1 = br.continue_branch(p, start, stop=(0.0, 4.0 * start.load), N=N)
        brk = next((q.value for q in b1.special if q.kind == "break"), math.nan)
        return time.perf_counter() - t0, b1, brk

    print("rung 2: branch b1 from its pitchfork to B = 4 B_1 at the mission's spin and tension (one BLAS thread)")
    _, ref, ref_brk = trace(48)
    print(f"{'N':>4} {'time [s]':>9} {'points':>7} {'measure1 at end':>16} {'error':>9} {'2nd pitchfork B':>16} {'error':>9}")
    for N in (20, 24, 32, 40):
        t, b1, brk = trace(N)
        print(f"{N:>4} {t:>9.2f} {len(b1.values):>7} {b1.measure1[-1]:>16.10f} {abs(b1.measure1[-1] - ref.measure1[-1]):>9.1e}"
              f" {brk:>16.10f} {abs(brk - ref_brk) / ref_brk:>9.1e}")
