"""The two-core map: same results in the same order as a serial map, whoever computed them."""

import os

import pytest

from etcheck.numerics import parallel
from etcheck.numerics.parallel import can_split, split_map

forks = pytest.mark.skipif(not can_split(), reason="needs fork, two cores and a single thread")


def _square_and_pid(x):
    return x * x, os.getpid()


@pytest.mark.parametrize("n", [0, 1, 2, 5, 8])
def test_same_results_in_the_same_order_as_a_serial_map(n):
    out = split_map(_square_and_pid, range(n))
    assert [v for v, _ in out] == [x * x for x in range(n)]


@forks
def test_every_second_item_is_computed_by_a_helper():
    out = split_map(_square_and_pid, range(7))
    pids = [pid for _, pid in out]
    assert set(pids[0::2]) == {os.getpid()}
    assert len(set(pids[1::2])) == 1 and pids[1] != os.getpid()


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
    parent, x = job
    if os.getpid() == parent and x == 2:
        raise ValueError("bad item")
    return x


def test_an_error_here_is_raised_and_leaves_no_helper_behind():
    with pytest.raises(ValueError, match="bad item"):
        split_map(_fails_here, [(os.getpid(), x) for x in range(6)])
    with pytest.raises(ChildProcessError):
        os.waitpid(-1, os.WNOHANG)  # no child left to reap


def _may_split(_):
    return can_split()


@forks
def test_a_helper_never_forks_again():
    assert split_map(_may_split, range(4)) == [True, False, True, False]


def test_serial_here_turns_forking_off(monkeypatch):
    monkeypatch.setattr(parallel, "_SERIAL", False)
    parallel.serial_here()
    assert not can_split()
    assert {pid for _, pid in split_map(_square_and_pid, range(6))} == {os.getpid()}


@forks
def test_weights_balance_the_two_sides():
    """The heaviest item alone on one side, the rest on the other; results in input order."""
    out = split_map(_square_and_pid, range(5), weights=[10.0, 1.0, 2.0, 3.0, 1.0])
    assert [v for v, _ in out] == [0, 1, 4, 9, 16]
    pids = [pid for _, pid in out]
    assert pids[0] == os.getpid() and len(set(pids[1:])) == 1 and pids[1] != os.getpid()


def test_serial_turns_forking_off_inside_its_block_only(monkeypatch):
    monkeypatch.setattr(parallel, "_SERIAL", False)
    with parallel.serial():
        assert not can_split()
        assert {pid for _, pid in split_map(_square_and_pid, range(6))} == {os.getpid()}
    assert parallel._SERIAL is False
