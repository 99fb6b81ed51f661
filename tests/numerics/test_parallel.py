"""The two-core map: same results in the same order as a serial map, whoever computed them."""

import os
import time

import pytest

from etcheck.runtime import parallel
from etcheck.runtime.parallel import can_split, split_map


def _forkable() -> bool:
    """can_split() with forking allowed (the suite's xdist workers turn it off: tests/conftest.py)."""
    with parallel.serial(False):
        return can_split()


forks = pytest.mark.skipif(not _forkable(), reason="needs fork, two cores and a single thread")


@pytest.fixture(autouse=True)
def forking_allowed():
    """These tests are about the forks: allowed here whatever the test process says."""
    with parallel.serial(False):
        yield


def _square_and_pid(x):
    return x * x, os.getpid()


@pytest.mark.parametrize("n", [0, 1, 2, 5, 8])
def test_same_results_in_the_same_order_as_a_serial_map(n):
    out = split_map(_square_and_pid, range(n))
    assert [v for v, _ in out] == [x * x for x in range(n)]


def _sleep_and_pid(seconds):
    time.sleep(seconds)
    return os.getpid()


@forks
def test_the_first_item_is_computed_here_and_the_second_by_a_helper():
    pids = split_map(_sleep_and_pid, [0.5, 0.0])
    assert pids[0] == os.getpid() != pids[1]


@forks
def test_a_free_side_takes_the_next_item():
    """One long item here: the helper takes every short one meanwhile (a static split would leave half of them
    waiting here)."""
    pids = split_map(_sleep_and_pid, [0.8] + [0.02] * 6)
    assert pids[0] == os.getpid()
    assert os.getpid() not in pids[1:] and len(set(pids[1:])) == 1


@forks
def test_fewer_items_than_asked_for_run_here():
    out = split_map(_square_and_pid, range(5), min_items=6)
    assert {pid for _, pid in out} == {os.getpid()}


def _fails_in_the_helper(job):
    parent, x = job
    if os.getpid() != parent:
        raise RuntimeError("helper fails")
    return x + 1


@forks
def test_a_failed_helper_leaves_its_items_to_this_process():
    me = os.getpid()
    assert split_map(_fails_in_the_helper, [(me, x) for x in range(6)]) == [x + 1 for x in range(6)]


def _fails_here(job):
    """Fails on the first item: the one this process always computes (taken before the helper starts), so that
    the error is raised here whichever items the helper takes meanwhile."""
    parent, x = job
    if os.getpid() == parent and x == 0:
        time.sleep(0.2)  # the helper is running by now
        raise ValueError("bad item")
    return x


def _children() -> set[int]:
    """This process's child processes (Linux /proc; other tests may have left their own)."""
    tasks = f"/proc/{os.getpid()}/task"
    return {int(c) for t in os.listdir(tasks) for c in open(f"{tasks}/{t}/children").read().split()}


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="children listed by /proc (Linux)")
def test_an_error_here_is_raised_and_leaves_no_helper_behind():
    before = _children()
    with pytest.raises(ValueError, match="bad item"):
        split_map(_fails_here, [(os.getpid(), x) for x in range(6)])
    assert _children() <= before  # the helper was killed and reaped


def _may_split(_):
    return can_split()


@forks
def test_neither_side_forks_again_while_both_run():
    assert split_map(_may_split, range(4)) == [False] * 4
    assert can_split()


def test_serial_here_turns_forking_off():
    parallel.serial_here()  # until the fixture's block ends
    assert not can_split()
    assert {pid for _, pid in split_map(_square_and_pid, range(6))} == {os.getpid()}


@forks
def test_weights_order_the_queue_heaviest_first():
    """The heaviest item (here the last) is taken first, here; the helper takes the rest meanwhile."""
    pids = split_map(_sleep_and_pid, [0.02, 0.02, 0.02, 0.02, 0.8], weights=[1.0, 1.0, 1.0, 1.0, 10.0])
    assert pids[4] == os.getpid()
    assert os.getpid() not in pids[:4] and len(set(pids[:4])) == 1


@forks
def test_more_items_than_the_queue_has_entries():
    """Items travel in blocks when there are more than the queue's entries (the pipe must not fill up)."""
    n = 3 * parallel.QUEUE_BLOCKS + 7
    assert split_map(abs, [-x for x in range(n)]) == list(range(n))


@forks
def test_serial_turns_forking_off_inside_its_block_only():
    with parallel.serial():
        assert not can_split()
        assert {pid for _, pid in split_map(_square_and_pid, range(6))} == {os.getpid()}
        with parallel.serial(False):  # and on again inside an inner block
            assert can_split()
        assert not can_split()
    assert can_split()


def test_no_process_to_spare_means_one_by_one(monkeypatch):
    monkeypatch.setattr(parallel, "can_split", lambda: True)

    def no_fork():
        raise OSError("resource temporarily unavailable")

    monkeypatch.setattr(os, "fork", no_fork)
    out = split_map(_square_and_pid, range(5))
    assert out == [(x * x, os.getpid()) for x in range(5)]


# --- ahead: one independent piece of work in a helper while this process goes on --------------------------


@forks
def test_ahead_computes_in_a_helper_while_this_process_goes_on():
    t0 = time.perf_counter()
    with parallel.ahead(lambda: _sleep_and_pid(0.5)) as later:
        here = _sleep_and_pid(0.5)
        there = later()
    assert here == os.getpid() != there
    assert time.perf_counter() - t0 < 0.9  # side by side, not one after the other
    assert later() == there  # asked again: the same result, no second run


def test_ahead_without_a_helper_computes_here_when_asked():
    parallel.serial_here()  # until the fixture's block ends
    calls = []
    with parallel.ahead(lambda: calls.append(os.getpid()) or 7) as later:
        assert calls == []  # nothing yet
        assert later() == 7
    assert calls == [os.getpid()]


def _fails_in_a_helper(parent):
    if os.getpid() != parent:
        raise RuntimeError("helper fails")
    return "here"


@forks
def test_ahead_whose_helper_failed_computes_here():
    me = os.getpid()
    with parallel.ahead(lambda: _fails_in_a_helper(me)) as later:
        assert later() == "here"


@forks
@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="children listed by /proc (Linux)")
def test_ahead_not_asked_leaves_no_helper_behind():
    before = _children()
    with pytest.raises(ValueError, match="error here"), parallel.ahead(lambda: _sleep_and_pid(30)):
        raise ValueError("error here")
    assert _children() <= before  # killed and reaped
