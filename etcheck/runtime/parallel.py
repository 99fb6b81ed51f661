"""A map over items on two cores: a forked helper and this process take the items from one queue.

The helper is a copy of this process (``os.fork``, Linux): nothing is imported
again and the function is not pickled; only the results come back, pickled
through a pipe. The map is serial where a fork cannot help or is not safe: one
core, other threads running (a fork copies only the calling thread, and a lock
another thread holds would stay locked in the copy), inside a helper
(:func:`serial_here`) or a sweep's chunk (:func:`serial`: the sweep already
keeps every core busy), or fewer than ``min_items`` items. If the helper fails, its items are computed
here (an error is then raised here, with its traceback). The results are the
same bytes either way: the same code runs on one BLAS thread in both processes. A helper never outlives this
process (:mod:`etcheck.runtime.lifetime`), and is stopped when this process leaves the map by an exception (a
signal included).

Only work whose result is all that is needed belongs in the map: what the helper memoises (lru caches,
counters) stays in the helper. The undamped load line computed in a helper inside a sweep would lose the
roots the sweep shares between the points of a length (a sweep several times slower);
a single check computes it in a helper (nothing to share), a sweep's chunks never fork.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import threading
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from etcheck.runtime.lifetime import die_with_parent, kill_and_reap

__all__ = ["split_map", "ahead", "serial_here", "serial", "can_split", "QUEUE_BLOCKS"]

_SERIAL = False
#: the most entries of 8 bytes the queue of :func:`split_map` writes to its pipe (32 KiB, within Linux's 64 KiB
#: pipe buffer): more items than this travel in blocks
QUEUE_BLOCKS = 4096


def serial_here() -> None:
    """Never fork from this process (a worker of a pool that already uses every core)."""
    global _SERIAL
    _SERIAL = True


@contextlib.contextmanager
def serial(on: bool = True) -> Iterator[None]:
    """No forked helpers inside the block (a study that keeps every core busy with its own workers, or that
    shares memoised results between its items); ``on=False``: helpers allowed inside the block whatever this
    process said before (:func:`serial_here`), where the cores allow them (:func:`can_split`)."""
    global _SERIAL
    before = _SERIAL
    _SERIAL = on
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
    """``[fn(x) for x in items]``, the items shared with a forked helper when that helps.

    Both processes take the next item from one queue as soon as they are free (so a long item on one side does not
    leave the other idle): in the given order, or with ``weights`` (the expected cost of each item) heaviest first.
    This process takes the first item of the queue before the helper starts (so that with two items each side
    computes one, the first here). While the helper runs, the items here run without further forks (two
    processes for two cores).
    """
    items = list(items)
    if len(items) < max(2, min_items) or not can_split():
        return [fn(x) for x in items]
    order = list(range(len(items))) if weights is None else sorted(range(len(items)), key=lambda i: -float(weights[i]))
    queue = _Queue(order)
    first = queue.take()
    read, write = os.pipe()
    parent = os.getpid()
    try:
        pid = os.fork()
    except OSError:  # no process to spare (a resource limit): one by one
        for fd in (read, write):
            os.close(fd)
        queue.close()
        return [fn(x) for x in items]
    if pid == 0:  # the helper: compute what it takes and send it

        def taken() -> dict:
            queue.forget()  # what this process took before the fork is its own
            out = {}
            while (i := queue.take()) is not None:
                out[i] = fn(items[i])
            return out

        _be_the_helper(parent, read, write, taken)
    os.close(write)
    mine = {}
    try:
        with serial():
            i = first
            while i is not None:
                mine[i] = fn(items[i])
                i = queue.take()
        queue.close()
        with os.fdopen(os.dup(read), "rb") as fh:
            data = fh.read()
        _, status = os.waitpid(pid, 0)
        pid = 0
    except BaseException:  # an error here or a stop signal: the helper's work is not needed
        if pid:
            kill_and_reap(pid)
        queue.close()
        raise
    finally:
        os.close(read)
    theirs = pickle.loads(data) if status == 0 and data else {}
    # what the helper took but did not deliver (it failed) is computed here
    return [mine[i] if i in mine else theirs[i] if i in theirs else fn(items[i]) for i in range(len(items))]


@contextlib.contextmanager
def ahead(fn: Callable[[], Any]) -> Iterator[Callable[[], Any]]:
    """Start ``fn()`` in a forked helper now (where :func:`can_split`) and go on here; the block gets a function
    that returns its result, waiting for the helper. Where no helper could start, or it failed, ``fn()`` runs here
    when the result is asked (an error is then raised here). A helper whose result was not asked when the block
    ends is stopped. For independent work that would otherwise wait for this process's next free moment: the
    check's accuracy table beside its spectra."""
    if not can_split():
        yield fn
        return
    read, write = os.pipe()
    parent = os.getpid()
    try:
        pid = os.fork()
    except OSError:  # no process to spare: here, when asked
        for fd in (read, write):
            os.close(fd)
        yield fn
        return
    if pid == 0:
        _be_the_helper(parent, read, write, fn)
    os.close(write)
    got: list = []
    reaped = [False]

    def result() -> Any:
        if not got and not reaped[0]:
            with os.fdopen(os.dup(read), "rb") as fh:
                data = fh.read()
            _, status = os.waitpid(pid, 0)
            reaped[0] = True
            if status == 0 and data:
                got.append(pickle.loads(data))
        if not got:  # the helper failed: here
            got.append(fn())
        return got[0]

    try:
        yield result
    finally:
        if not reaped[0]:  # not asked (an error here or a stop signal): the helper's work is not needed
            kill_and_reap(pid)
        os.close(read)


def _be_the_helper(parent: int, read: int, write: int, compute: Callable[[], Any]) -> None:
    """In a forked helper of ``parent``: compute (without forking again), send the result through the pipe and leave
    without any clean-up of the parent's state; exit status 1 where anything failed (the parent then computes it
    itself). The helper ends with its parent (:func:`etcheck.runtime.lifetime.die_with_parent`)."""
    code = 1
    try:
        die_with_parent(parent)
        os.close(read)
        serial_here()
        out = compute()
        with os.fdopen(write, "wb") as fh:
            pickle.dump(out, fh, protocol=pickle.HIGHEST_PROTOCOL)
        code = 0
    finally:
        os._exit(code)


class _Queue:
    """Item positions in a pipe, written in full before the fork: each process reads the next one (a read of a
    pipe is atomic), end-of-file when all are taken. Positions travel in blocks so that any number fits the
    pipe's buffer."""

    BLOCKS = QUEUE_BLOCKS

    def __init__(self, order: list[int]) -> None:
        size = -(-len(order) // self.BLOCKS)
        self._blocks = [order[k:k + size] for k in range(0, len(order), size)]
        self._read, w = os.pipe()
        os.write(w, b"".join(k.to_bytes(8, "little") for k in range(len(self._blocks))))
        os.close(w)
        self._pending: list[int] = []

    def take(self) -> int | None:
        """The next item position, or None when the queue is empty."""
        if not self._pending:
            raw = os.read(self._read, 8)
            if not raw:
                return None
            self._pending = list(self._blocks[int.from_bytes(raw, "little")])
        return self._pending.pop(0)

    def forget(self) -> None:
        """Drop the positions of a block taken before a fork (in the copy that did not take it)."""
        self._pending = []

    def close(self) -> None:
        """Close the pipe (once; again does nothing)."""
        if self._read >= 0:
            os.close(self._read)
            self._read = -1
