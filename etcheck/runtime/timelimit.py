"""Work that may be cut off at a deadline: the parts of an answer that only illustrate it.

A sign-off check answers its margins whatever they cost, and then computes
what the report shows besides them (the operating spectrum, the Campbell
diagram, the stability map, the accuracy table). Those extras have a time
budget: :func:`within` runs one of them until a deadline and raises
:class:`OutOfTime` when it passes, so that the caller can say which part was
skipped and why instead of taking minutes over a tether that fails by orders
of magnitude. The deadline is an alarm (SIGALRM, the main thread on POSIX):
it is acted on between two numerical steps, so a ladder of resolutions also
asks :func:`predicted_past` before a step that would overrun it (its cost
predicted from the last one's). Forked helpers of the part are stopped with
it (:mod:`etcheck.runtime.parallel` kills its helper on any exception).
Elsewhere (another thread, no SIGALRM) the part runs to its end.
"""

from __future__ import annotations

import signal
import threading
import time
from collections.abc import Callable
from typing import Any

__all__ = ["OutOfTime", "within", "remaining", "predicted_past"]


class OutOfTime(BaseException):
    """The deadline of :func:`within` passed (a BaseException: no ``except Exception`` of the part swallows it)."""


def remaining(deadline: float | None) -> float:
    """Seconds left before ``deadline`` (a ``time.perf_counter()`` value; None: no deadline, inf)."""
    return float("inf") if deadline is None else deadline - time.perf_counter()


def predicted_past(deadline: float | None, seconds: float) -> bool:
    """Whether work predicted to take ``seconds`` would end past ``deadline``."""
    return deadline is not None and seconds > remaining(deadline)


def _alarm(signum, frame) -> None:
    raise OutOfTime


def within(deadline: float | None, fn: Callable[[], Any]) -> Any:
    """``fn()``, or OutOfTime when ``deadline`` (a ``time.perf_counter()`` value) passes first or has passed."""
    if deadline is None or not hasattr(signal, "setitimer") or threading.current_thread() is not threading.main_thread():
        return fn()
    left = remaining(deadline)
    if left <= 0:
        raise OutOfTime
    before = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, left)
    try:
        return fn()
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, before)
