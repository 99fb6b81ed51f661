"""``etcheck``: the entry point. ``etcheck MISSION.toml`` is short for ``etcheck check MISSION.toml``."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys

from etcheck import __version__
from etcheck.cli import accuracy, check, damping_map, diagram, sweep
from etcheck.cli.common import EXIT_TEXT, stopped
from etcheck.runtime import memory
from etcheck.runtime.blas import pin_before_numpy
from etcheck.runtime.heap import keep_freed_memory
from etcheck.runtime.lifetime import stop_on_signals

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
    for command in sub.choices.values():
        command.add_argument("--memory-budget", metavar="SIZE", default=None,
                             help=f"most memory one process may use, e.g. \"2 GB\" (default: ${memory.VARIABLE} or "
                             f"{memory.DEFAULT}); a solve that would need more is not answered (exit 1, with the reason)")
    return p


def main(argv: list[str] | None = None) -> int:
    pin_before_numpy()  # small matrices, parallel processes: BLAS threads only cost time (and ~20 ms to limit)
    keep_freed_memory()  # the solvers' matrices reuse freed memory instead of fresh pages (etcheck.runtime.heap)
    argv = list(sys.argv[1:] if argv is None else argv)
    names = {m.NAME for m in COMMANDS}
    if argv and argv[0] not in names and not argv[0].startswith("-"):
        argv = ["check", *argv]  # the shorthand the README uses
    p = parser()
    args = p.parse_args(argv)
    if args.command is None:
        p.print_help()
        return 2
    with stop_on_signals(), memory_budget(args):  # stop signals: helpers stopped, nothing half-written, 128 + signal
        return args.run(args, args.parser)


@contextlib.contextmanager
def memory_budget(args: argparse.Namespace):
    """The budget of --memory-budget (else the environment's) checked, and set in the environment for the
    command's helpers and workers while it runs; a usage error (exit 2) naming the option or the variable."""
    given = args.memory_budget
    text = given if given is not None else os.environ.get(memory.VARIABLE)
    if text:
        try:
            memory.parse(text)
        except ValueError as exc:
            args.parser.error(f"{'--memory-budget' if given is not None else memory.VARIABLE}: {exc}")
    before = os.environ.get(memory.VARIABLE)
    if given is not None:
        os.environ[memory.VARIABLE] = given
    try:
        yield
    finally:
        if given is not None:
            if before is None:
                os.environ.pop(memory.VARIABLE, None)
            else:
                os.environ[memory.VARIABLE] = before


def run() -> None:
    """The ``etcheck`` command (and ``python -m etcheck``): :func:`main`, then the process ends at once.

    Everything is written by then (reports atomically and synced, the report process and any helpers joined);
    what is left is the interpreter's teardown of ~640 modules and their objects, ~0.1 s of a cold
    ``--format json`` run. Output is flushed first; a
    reader that went away (a closed pipe) ends it with 141, as the shell reports a command stopped by SIGPIPE.
    """
    try:
        code = main()
    except SystemExit as exc:  # argparse: a usage error (2), --help or --version (0)
        if not isinstance(exc.code, int | None):
            raise
        code = exc.code or 0
    except BrokenPipeError:  # the reader went away (`etcheck ... | head`): the shell's code for SIGPIPE, no traceback
        code = 128 + 13
    except KeyboardInterrupt as exc:  # stopped outside a command's own guard (its summary, the parser)
        code = stopped(exc, "stopped")
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed pipe: nothing more to say
            stream.flush()
    os._exit(code)
