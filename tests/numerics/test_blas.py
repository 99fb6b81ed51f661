"""When the environment already starts BLAS with one thread (and the solvers need not limit it)."""

from __future__ import annotations

import pytest

from etcheck.runtime.blas import BLAS_THREAD_VARIABLES, pinned_by_environment

ALL = (*BLAS_THREAD_VARIABLES, "OMP_NUM_THREADS")


@pytest.mark.parametrize(("env", "pinned"), [
    ({"OMP_NUM_THREADS": "1"}, True),  # the fallback of every library
    (dict.fromkeys(BLAS_THREAD_VARIABLES, "1"), True),  # every library's own variable
    ({"OPENBLAS_NUM_THREADS": "1"}, False),  # MKL or BLIS would still start threads
    ({"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "4"}, False),  # a library's own variable wins
    ({"OMP_NUM_THREADS": "2"}, False),
    ({}, False),
])
def test_pinned_by_environment(monkeypatch, env, pinned):
    for name in ALL:
        monkeypatch.delenv(name, raising=False)
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    assert pinned_by_environment() is pinned
