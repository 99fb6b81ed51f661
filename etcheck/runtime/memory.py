"""The memory budget of one process: every route states what its largest matrices need before it builds them.

A check, a sweep's worker or a forked helper never holds more than the budget
(default :data:`DEFAULT`, 1 GB per process; ``--memory-budget`` on the
command line, or the environment variable ``ETCHECK_MEMORY_BUDGET``, e.g.
``"512 MB"``, ``"2 GB"``, ``"1.5 GiB"``). Before a route builds its largest
matrices it calls :func:`require` with their size; what is held for reuse
(the operators memoised by :class:`Memo`) is released first where that makes
room. When it still does not fit, :class:`OverBudget` says what would need
how much ("not answered: ... would need 2.3 GB of memory, past the budget
of 1 GB"): a route with a resolution ladder stops at the largest rung that
fits (:func:`fits`) and reports its error estimate there, a damped critical
value falls back to the exact determinant (no large matrix), and the command
ends with exit code 1 and that reason where no route fits. Nothing is
allowed to grow into swap.

The accounting is deterministic (it does not depend on what else runs): the
stated size of the route, plus what the memos hold, plus :data:`BASELINE`
for the interpreter, numpy, scipy and astropy (a check's process holds
75-190 MB besides its solves). The stated sizes are upper bounds measured
with tracemalloc (tests/numerics/test_memory.py).
"""

from __future__ import annotations

import os
import re
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any

from etcheck.errors import EtcheckError

__all__ = ["VARIABLE", "DEFAULT", "BASELINE", "OverBudget", "parse", "budget", "describe", "matrix_bytes", "fits",
           "require", "Memo", "held", "release", "WORKSPACE",
           "items_within"]

#: the environment variable that sets the budget (the CLI's --memory-budget sets it for its helpers too)
VARIABLE = "ETCHECK_MEMORY_BUDGET"
#: the budget when none is set: one process of a 2-core, 8 GB laptop with the report process beside it
DEFAULT = "1 GB"
#: bytes of a process before its solves: the interpreter, numpy, scipy and astropy, the results (measured
#: 75-190 MB for a check, draft to sign-off)
BASELINE = 200e6
#: the share of the budget that memoised operators may hold (the most recent one is always kept)
MEMO_SHARE = 0.25
#: bytes a route needs besides its large matrices (vectors, ARPACK's and LAPACK's small work arrays, memoised grids),
#: added to each stated size
WORKSPACE = 4e6

_UNITS = {"": 1, "b": 1, "kb": 1e3, "mb": 1e6, "gb": 1e9, "tb": 1e12, "kib": 2**10, "mib": 2**20, "gib": 2**30,
          "tib": 2**40}
_MEMOS: list[Memo] = []


class OverBudget(EtcheckError):
    """A route would need more memory than the budget allows: not answered (exit code 1, with the reason)."""

    exit_code = 1

    def __init__(self, what: str, need: float, limit: float) -> None:
        self.what, self.need, self.limit = what, float(need), float(limit)
        super().__init__(f"not answered: {what} would need {describe(need)} of memory, past the budget of "
                         f"{describe(limit)} per process (raise it with --memory-budget or {VARIABLE})")


def parse(text: str | float) -> int:
    """Bytes of a budget written as ``"1 GB"``, ``"512 MB"``, ``"1.5 GiB"`` or a number of bytes; ValueError with
    the expected form otherwise (decimal units are powers of 1000, binary ones of 1024)."""
    match = re.fullmatch(r"\s*([0-9.]+(?:[eE][-+]?[0-9]+)?)\s*([A-Za-z]*)\s*", str(text))
    unit = match.group(2).lower() if match else ""
    if not match or unit not in _UNITS:
        raise ValueError(f"cannot read {text!r} as a memory size; expected e.g. \"1 GB\", \"512 MB\" or \"2 GiB\"")
    value = float(match.group(1)) * _UNITS[unit]
    if not value >= BASELINE:
        raise ValueError(f"{text!r} is below the {describe(BASELINE)} a process holds before any solve")
    return int(value)


def budget() -> int:
    """This process's budget in bytes (:data:`VARIABLE`, else :data:`DEFAULT`)."""
    return parse(os.environ.get(VARIABLE) or DEFAULT)


def describe(nbytes: float) -> str:
    """``"2.3 GB"``, ``"480 MB"``: a size for a reader (decimal units)."""
    return f"{nbytes / 1e9:.2g} GB" if nbytes >= 1e9 else f"{nbytes / 1e6:.3g} MB"


def matrix_bytes(rows: int, cols: int | None = None, count: float = 1.0, complex_: bool = False) -> float:
    """Bytes of ``count`` dense float64 (``complex_``: complex128) matrices of rows x cols (square by default)."""
    return float(count) * rows * (rows if cols is None else cols) * (16 if complex_ else 8)


def items_within(per_item: float, share: float) -> int:
    """How many items of ``per_item`` bytes fit ``share`` of what the budget leaves besides the baseline (at
    least one): the block size of a vectorised evaluation whose values do not depend on its blocks (beyond the
    last bits of numpy's vectorised functions)."""
    return max(1, int(share * (budget() - BASELINE) / per_item))


def held() -> float:
    """Bytes held by the memos (their entries' stated sizes)."""
    return sum(m.nbytes for m in _MEMOS)


def release() -> None:
    """Empty every memo (their entries are rebuilt when asked for again)."""
    for m in _MEMOS:
        m.clear()


def fits(nbytes: float) -> bool:
    """Whether a route that needs ``nbytes`` fits the budget beside the baseline, once the memos are released."""
    return BASELINE + nbytes <= budget()


def require(what: str, nbytes: float) -> None:
    """State that ``what`` is about to need ``nbytes``: the memos are released if that makes room; OverBudget
    (exit 1, with the reason) where it does not fit even then."""
    limit = budget()
    if BASELINE + held() + nbytes <= limit:
        return
    release()
    if BASELINE + nbytes > limit:
        raise OverBudget(what, BASELINE + nbytes, limit)


class Memo:
    """A memo of large objects, bounded by their stated sizes: ``Memo(build, size)`` is called like ``build``
    (positional, hashable arguments) and keeps the results most recently asked for, while together they state at
    most :data:`MEMO_SHARE` of the budget (the last one is always kept); ``size(*args)``: the bytes an entry
    holds, stated before it is built (the build itself calls :func:`require`)."""

    def __init__(self, build: Callable[..., Any], size: Callable[..., float]) -> None:
        self._build, self._size = build, size
        self._entries: OrderedDict[Hashable, tuple[Any, float]] = OrderedDict()
        _MEMOS.append(self)

    @property
    def nbytes(self) -> float:
        return sum(size for _, size in self._entries.values())

    def __call__(self, *args: Hashable) -> Any:
        if args in self._entries:
            self._entries.move_to_end(args)
            return self._entries[args][0]
        value = self._build(*args)
        self._entries[args] = (value, float(self._size(*args)))
        share = MEMO_SHARE * budget()
        while len(self._entries) > 1 and self.nbytes > share:
            self._entries.popitem(last=False)
        return value

    def clear(self) -> None:
        self._entries.clear()

    def __len__(self) -> int:
        return len(self._entries)
