"""``etcheck sweep MISSION.toml --length 50m:5km:40:log --spin 0rpm:2rpm:40``: the what-if sweep.

Writes OUT/<mission>/sweep/{sweep.html, sweep.pdf, sweep.json, sweep.csv,
sweep.nc}; per-point results are kept in OUT/<mission>/sweep/cache as they
finish, so an interrupted sweep resumes when the same command is run again.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from etcheck.cli.common import EXIT_TEXT, add_output_options, formats, guarded
from etcheck.report.background import renderer

NAME = "sweep"
FORMATS = ("html", "pdf", "json", "csv", "nc")


def add_parser(sub) -> None:
    p = sub.add_parser(
        NAME, help="what-if maps: sweep length, spin, current, field, tension, orbit altitude or inclination",
        description="Sweep one or two mission quantities and map the margins of the straight tether.",
        epilog="axes: START:STOP:POINTS[:log], values with units, e.g. --length 50m:5km:40:log "
        "--spin 0rpm:2rpm:40. Without axis options the mission's [sweep] table is used.\n" + EXIT_TEXT,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("mission", help="mission file (TOML)")
    for option, what in (("length", "tether length"), ("spin", "spin rate"), ("current", "current"),
                         ("field", "axial magnetic field"), ("tension", "end tension"),
                         ("altitude", "circular orbit altitude (needs [orbit]; each orbit's worst axial field)"),
                         ("inclination", "orbit inclination (needs [orbit]; each orbit's worst axial field)")):
        p.add_argument(f"--{option}", metavar="START:STOP:N[:log]", help=f"sweep the {what}")
    add_output_options(p, FORMATS, "OUT/<mission>/sweep/")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: every core; 1: serial)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run on a dask.distributed cluster, e.g. tcp://10.0.0.5:8786 (needs etcheck[distributed])")
    p.add_argument("--tolerance", type=float, default=None,
                   help="relative two-resolution agreement of every critical value (default: the mission's [check] tolerance)")
    p.add_argument("--no-cache", action="store_true", help="do not keep per-point results (no resume)")
    p.add_argument("--buckled", action="store_true",
                   help="at straight-unstable points, check the coiled tether on b1 (rungs 2-3; about 1 s per point)")
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    fmts = formats(args, parser)
    if args.workers is not None and args.workers < 1:
        parser.error("--workers must be at least 1")
    if args.tolerance is not None and not 1e-13 <= args.tolerance <= 1e-3:
        parser.error("--tolerance must lie in [1e-13, 1e-3]")

    def action(render):
        # imported here so that `etcheck --help` does not load astropy, scipy and the report stack
        from etcheck.cli.progress import ProgressBar
        from etcheck.input.mission import load_mission
        from etcheck.input.sweep_axes import OPTIONS, parse_option
        from etcheck.report import write_reports
        from etcheck.studies.sweep import SweepOptions, load_axes_or_table, sweep

        mission = load_mission(args.mission)
        axes = load_axes_or_table(mission, [parse_option(o, getattr(args, o)) for o in OPTIONS if getattr(args, o)])
        folder = Path(args.out) / mission.slug / "sweep"
        options = SweepOptions(tol=args.tolerance or mission.check.tolerance, workers=args.workers,
                               scheduler=args.scheduler, cache=None if args.no_cache else folder / "cache",
                               buckled=args.buckled)
        results = sweep(mission, axes, options, progress=ProgressBar(f"etcheck sweep {mission.provenance.name}"))
        return results, write_reports(results, folder, fmts, kind="sweep", renderer=render)

    with renderer(fmts, "sweep") as render:  # started first: the report stack loads while the sweep runs
        out = guarded(lambda: action(render), "rerun the same command to resume")
    if isinstance(out, int):
        return out
    results, paths = out
    _summary(results, paths)
    g = results["grid"]
    return 0 if g["regions"]["failed"] == 0 else 1


def _summary(results: dict, paths: list[Path]) -> None:
    g, c = results["grid"], results["cost"]
    print(f"etcheck sweep: {results['mission']['name']}: {c['points']} points "
          f"({c['solved']} solved, {c['from_cache']} from the cache) in {c['wall_s']:.1f} s")
    v = g["verdicts"]
    print(f"  {v['pass']} of {sum(v.values())} points meet the required margin within the model's validity; "
          f"{g['stable_short']} straight-stable but short of it; {v['outside']} outside the model's validity")
    print(f"  straight-stable {g['regions']['straight-stable']}, buckled-stable {g['regions']['buckled-stable']}, "
          f"straight-unstable {g['regions']['straight-unstable']}, "
          f"no answer {g['regions']['failed']}; largest estimated error {g['max_error'] or 0:.1e}")
    for row in results.get("critical_length") or []:
        if row["status"] == "ok" and row.get("other") is None:
            print(f"  critical length {row['length_m']:.6g} m")
    for path in paths:
        print(f"  wrote {path}")
