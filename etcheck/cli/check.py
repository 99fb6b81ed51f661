"""``etcheck check MISSION.toml`` (or ``etcheck MISSION.toml``): the margin report of one mission."""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from etcheck import __version__
from etcheck.checks.fidelity import TIME_BUDGET
from etcheck.cli.common import EXIT_TEXT, add_output_options, formats, guarded
from etcheck.report.background import renderer

NAME = "check"
FORMATS = ("html", "pdf", "json")


def add_parser(sub) -> None:
    p = sub.add_parser(NAME, help="check a mission and write its HTML, PDF and JSON margin report",
                       description="Check an electrodynamic tether mission against magnetic buckling and whirl, "
                       "and write HTML, PDF and JSON margin reports.",
                       epilog=EXIT_TEXT, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("mission", help="mission file (TOML), e.g. missions/set.toml")
    add_output_options(p, FORMATS, "OUT/<mission-name>/")
    p.add_argument("--draft", action="store_true",
                   help="margins and verdict only, at a looser tolerance (1e-6): no maps, Campbell diagram, "
                   "accuracy table or post-buckling analysis (same as [check] fidelity = \"draft\")")
    p.add_argument("--time-budget", type=float, default=TIME_BUDGET, metavar="SECONDS",
                   help=f"seconds of computation after which a sign-off skips the report's extras it has not "
                   f"computed yet (operating spectrum, Campbell diagram, stability map, accuracy table), saying so "
                   f"in the report; the margins are always answered (default {TIME_BUDGET:g}; 0: no limit)")
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    fmts = formats(args, parser)
    if not args.time_budget >= 0:  # NaN included
        parser.error(f"--time-budget: {args.time_budget:g} is not a number of seconds >= 0")

    def action(render):
        from etcheck.checks.pipeline import check
        from etcheck.checks.rungs.straight import DEFAULT_OPTIONS
        from etcheck.input.mission import load_mission
        from etcheck.report import render as in_process
        from etcheck.report import write_reports

        mission = load_mission(args.mission)
        if args.draft:
            mission = mission.with_fidelity("draft")
        if sys.stderr.isatty():
            print(f"etcheck: checking {mission.provenance.name} ...", file=sys.stderr, flush=True)
        # while a report process loads the report stack, the accuracy table's timed solves run after the rest
        result = check(mission, replace(DEFAULT_OPTIONS, accuracy_beside=render is in_process,
                                        time_budget=args.time_budget or None))
        return result, write_reports(result.results, Path(args.out) / mission.slug, fmts, renderer=render)

    with renderer(fmts) as render:  # started first: the report stack loads while the check runs
        out = guarded(lambda: action(render), "no report written")
    if isinstance(out, int):
        return out
    result, paths = out
    summary(result.results, paths)
    return result.exit_code


def summary(results: dict, paths: list[Path]) -> None:
    """A few lines on stdout: verdict, margins, where the reports are."""
    draft = " (DRAFT: margins only, not for signature)" if results.get("fidelity", {}).get("name") == "draft" else ""
    verdict = "OUTSIDE THE MODEL'S VALIDITY" if results["verdict"] == "outside" else results["verdict"].upper()
    print(f"etcheck {__version__}: {results['mission']['name']}: {verdict}{draft}")
    for reason in results["model_validity"]["reasons"]:
        print(f"  outside the model's validity: {reason}")
    if "attachment" in results:
        print(f"  ends: {results['attachment']['described']}")
    for m in results["margins"]:
        value = "not answered" if m["verdict"] == "incomplete" else "unlimited" if m["value"] is None else f"{m['value']:.4g}"
        print(f"  {m['name']}: margin {value} (required {m['required']:g}) -> {m['verdict']} [{m['model']}]")
        if m["verdict"] == "incomplete":
            print(f"    incomplete: {m['why']}")
        for a in m.get("alternatives", ()):
            other = "not answered" if a["verdict"] == "incomplete" else "unlimited" if a["value"] is None else \
                f"{a['value']:.4g}"
            print(f"    if both ends were {a['ends'][0]}: margin {other} -> {a['verdict']}")
    for part in results.get("resources", {}).get("skipped", []):
        print(f"  skipped {part['part']}: {part['why']}")
    slow = slow_check(results)
    if slow:
        print(f"  {slow}")
    for line in probability_lines(results):
        print(line)
    for path in paths:
        print(f"  wrote {path}")


#: seconds a sign-off is expected to take at most (docs/performance.md); past it the CLI says where the time went
SIGN_OFF_SECONDS = 10.0
#: seconds a draft aims at (its check, not the command's start-up); past it the CLI says which models took the time
DRAFT_SECONDS = 1.0


def slow_check(results: dict) -> str:
    """For a sign-off that took longer than :data:`SIGN_OFF_SECONDS`: how long, how much of it the margins took
    (never skipped) and by which model, and the draft that answers the margins alone; for a draft past
    :data:`DRAFT_SECONDS`: how long, and the models of its margins (a draft computes nothing else); "" otherwise."""
    res = results.get("resources") or {}
    elapsed = results.get("elapsed_s", 0.0)
    models = ", ".join(dict.fromkeys(m["model"] for m in results.get("margins", ())))
    if results.get("fidelity", {}).get("name") == "draft":
        if elapsed <= DRAFT_SECONDS:
            return ""
        return (f"this draft took {elapsed:.1f} s, more than the second a draft aims at: its margins alone, by "
                f"{models} for this scene (docs/performance.md)")
    if elapsed <= SIGN_OFF_SECONDS or "margins_s" not in res:
        return ""
    return (f"this sign-off took {elapsed:.1f} s, {res['margins_s']:.1f} s of it the margins ({models}), "
            "which are never skipped; --draft answers the margins alone at a relative tolerance of 1e-6")


def probability_lines(results: dict) -> list[str]:
    """The uncertainty study's probability of each margin falling short, one line each (empty without it)."""
    lines = []
    for p in (results.get("uncertainty") or {}).get("probabilities", []):
        head = f"  P({p['margin']} < {p['required']:g})"
        if p["value"] is None and p["bound"] is None:
            lines.append(f"{head}: not answered: {p['how']}")
        elif p["value"] is None:
            lines.append(f"{head} < {p['bound']:.2g} [{p['method']}, {p['evaluations']} margin evaluations]")
        else:
            err = (f"± {100 * p['error']:.2g} %, 95 % interval {p['low']:.6g} … {p['high']:.6g}"
                   if p["method"] == "sampling" else
                   f"error ≤ {p['error']:.1e} relative" if p["error"] is not None else "exact")
            lines.append(f"{head} = {p['value']:.4g} ({err}) [{p['method']}, {p['evaluations']} margin evaluations]")
    return lines
