"""Helpers end with their parent; a stop signal stops the helpers and raises Stopped."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from etcheck.runtime.lifetime import Stopped, stop_words

linux = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="parent-death signal and /proc (Linux)")


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie has ended: only its exit status is left)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            return fh.read().rsplit(b")", 1)[1].split()[0] not in (b"Z", b"X")
    except OSError:
        return False


def _run(code: str, timeout: float = 30) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=timeout)


@linux
def test_a_helper_is_killed_when_its_parent_is():
    """A middle process starts a helper that would sleep 60 s; the middle one is SIGKILLed; the helper follows."""
    out = _run("""
        import os, sys, time
        from etcheck.runtime.lifetime import die_with_parent
        r, w = os.pipe()
        middle = os.fork()
        if middle == 0:
            parent = os.getpid()
            helper = os.fork()
            if helper == 0:
                die_with_parent(parent)
                time.sleep(60)
                os._exit(0)
            os.write(w, str(helper).encode())
            time.sleep(60)
            os._exit(0)
        helper = int(os.read(r, 64))
        time.sleep(0.1)  # the helper has made its request by now
        os.kill(middle, 9)
        os.waitpid(middle, 0)
        print(helper)
    """)
    helper = int(out.stdout)
    deadline = time.monotonic() + 2.0
    while _alive(helper) and time.monotonic() < deadline:
        time.sleep(0.02)
    alive = _alive(helper)
    if alive:
        os.kill(helper, signal.SIGKILL)
    assert not alive, "the helper outlived its parent"


@linux
def test_a_helper_whose_parent_ended_before_the_request_leaves_at_once():
    out = _run("""
        import os
        from etcheck.runtime.lifetime import die_with_parent
        pid = os.fork()
        if pid == 0:
            die_with_parent(os.getppid() + 1_000_000)  # not its parent: as if the parent had ended already
            os._exit(0)
        print(os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1]))
    """)
    assert out.stdout.strip() == "1", out.stderr


@linux
def test_a_stop_signal_stops_the_children_and_raises_stopped():
    out = _run("""
        import os, signal, subprocess, time
        from etcheck.runtime.lifetime import Stopped, stop_on_signals
        child = subprocess.Popen(["sleep", "60"])
        try:
            with stop_on_signals():
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(5)
        except Stopped as exc:
            print(exc.signum, child.wait(timeout=5))
        print(signal.getsignal(signal.SIGTERM) is signal.SIG_DFL)
    """)
    assert out.stdout.split() == [str(int(signal.SIGTERM)), str(-int(signal.SIGKILL)), "True"], out.stderr


def test_stopped_is_a_keyboard_interrupt_that_names_its_signal():
    import pickle

    exc = Stopped(signal.SIGTERM)
    assert isinstance(exc, KeyboardInterrupt)
    assert exc.signum == 15 and str(exc) == "SIGTERM"
    assert pickle.loads(pickle.dumps(exc)).signum == 15  # it may cross a process pool
    assert stop_words(exc) == "stopped by SIGTERM"
    assert stop_words(KeyboardInterrupt()) == "interrupted"


@linux
def test_a_stop_hidden_by_another_exception_is_still_known():
    """A Stopped raised where Python only prints it (an at-fork hook) is not printed; requested() tells it."""
    out = _run("""
        import os, signal
        from etcheck.runtime.lifetime import requested, stop_on_signals
        with stop_on_signals():
            os.register_at_fork(after_in_parent=lambda: os.kill(os.getpid(), signal.SIGTERM))
            pid = os.fork()
            if pid == 0:
                os._exit(0)
            os.waitpid(pid, 0)
            print(requested().signum)
        print(requested())
    """)
    assert out.stdout.split() == [str(int(signal.SIGTERM)), "None"], out.stderr
    assert out.stderr == ""  # not "Exception ignored in ... Stopped"
