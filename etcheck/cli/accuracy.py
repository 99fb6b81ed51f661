"""``etcheck accuracy MISSION.toml``: the speed/accuracy trade of the solvers, measured.

Prints, for the mission's scene, the time of one solve and the error of the
lowest eigenvalue pairs and of the first static load B_c versus the Chebyshev
resolution N (against a reference at 1.5 times the finest N or more), and the time of one automatic
stability solve as the check runs it; with ``--rung2``, the same for tracing
the first post-buckling branch. A measurement, not a test.
"""

from __future__ import annotations

import argparse

from etcheck.cli.common import guarded

NAME = "accuracy"


def _ints(text: str) -> tuple[int, ...]:
    try:
        values = tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated integers, got {text!r}") from None
    if not values or any(n < 4 or n > 80 for n in values):
        raise argparse.ArgumentTypeError("each N must lie in [4, 80]")
    return values


def add_parser(sub) -> None:
    p = sub.add_parser(NAME, help="measure time and accuracy of the solvers versus resolution",
                       description="Measure time and accuracy of the linear (rung 1) solver versus resolution N "
                       "for a mission's scene.")
    p.add_argument("mission", help="mission file (TOML)")
    p.add_argument("--N", type=_ints, default=(8, 12, 16, 24, 32, 48, 64),
                   help="comma-separated resolutions (default 8,12,16,24,32,48,64)")
    p.add_argument("--pairs", type=int, default=10, help="eigenvalue pairs compared (default 10)")
    p.add_argument("--rung2", action="store_true",
                   help="also measure rung 2: time and error of tracing the first post-buckling branch b1")
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    if not 1 <= args.pairs <= 30:
        parser.error("--pairs must lie in [1, 30]")

    def action():
        # imported here so that `etcheck --help` does not load astropy and scipy
        from etcheck.checks.orbit_field import resolve
        from etcheck.input.mission import load_mission
        from etcheck.scaling import scale
        from etcheck.studies.accuracy import rung1_accuracy, rung2_accuracy

        resolved = resolve(load_mission(args.mission))
        mission, scaled = resolved.mission, scale(resolved.scene)
        rows, auto = rung1_accuracy(scaled, args.N, args.pairs)
        _print_rung1(mission.provenance.name, scaled.params, args.pairs, rows, auto)
        if args.rung2:
            print("rung 2: branch b1 from its pitchfork to B = 4 B_1 at the mission's spin and tension "
                  "(one BLAS thread)")
            _print_rung2(*rung2_accuracy(scaled.params))
        return 0

    return guarded(action, "measurement stopped")


def _print_rung1(name, p, pairs, rows, auto) -> None:
    print(f"etcheck accuracy: {name}: P={p.P:.4g} R={p.R:.6g} Gamma={p.Gamma:.6g} "
          f"B={p.B:.6g} omega={p.omega:.6g} T={p.T:.6g} gamma={p.gamma:.6g} f={p.f:.7g}")
    print(f"lowest {pairs} eigenvalue pairs and first static load B_c vs N (reference N = {rows[0].reference_N}, "
          "one BLAS thread, one timed solve per N)")
    print(f"{'N':>4} {'time/solve [ms]':>16} {'eigenvalue error':>17} {'B_c error':>11}")
    for r in rows:
        print(f"{r.N:>4} {r.solve_time_s * 1e3:>16.2f} {r.eigenvalue_error:>17.2e} {r.load_error:>11.2e}")
    state = "converged" if auto.converged else "NOT converged"
    print(f"automatic stability solve (two resolutions, N = {auto.N_check} and {auto.N}): "
          f"{auto.time_s * 1e3:.1f} ms, {state}, max error estimate {auto.max_error:.1e}")
    from etcheck.checks.plan import EXACT, LAYER_MIN, R_MIN_SPECTRAL, boundary_layer, straight_route

    if straight_route(p) == EXACT:
        layer = boundary_layer(p)
        why = (f"its end boundary layers are {layer:.2g} of the length (below {LAYER_MIN:g})" if layer < LAYER_MIN
               else f"its weak axis is nearly a string (R = {p.R:.2g} < {R_MIN_SPECTRAL:g})")
        print(f"NOTE: this scene is outside the collocation's range: {why}. The collocation does not resolve "
              "its bending modes (the B_c column shows how far off they are), and the convergence above concerns "
              "only the eigenvalues it does resolve. `etcheck MISSION` computes this scene's critical values from "
              "the exact characteristic determinant (rung 1x) instead.")


def _print_rung2(ref, traces) -> None:
    if ref.liftoff_omega is not None:
        print(f"b1 has lifted off the straight tether at this spin (lift-off at omega = {ref.liftoff_omega:.6g}, "
              f"N = {ref.N}): there is no b1 to trace; lower operation.spin_rate below it to measure rung 2")
        return
    print(f"{'N':>4} {'time [s]':>9} {'points':>7} {'measure1 at end':>16} {'error':>9} {'2nd pitchfork B':>16} {'error':>9}")
    for t in traces:
        if t.liftoff_omega is not None:
            print(f"{t.N:>4} {t.time_s:>9.2f} b1 has lifted off at this resolution (omega = {t.liftoff_omega:.6g})")
            continue
        print(f"{t.N:>4} {t.time_s:>9.2f} {t.points:>7} {t.measure1_end:>16.10f} "
              f"{abs(t.measure1_end - ref.measure1_end):>9.1e} {_pitchfork(t, ref)}")
    if ref.secondary_pitchfork_B is None:
        print(f"  2nd pitchfork: not found below 4 B_1 (b1 has no secondary pitchfork there at N = {ref.N})")


def _pitchfork(t, ref) -> str:
    """The secondary pitchfork column and its relative error against the reference, or why not."""
    if t.secondary_pitchfork_B is None:
        return f"{'not found below 4 B_1':>26}"
    if ref.secondary_pitchfork_B is None:
        return f"{t.secondary_pitchfork_B:>16.10f} {'n/a':>9}"
    rel = abs(t.secondary_pitchfork_B - ref.secondary_pitchfork_B) / ref.secondary_pitchfork_B
    return f"{t.secondary_pitchfork_B:>16.10f} {rel:>9.1e}"
