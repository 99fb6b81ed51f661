"""BLAS with one thread: the matrices here are small, and etcheck's parallelism is processes.

Threaded BLAS only adds overhead on matrices of a few hundred rows and
oversubscribes the cores when other work runs (scans several times slower on
busy cores, dense eigen-solves tens of times slower). The CLI starts BLAS
with one thread (:func:`pin_before_numpy`); a library caller keeps its own
settings, and the solvers limit BLAS to one thread while they run
(:func:`one_blas_thread`, threadpoolctl).

No numpy here: the CLI calls this before numpy loads.
"""

from __future__ import annotations

import contextlib
import functools
import os
import sys

from threadpoolctl import ThreadpoolController

__all__ = ["BLAS_THREAD_VARIABLES", "pinned_by_environment", "pin_before_numpy", "one_blas_thread",
           "single_blas_thread"]

#: the variables that set the threads of the BLAS libraries threadpoolctl knows; OMP_NUM_THREADS is each one's fallback
BLAS_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")


def pinned_by_environment() -> bool:
    """Whether the environment starts every BLAS library with one thread (each one's variable, or OMP_NUM_THREADS
    where that is unset, is 1): the CLI sets this before numpy loads, :func:`pin_before_numpy`. Read at the first
    solve; the libraries read it when they load, so a program that sets these variables after loading numpy has
    BLAS threads that the solvers then leave running (slower, never wrong)."""
    own = [os.environ.get(v) for v in BLAS_THREAD_VARIABLES]
    return all(v == "1" for v in own) or (os.environ.get("OMP_NUM_THREADS") == "1" and all(v in (None, "1") for v in own))


@functools.cache
def _blas() -> ThreadpoolController | None:
    """The process's BLAS libraries, found once (scanning them costs ~20 ms with scipy and astropy loaded;
    switching them, microseconds); None when the environment already pins them to one thread."""
    return None if pinned_by_environment() else ThreadpoolController()


def one_blas_thread():
    """Context manager: BLAS limited to one thread inside it."""
    blas = _blas()
    return contextlib.nullcontext() if blas is None else blas.limit(limits=1, user_api="blas")


def single_blas_thread(fn):
    """Decorator: run fn with BLAS limited to one thread.

    The matrices here are small (hundreds); threaded BLAS only adds overhead
    and oversubscribes the cores when other work runs (module docstring).
    """

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with one_blas_thread():
            return fn(*args, **kwargs)

    return wrapper


def pin_before_numpy() -> None:
    """Start every BLAS library with one thread (unless this process has set its threads already): sets the
    variables of :data:`BLAS_THREAD_VARIABLES` and OMP_NUM_THREADS that are unset; too late, and nothing is done,
    once numpy has loaded."""
    if "numpy" in sys.modules:
        return
    for name in (*BLAS_THREAD_VARIABLES, "OMP_NUM_THREADS"):
        os.environ.setdefault(name, "1")
