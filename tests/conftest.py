"""Shared test set-up: the independent references (tests/independent.py) and mission
builders (tests/helpers.py) are importable from every test folder."""

import compileall
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))


def pytest_configure(config):
    """Compile etcheck's bytecode once, before the workers start: the CLI and report tests start fresh
    interpreters, and where PYTHONDONTWRITEBYTECODE is set (as on CI) each would compile ~0.25 s of source."""
    if not hasattr(config, "workerinput"):  # the xdist controller, or a run without xdist
        compileall.compile_dir(Path(__file__).resolve().parents[1] / "etcheck", quiet=1)


def pytest_sessionstart(session):
    """Every test process reuses freed matrices as the CLI's does (etcheck.runtime.heap): the same numbers, sooner.

    The xdist workers are a pool that keeps every core busy: like a sweep's workers they fork no helpers
    (etcheck.runtime.parallel.serial_here; the results are the same bytes either way). A helper forked from a
    worker of several hundred MB only oversubscribed the cores and copied pages: the suite took 176 s with
    them, 155 s without (measured back to back, fresh clone). The helpers are tested where they are the subject:
    tests/numerics/test_parallel.py and the comparisons that switch them on (the fixture ``forks_allowed``, or
    ``with parallel.serial(False)``)."""
    from etcheck.runtime.heap import keep_freed_memory

    keep_freed_memory()
    if hasattr(session.config, "workerinput"):
        from etcheck.runtime.parallel import serial_here

        serial_here()


@pytest.fixture
def forks_allowed():
    """Forked helpers allowed in this test whatever the test process says (the suite's workers fork none)."""
    from etcheck.runtime.parallel import serial

    with serial(False):
        yield
