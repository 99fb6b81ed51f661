"""A map over items on two cores: a forked helper takes every second item.

The helper is a copy of this process (``os.fork``, Linux): nothing is imported
again and the function is not pickled; only the results come back, pickled
through a pipe. The map is serial where a fork cannot help or is not safe: one
core, other threads running (a fork copies only the calling thread, and a lock
another thread holds would stay locked in the copy), inside a helper
(:func:`serial_here`) or a sweep's chunk (:func:`serial`: the sweep already
keeps every core busy), or fewer than ``min_items`` items. If the helper fails, its items are computed
here (an error is then raised here, with its traceback). The results are the
same bytes either way: the same code runs on one BLAS thread in both processes.

Only work whose result is all that is needed belongs in the map: what the helper memoises (lru caches,
counters) stays in the helper. Measured: the undamped load line computed in a helper inside a sweep lost the
roots the sweep shares between the points of a length (a 40 x 40 undamped sweep took 300 s instead of 69 s);
a single check computes it in a helper (nothing to share), a sweep's chunks never fork.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import threading
from collections.abc import Callable, Iterator, Sequence
from typing import Any

__all__ = ["split_map", "serial_here", "serial", "can_split"]

_SERIAL = False


def serial_here() -> None:
    """Never fork from this process (a worker of a pool that already uses every core)."""
    global _SERIAL
    _SERIAL = True


@contextlib.contextmanager
def serial() -> Iterator[None]:
    """No forked helpers inside the block (a study that keeps every core busy with its own workers, or that
    shares memoised results between its items)."""
    global _SERIAL
    before = _SERIAL
    _SERIAL = True
    try:
        yield
    finally:
        _SERIAL = before


def can_split() -> bool:
    """Whether :func:`split_map` would fork here now."""
    return (not _SERIAL and hasattr(os, "fork") and hasattr(os, "sched_getaffinity")  # Linux
            and len(os.sched_getaffinity(0)) >= 2 and threading.active_count() == 1)


def split_map(fn: Callable[[Any], Any], items: Sequence, min_items: int = 2,
              weights: Sequence[float] | None = None) -> list:
    """``[fn(x) for x in items]``, part of the items computed by a forked helper when that helps: those at odd
    positions, or, with ``weights`` (the expected cost of each item), a share of about half the total weight
    (heaviest first, each to the lighter side)."""
    items = list(items)
    if len(items) < max(2, min_items) or not can_split():
        return [fn(x) for x in items]
    if weights is None:
        mine_idx, theirs_idx = list(range(0, len(items), 2)), list(range(1, len(items), 2))
    else:
        sides: tuple[list[int], list[int]] = ([], [])
        load = [0.0, 0.0]
        for i in sorted(range(len(items)), key=lambda i: -float(weights[i])):
            side = 0 if load[0] <= load[1] else 1
            sides[side].append(i)
            load[side] += float(weights[i])
        mine_idx, theirs_idx = sorted(sides[0]), sorted(sides[1])
    if not theirs_idx:
        return [fn(x) for x in items]
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the helper: compute its share, send it, leave without any clean-up of the parent's state
        code = 1
        try:
            os.close(read)
            serial_here()
            out = [fn(items[i]) for i in theirs_idx]
            with os.fdopen(write, "wb") as fh:
                pickle.dump(out, fh, protocol=pickle.HIGHEST_PROTOCOL)
            code = 0
        finally:
            os._exit(code)
    os.close(write)
    try:
        mine = [fn(items[i]) for i in mine_idx]
    except BaseException:
        os.close(read)
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        raise
    with os.fdopen(read, "rb") as fh:
        data = fh.read()
    _, status = os.waitpid(pid, 0)
    theirs = pickle.loads(data) if status == 0 and data else [fn(items[i]) for i in theirs_idx]
    out: list = [None] * len(items)
    for i, v in zip(mine_idx, mine):
        out[i] = v
    for i, v in zip(theirs_idx, theirs):
        out[i] = v
    return out
