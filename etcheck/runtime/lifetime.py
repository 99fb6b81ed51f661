"""Helper processes that cannot outlive the process that started them, and a stop signal that stops them too.

etcheck runs work in processes of its own: a forked helper beside a check
(:mod:`etcheck.runtime.parallel`), the report process
(:mod:`etcheck.report.background`) and its figure helper, a sweep's local
workers. Each calls :func:`die_with_parent` first thing: on Linux the
kernel then sends it SIGKILL when its parent ends, however the parent ends
(SIGKILL from a CI runner or the out-of-memory killer included), so that no
helper keeps computing, or holding its memory, without anyone to read its
result. Where the parent ended before the request was made (the race between
the fork and the request) the helper leaves at once. Elsewhere than Linux a
thread of the helper watches its parent instead (twice a second).

:func:`stop_on_signals` (the ``etcheck`` command, for its own process)
turns SIGTERM, SIGHUP and SIGINT into :class:`Stopped` (a KeyboardInterrupt,
so every clean-up path written for Ctrl-C runs): the helpers are stopped at
once (SIGKILL to this process's children), the block being computed is
left, reports not yet renamed into place are removed (they are written to a
temporary file and renamed: a report is either the old one, the new one or
absent), and the command ends with the shell's code for the signal,
128 + its number. A signal is acted on between two numerical steps, never
inside one (a LAPACK call is not interrupted); SIGKILL is immediate and the
helpers follow through :func:`die_with_parent`.
"""

from __future__ import annotations

import contextlib
import ctypes
import functools
import os
import signal
import sys
import threading
import time

__all__ = ["Stopped", "die_with_parent", "stop_on_signals", "stop_children", "children", "kill_and_reap", "stop_words",
           "requested"]

#: prctl option: the signal the kernel sends this process when its parent thread ends (linux/prctl.h)
_PR_SET_PDEATHSIG = 1
#: the signals :func:`stop_on_signals` turns into :class:`Stopped`
STOP_SIGNALS = (signal.SIGTERM, signal.SIGINT) + ((signal.SIGHUP,) if hasattr(signal, "SIGHUP") else ())


class Stopped(KeyboardInterrupt):
    """The process was asked to stop by a signal (``Stopped(signum)``); a KeyboardInterrupt for the clean-up
    paths."""

    @property
    def signum(self) -> int:
        return int(self.args[0])

    def __str__(self) -> str:
        return signal.Signals(self.signum).name


def stop_words(exc: KeyboardInterrupt) -> str:
    """"interrupted" (Ctrl-C) or "stopped by SIGTERM" (or the signal's name)."""
    signum = getattr(exc, "signum", signal.SIGINT)
    return "interrupted" if signum == signal.SIGINT else f"stopped by {signal.Signals(signum).name}"


def die_with_parent(parent: int) -> None:
    """In a newly started helper (``parent``: the pid of the process that started it, read before the fork):
    be killed when the parent ends; leave at once (exit status 1) where it has ended already."""
    if not _death_signal():
        threading.Thread(target=_watch, args=(parent,), daemon=True, name="etcheck-parent-watch").start()
    if os.getppid() != parent:  # the parent ended before the request: nobody would kill this process
        os._exit(1)


def _death_signal() -> bool:
    """Ask the kernel for SIGKILL at the parent's end (Linux prctl); False where that is not available."""
    prctl = _prctl()
    return prctl is not None and prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0


@functools.cache
def _prctl():
    """libc's prctl (Linux), or None; found once, in the parent before its first fork where it is asked there."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        prctl = ctypes.CDLL(None).prctl  # the symbols already loaded (libc's among them): no library search
    except (OSError, AttributeError):
        return None
    prctl.argtypes = (ctypes.c_int, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong)
    prctl.restype = ctypes.c_int
    return prctl


def _watch(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(0.5)
    os._exit(1)


def children() -> list[int]:
    """The pids of this process's living children (Linux: from /proc; elsewhere none are found)."""
    me, out = os.getpid(), []
    with contextlib.suppress(OSError):
        for entry in os.scandir("/proc"):
            if not entry.name.isdigit():
                continue
            try:
                with open(f"/proc/{entry.name}/stat", "rb") as fh:
                    fields = fh.read().rsplit(b")", 1)[1].split()
            except OSError:  # it ended meanwhile
                continue
            if int(fields[1]) == me and fields[0] != b"Z":
                out.append(int(entry.name))
    return out


def stop_children() -> None:
    """SIGKILL to every living child of this process (they are reaped by whoever waits for them)."""
    for pid in children():
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)


def kill_and_reap(pid: int) -> None:
    """SIGKILL to a child of this process and wait for its end (it may have ended, or been reaped, already)."""
    with contextlib.suppress(ProcessLookupError, ChildProcessError):
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)


#: the stop signals received within :func:`stop_on_signals` (emptied when it ends)
_REQUESTED: list[int] = []


def requested() -> Stopped | None:
    """The stop a signal asked for within :func:`stop_on_signals`, if any. Another exception may have hidden it:
    :class:`Stopped` raised where Python only prints it (a fork's at-fork hook) or the error of work whose helper
    was stopped with it (a broken process pool); the caller then reports the stop, not that error."""
    return Stopped(_REQUESTED[0]) if _REQUESTED else None


def _stop(signum: int, frame) -> None:
    _REQUESTED.append(signum)
    stop_children()
    raise Stopped(signum)


def _quiet(hook):
    """``sys.unraisablehook`` that says nothing of a :class:`Stopped` raised where it could not propagate."""

    def unraisable(u) -> None:
        if not isinstance(u.exc_value, Stopped):
            hook(u)

    return unraisable


@contextlib.contextmanager
def stop_on_signals():
    """Within the block SIGTERM, SIGHUP and SIGINT stop this process's helpers and raise :class:`Stopped` (module
    docstring); the previous handlers are restored after it. Main thread only (where Python runs handlers)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _REQUESTED.clear()
    before = {s: signal.signal(s, _stop) for s in STOP_SIGNALS}
    hook, sys.unraisablehook = sys.unraisablehook, _quiet(sys.unraisablehook)
    try:
        yield
    finally:
        for s, handler in before.items():
            signal.signal(s, handler)
        sys.unraisablehook = hook
        _REQUESTED.clear()
