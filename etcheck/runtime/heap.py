"""Freed matrices kept for the next ones: glibc's malloc tuned for the solvers' allocation pattern.

A solve allocates and frees dense matrices of 1-3 MB many times over (an
operator at N = 48 is 588 x 588 doubles, 2.8 MB; its LU, products and copies
alike). glibc's malloc returns freed memory at the top of its heap to the
system once more than twice its (self-adjusting) mmap threshold is free, and
serves large blocks by mmap; either way the next matrix of that size is
fresh memory, zeroed page by page by the kernel at its first touch
(microseconds per 4 KiB page, a large share of building an operator).

:func:`keep_freed_memory` raises both thresholds (blocks up to 32 MiB come
from the heap, which keeps up to 256 MiB of freed memory). It changes how
fast memory is reused, never what is computed. The CLI calls it for its own
process (and the processes it forks); a program that imports etcheck keeps
its allocator as it is. Elsewhere than glibc (musl, macOS, Windows) it does
nothing.
"""

from __future__ import annotations

import ctypes
import functools
import sys

__all__ = ["keep_freed_memory", "MMAP_THRESHOLD", "TRIM_THRESHOLD"]

#: glibc's mallopt parameters (malloc.h)
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
#: blocks up to this size come from the heap (glibc's largest allowed value on 64-bit systems)
MMAP_THRESHOLD = 32 * 1024 * 1024
#: freed memory at the top of the heap kept for reuse, up to this size
TRIM_THRESHOLD = 256 * 1024 * 1024


@functools.cache
def keep_freed_memory() -> bool:
    """Tune glibc's malloc in this process (module docstring); True where that was done, False where this is
    not glibc or it refused."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        mallopt = ctypes.CDLL("libc.so.6").mallopt  # glibc's name (not looked up: that runs ldconfig)
    except (OSError, AttributeError):  # not glibc (musl has no mallopt)
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    # the mmap threshold first: setting either one ends glibc's own adjustment of both
    return bool(mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))
