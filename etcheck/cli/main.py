"""``etcheck``: the entry point. ``etcheck MISSION.toml`` is short for ``etcheck check MISSION.toml``."""

from __future__ import annotations

import argparse
import sys

from etcheck import __version__
from etcheck.cli import accuracy, check, damping_map, diagram, sweep
from etcheck.cli.common import EXIT_TEXT
from etcheck.numerics.blas import pin_before_numpy
from etcheck.numerics.heap import keep_freed_memory

#: subcommand modules; each has ``add_parser(subparsers)`` that sets ``run(args, parser) -> int``
COMMANDS = (check, sweep, diagram, damping_map, accuracy)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="etcheck",
        description="Design checks of electrodynamic space tethers against magnetic buckling and whirl. "
        "'etcheck MISSION.toml' is short for 'etcheck check MISSION.toml'.",
        epilog=EXIT_TEXT,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--version", action="version", version=f"etcheck {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", title="commands")
    for module in COMMANDS:
        module.add_parser(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    pin_before_numpy()  # small matrices, parallel processes: BLAS threads only cost time (and ~20 ms to limit)
    keep_freed_memory()  # the solvers' matrices reuse freed memory instead of fresh pages (etcheck.numerics.heap)
    argv = list(sys.argv[1:] if argv is None else argv)
    names = {m.NAME for m in COMMANDS}
    if argv and argv[0] not in names and not argv[0].startswith("-"):
        argv = ["check", *argv]  # the shorthand the README uses
    p = parser()
    args = p.parse_args(argv)
    if args.command is None:
        p.print_help()
        return 2
    return args.run(args, args.parser)
