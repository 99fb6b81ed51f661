"""What every subcommand shares: output options, the error guard, exit codes."""

from __future__ import annotations

import argparse
import signal
import sys
from collections.abc import Callable
from typing import Any

from etcheck.errors import EtcheckError
from etcheck.runtime.lifetime import requested, stop_words

EXIT_TEXT = """exit codes:
  0  the run finished and every margin meets the required margin
  1  a margin fails, the check is incomplete, the scene is outside the model's validity, or some sweep points
     have no answer (never a silent pass); or a solve would exceed the memory budget (--memory-budget): not
     answered, with the reason
  2  bad input or usage (mission file, options, report cannot be written): the message names the field
  3  a numerical solve failed (nothing is reported from it)
  130 interrupted by Ctrl-C (SIGINT), 143 stopped by SIGTERM, 129 by SIGHUP: helpers stopped, no report
      half-written (a sweep resumes when the same command is run again)
"""


def add_output_options(p: argparse.ArgumentParser, formats: tuple[str, ...], where: str) -> None:
    """``--out`` and ``--format`` (checked by :func:`formats`)."""
    p.add_argument("--out", default="reports", help=f"output folder (default: reports/); files go to {where}")
    p.add_argument("--format", default=",".join(formats),
                   help=f"comma-separated list of {', '.join(formats)} (default: all)")
    p.set_defaults(known_formats=formats)


def formats(args: argparse.Namespace, parser: argparse.ArgumentParser) -> tuple[str, ...]:
    """The requested formats, or a usage error (exit 2) naming the bad one."""
    items = tuple(x.strip().lower() for x in args.format.split(",") if x.strip())
    bad = [x for x in items if x not in args.known_formats]
    if bad or not items:
        parser.error(f"--format: unknown format {', '.join(bad) or '(empty)'}; "
                     f"use any of {', '.join(args.known_formats)}")
    return items


def guarded(action: Callable[[], Any], interrupted: str):
    """Run ``action()``; user errors, Ctrl-C and bugs become a message and an exit code (no traceback).

    Returns the action's value, or the exit code (an int) when it failed.
    """
    try:
        return action()
    except KeyboardInterrupt as exc:
        return stopped(exc, interrupted)
    except Exception as exc:
        stop = requested()  # a stop signal whose exception another one hid (e.g. a pool whose workers it stopped)
        if stop is not None and not (isinstance(exc, EtcheckError) and exc.exit_code >= 128):
            return stopped(stop, interrupted)
        if isinstance(exc, EtcheckError):
            print(f"etcheck: {'error: ' if exc.exit_code in (2, 3) else ''}{exc}", file=sys.stderr)  # 1, 128+: none
            return exc.exit_code
        # a bug, not the user's fault: say so, no traceback
        print(f"etcheck: internal error ({type(exc).__name__}: {exc}); {interrupted}. "
              "Please report this with the mission file.", file=sys.stderr)
        return 3


def stopped(exc: KeyboardInterrupt, interrupted: str) -> int:
    """Say that the run was stopped (Ctrl-C or a stop signal, :mod:`etcheck.runtime.lifetime`); the shell's exit
    code for that signal, 128 + its number."""
    print(f"etcheck: {stop_words(exc)}; {interrupted}", file=sys.stderr)
    return 128 + getattr(exc, "signum", signal.SIGINT)


def run_and_summarise(action: Callable[[], tuple], summary: Callable[..., int | None],
                      interrupted: str = "nothing written") -> int:
    """``guarded(action)``, then ``summary(*result)``; its exit code (0 if it returns None), or the error's."""
    out = guarded(action, interrupted)
    if isinstance(out, int):
        return out
    code = summary(*out)
    return 0 if code is None else code
