"""``etcheck damping-map MISSION.toml``: where the coiled tether is stable and how well damped (rung 3).

The tether's version of the paper's Fig. 19 (arXiv:0810.3668): over the plane of load
B and spin omega, the damping ratio of the least-damped mode of the first
post-buckling branch b1 for several damping values, under b1's secondary
pitchfork curve. Writes OUT/<mission>/damping-map/{damping.html, damping.pdf,
damping.json} and prints the time and the largest estimated error.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from etcheck.cli.common import add_output_options, formats, run_and_summarise
from etcheck.report.background import renderer

NAME = "damping-map"
FORMATS = ("html", "pdf", "json")


def _floats(text: str) -> tuple[float, ...]:
    try:
        values = tuple(float(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}") from None
    if not values or not all(math.isfinite(v) and 0 < v < 10 for v in values):
        raise argparse.ArgumentTypeError("each damping must lie in (0, 10)")
    return values


def add_parser(sub) -> None:
    p = sub.add_parser(
        NAME, help="stability and damping of the coiled tether over load and spin",
        description="Damping margin of the coiled tether (b1) over load and spin for several dampings "
        "(cf. arXiv:0810.3668 Fig. 19).",
        epilog="exit codes: 0 written, 2 bad input or a scene outside rungs 2-3's validated range (the message names "
        "the limit), 3 a solve failed",
    )
    p.add_argument("mission", help="mission file (TOML)")
    p.add_argument("--gammas", type=_floats, default=None,
                   help="dimensionless Kelvin-Voigt dampings (default: the five of the paper's Fig. 11)")
    p.add_argument("--B-max", type=float, default=None,
                   help="largest dimensionless load B (default: 5 times b1's pitchfork at rest, 2.93 for SET)")
    p.add_argument("--spin-max", type=float, default=4.0, help="largest dimensionless spin omega (default 4)")
    p.add_argument("--points", default="14x12", help="grid, B points x spin points (default 14x12)")
    p.add_argument("--N", type=int, default=24, help="Chebyshev resolution (default 24; the check uses 1.5 N)")
    add_output_options(p, FORMATS, "OUT/<mission>/damping-map/")
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    fmts = formats(args, parser)
    try:
        n_B, n_w = (int(x) for x in args.points.lower().split("x"))
    except ValueError:
        parser.error(f"--points: expected e.g. 14x12, got {args.points!r}")
    if not (2 <= n_B <= 60 and 2 <= n_w <= 60):
        parser.error("--points: each count must lie in [2, 60]")
    if not ((args.B_max is None or 0 < args.B_max <= 50) and 0 < args.spin_max <= 20):
        parser.error("--B-max must lie in (0, 50] and --spin-max in (0, 20]")
    if not 16 <= args.N <= 64:
        parser.error("--N must lie in [16, 64]")

    def action(render):
        # imported here so that `etcheck --help` does not load astropy, scipy and the report stack
        from etcheck.input.mission import load_mission
        from etcheck.report import write_reports
        from etcheck.rod.buckled.damping_map import HOPF_GAMMAS
        from etcheck.studies.damping_map import damping_results

        mission = load_mission(args.mission)
        results = damping_results(mission, args.gammas or HOPF_GAMMAS, args.B_max, args.spin_max, n_B, n_w, args.N)
        return results, write_reports(results, Path(args.out) / mission.slug / "damping-map", fmts, kind="damping",
                                      renderer=render)

    with renderer(fmts, "damping") as render:  # started first: the report stack loads while the study runs
        return run_and_summarise(lambda: action(render), _summary)


def _summary(results: dict, paths: list) -> None:
    s = results["study"]
    print(f"etcheck damping-map: {results['mission']['name']}: {len(s['omega'])} spins x {len(s['B'])} loads, "
          f"{len(s['gammas'])} dampings, N = {s['N']}/{s['N_check']}: {s['time_s']:.1f} s "
          f"(work summed over the cores: equilibria {s['timing']['equilibria_s']:.1f} s, spectra "
          f"{s['timing']['spectra_s']:.1f} s)")
    largest = "not answered" if s["largest_error"] is None else f"{s['largest_error']:.1e}"
    print(f"  largest estimated error of max Re lambda: {largest}; unstable points (max Re lambda > "
          f"{s['unstable_threshold']:g} by more than its error) under the secondary pitchfork: {s['unstable_points']}")
    if s["unresolved_points"]:
        print(f"  {s['unresolved_points']} points not resolved: max Re lambda above the threshold by less than its "
              "error (raise --N)")
    if s.get("b1_born_unstable"):
        print(f"  note: {s['note']}")
    errs = [e for e in s["secondary_pitchfork_error"] if e is not None]
    print(f"  secondary pitchfork curve B*(omega): {len(errs)} points located at N = {s['N']} and {s['N_check']}, "
          f"largest difference {_e(max(errs, default=None))}, {s['curve_time_s']:.1f} s of work")
    for w, why in zip(s["omega"], s["spin_not_answered"]):
        if why:
            print(f"  spin omega = {w:.4g}: map not answered: {why}")
    for w, B, why in zip(s["omega"], s["secondary_pitchfork_B"], s["secondary_pitchfork_reason"]):
        if B is None:
            print(f"  B*(omega = {w:.4g}) not answered: {why}")
    p = s["spin_paths"]
    if p["max_re"] is None or not p["values"]:
        print(f"  b1 at B = {p['B']:.4g} followed in spin: not answered ({p.get('reason') or 'no eigenvalue located'})")
    else:
        print(f"  b1 at B = {p['B']:.4g} followed in spin to {p['values'][-1]:.3g}, gamma = {p['gamma']:g}: largest Re "
              f"lambda {p['max_re']:.3e} ({'no Hopf crossing' if p['max_re'] < 0 else 'a mode crosses'}), "
              f"{p['time_s']:.1f} s")
    for g, z in zip(s["gammas"], s["smallest_damping_ratio"]):
        print(f"  gamma = {g:g}: smallest damping ratio of b1 over the map {z if z is None else f'{z:.3e}'}")
    for path in paths:
        print(f"  wrote {path}")


def _e(x) -> str:
    """An error for the terminal, or "n/a" where none was located."""
    return "n/a" if x is None else f"{x:.1e}"
