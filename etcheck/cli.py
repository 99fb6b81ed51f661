"""Command line: a thin shell over :func:`etcheck.check` and the report writers."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import __version__
from .errors import EtcheckError

EXIT_TEXT = """exit codes:
  0  the check ran and every margin meets the required margin
  1  the check ran and a margin fails (or the check is incomplete)
  2  bad input or usage (mission file, options, report cannot be written)
  3  a numerical solve failed (nothing is reported from it)
"""

FORMATS = ("html", "pdf", "json")


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="etcheck",
        description="Check an electrodynamic tether mission against magnetic buckling and whirl, "
        "and write HTML, PDF and JSON margin reports.",
        epilog=EXIT_TEXT + "\nsee also: etcheck accuracy MISSION.toml (speed/accuracy of the solvers)\n"
        "          etcheck sweep MISSION.toml --length 50m:5km:40:log --spin 0rpm:2rpm:40 (what-if maps)\n"
        "          etcheck diagram MISSION.toml --spin 0.25 --branches 3 (post-buckling bifurcation diagram)\n"
        "          etcheck damping-map MISSION.toml (stability and damping of the coiled tether)",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("mission", help="mission file (TOML), e.g. missions/set.toml")
    p.add_argument("--out", default="reports", help="output folder (default: reports/); "
                   "the report goes to OUT/<mission-name>/")
    p.add_argument("--format", default="html,pdf,json",
                   help="comma-separated list of html, pdf, json (default: all three)")
    p.add_argument("--version", action="version", version=f"etcheck {__version__}")
    return p


def _formats(text: str, parser: argparse.ArgumentParser) -> tuple[str, ...]:
    items = tuple(x.strip().lower() for x in text.split(",") if x.strip())
    bad = [x for x in items if x not in FORMATS]
    if bad or not items:
        parser.error(f"--format: unknown format {', '.join(bad) or '(empty)'}; use any of {', '.join(FORMATS)}")
    return items


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == "accuracy":
        from .accuracy_cli import main as accuracy_main

        return accuracy_main(argv[1:])
    if argv and argv[0] == "diagram":
        from .diagram_cli import main as diagram_main

        return diagram_main(argv[1:])
    if argv and argv[0] == "damping-map":
        from .damping_cli import main as damping_main

        return damping_main(argv[1:])
    if argv and argv[0] == "sweep":
        from .sweep_cli import main as sweep_main

        return sweep_main(argv[1:])
    parser = _parser()
    args = parser.parse_args(argv)
    formats = _formats(args.format, parser)
    def run():
        from .mission import load_mission
        from .pipeline import check
        from .report import write_reports

        mission = load_mission(args.mission)
        if sys.stderr.isatty():
            print(f"etcheck: checking {mission.name} ...", file=sys.stderr, flush=True)
        result = check(mission)
        return result, write_reports(result.results, Path(args.out) / mission.slug, formats)

    out = guarded(run, "no report written")
    if isinstance(out, int):
        return out
    result, paths = out
    _summary(result.results, paths)
    return result.exit_code


def results_header(mission) -> dict:
    """Version, time stamp and mission echo at the top of every results file."""
    import datetime as dt

    return {"schema_version": 1, "etcheck_version": __version__,
            "generated": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"), "mission": mission.echo()}


def run_and_summarise(action, summary) -> int:
    """``guarded(action)``, then ``summary(results, paths)``; exit 0, or the error's exit code."""
    out = guarded(action, "nothing written")
    if isinstance(out, int):
        return out
    summary(*out)
    return 0


def guarded(action, interrupted: str):
    """Run ``action()``; user errors, Ctrl-C and bugs become a message and an exit code (no traceback).

    Returns the action's value, or the exit code (an int) when it failed.
    """
    try:
        return action()
    except EtcheckError as exc:
        print(f"etcheck: {'error: ' if exc.exit_code != 130 else ''}{exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print(f"etcheck: interrupted; {interrupted}", file=sys.stderr)
        return 130
    except Exception as exc:  # a bug, not the user's fault: say so, no traceback
        print(f"etcheck: internal error ({type(exc).__name__}: {exc}); {interrupted}. "
              "Please report this with the mission file.", file=sys.stderr)
        return 3


def _summary(results: dict, paths: list[Path]) -> None:
    """A few lines on stdout: verdict, margins, where the reports are."""
    print(f"etcheck {__version__}: {results['mission']['name']}: {results['verdict'].upper()}")
    for m in results["margins"]:
        value = "not answered" if m["verdict"] == "incomplete" else "unlimited" if m["value"] is None else f"{m['value']:.4g}"
        print(f"  {m['name']}: margin {value} (required {m['required']:g}) -> {m['verdict']} [{m['model']}]")
        if m["verdict"] == "incomplete":
            print(f"    incomplete: {m['why']}")
    for path in paths:
        print(f"  wrote {path}")
