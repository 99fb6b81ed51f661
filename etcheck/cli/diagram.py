"""``etcheck diagram MISSION.toml --spin 0.25 --branches 3``: bifurcation diagrams of the buckled tether.

Rung 2 (whirling equilibria, continuation from the pitchforks of the straight
tether, branch switching onto the connecting branches) with the stability of
every state (rung 3). ``--spin`` takes the paper's dimensionless omega (a
bare number) or a spin rate with units ("0.1 rpm"); ``--R`` overrides the
stiffness ratio EI2/EI1 (the paper's R = 1 figure). Writes
OUT/<mission>/diagram-<spin>[-R<R>]/{diagram.html, diagram.pdf, diagram.json}.
"""

from __future__ import annotations

import argparse
import math
import re
from pathlib import Path

from etcheck.cli.common import add_output_options, formats, run_and_summarise
from etcheck.errors import MissionError
from etcheck.report.background import renderer

NAME = "diagram"
FORMATS = ("html", "pdf", "json")


def add_parser(sub) -> None:
    p = sub.add_parser(
        NAME, help="bifurcation diagram of the buckled tether (post-buckling branches, stability, shapes)",
        description="Bifurcation diagram of the buckled tether (post-buckling branches, their stability and shapes).",
        epilog="exit codes: 0 written, 2 bad input or a scene outside rungs 2-3's validated range (the message names the limit), 3 a solve failed. Example (the paper's Fig. 12, arXiv:0810.3668): "
        "etcheck diagram missions/set.toml --spin 0.25 --branches 3",
    )
    p.add_argument("mission", help="mission file (TOML)")
    p.add_argument("--spin", default=None,
                   help="spin: dimensionless omega (e.g. 0.25) or a rate with units (e.g. '0.1 rpm'); default: the mission's")
    p.add_argument("--R", type=float, default=None, help="override the stiffness ratio EI2/EI1 (0 < R <= 1)")
    p.add_argument("--branches", type=int, default=3, help="number of primary branches b1, b2, ... (default 3)")
    p.add_argument("--B-max", type=float, default=None, help="end of the load range (dimensionless B; default 3 or past the last pitchfork)")
    p.add_argument("--N", type=int, default=32, help="Chebyshev resolution of the equilibria (default 32)")
    p.add_argument("--no-stability", action="store_true", help="skip the stability of each state (rung 3)")
    p.add_argument("--paths", default="b1,b12",
                   help="branches whose eigenvalue paths are computed and drawn: comma-separated labels, 'all' or "
                        "'none' (default b1,b12: the paper's Figs. 9 and 10)")
    add_output_options(p, FORMATS, "OUT/<mission>/diagram-w<spin>/")
    p.set_defaults(run=run, parser=p)


def _spin(text: str | None, frequency: float) -> float | None:
    """The --spin option as dimensionless omega (``frequency``: the reference frequency in rad/s)."""
    if text is None:
        return None
    from etcheck.input.units import QuantityProblem, to_quantity  # astropy: loaded only when a run starts

    try:
        value = float(text)
    except ValueError:
        try:
            q = to_quantity(text, "angular_rate")
        except QuantityProblem as exc:
            raise MissionError("command line", "--spin", str(exc)) from None
        value = float(q.value) / frequency
    if not math.isfinite(value) or value < 0:
        raise MissionError("command line", "--spin", f"must be a finite, non-negative spin, got {text!r}")
    return value


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    fmts = formats(args, parser)
    if not 1 <= args.branches <= 8:
        parser.error("--branches must lie in [1, 8]")
    if not 16 <= args.N <= 96:
        parser.error("--N must lie in [16, 96]")
    if args.R is not None and not 0 < args.R <= 1:
        parser.error("--R must lie in (0, 1]")
    if args.B_max is not None and not 0 < args.B_max <= 1e3:
        parser.error("--B-max must lie in (0, 1000]")
    paths = _paths(args.paths, parser)

    def action(render):
        # imported here so that `etcheck --help` does not load astropy, scipy and the report stack
        from etcheck.checks.orbit_field import resolve
        from etcheck.checks.rungs.buckled import DiagramOptions
        from etcheck.input.mission import load_mission
        from etcheck.report import write_reports
        from etcheck.scaling import scale
        from etcheck.studies.diagram import diagram_study, folder_name

        resolved = resolve(load_mission(args.mission))
        mission, scales = resolved.mission, scale(resolved.scene).scales
        omega = _spin(args.spin, scales.frequency)
        options = DiagramOptions(branches=args.branches, B_max=args.B_max, N=args.N, stability=not args.no_stability,
                                 paths=paths)
        results = diagram_study(mission, omega, args.R, options)
        tag = folder_name(results["diagram"]["params"]["omega"], args.R)
        return results, write_reports(results, Path(args.out) / mission.slug / tag, fmts, kind="diagram", renderer=render)

    with renderer(fmts, "diagram") as render:  # started first: the report stack loads while the study runs
        return run_and_summarise(lambda: action(render), _summary)


def _paths(text: str, parser: argparse.ArgumentParser) -> tuple[str, ...] | None:
    """--paths as branch labels (None: every branch), or a usage error naming the bad label."""
    text = text.strip().lower()
    if text == "all":
        return None
    if text == "none":
        return ()
    labels = tuple(x.strip() for x in text.split(",") if x.strip())
    bad = [x for x in labels if not re.fullmatch(r"b[1-9][0-9]*", x)]
    if bad or not labels:
        parser.error(f"--paths: {', '.join(bad) or '(empty)'} is not a branch label; give labels such as b1,b12, "
                     "'all' or 'none'")
    return labels


def _summary(results: dict, paths: list) -> None:
    d = results["diagram"]
    print(f"etcheck diagram: {results['mission']['name']} at omega = {d['params']['omega']:.4g} "
          f"(R = {d['params']['R']:.4g}), B up to {d['B_max']:.4g}, {d['time_s']:.1f} s")
    for b in d["branches"]:
        sp = ", ".join(f"{q['kind']} at B = {q['B']:.6g}" for q in b["special"]) or "no special points"
        start = (f"pitchfork B = {b['pitchfork_B']:.10g} +- {_err(b.get('pitchfork_B_error'))}"
                 if b.get("pitchfork_B") is not None else f"from {b.get('from')}")
        print(f"  {b['label']}: {start}; {b['points']} points, N = {b['N']}, {b['time']:.2f} s, "
              f"measure1 error {b['measure1_error']:.1e}; {sp}")
    for lifted in d["lifted_off"]:
        print(f"  {lifted['label']}: lifted off at omega = {lifted['liftoff_omega']:.6g} "
              f"+- {_err(lifted.get('liftoff_omega_error'))} (no longer bifurcates)")
    for path in paths:
        print(f"  wrote {path}")


def _err(x) -> str:
    """A stated error for the terminal: one significant digit, or "n/a" where none was stated."""
    return "n/a" if x is None else f"{x:.0e}"
