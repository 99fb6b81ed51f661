"""A stopped or killed etcheck leaves no process behind and no half-written file.

The command runs in its own session (its process group is its pid, and every helper it forks stays in that group,
even once orphaned), is stopped with SIGKILL or SIGTERM while its helpers compute, and the process table (/proc) is
read afterwards: no process of the group may still run (a zombie has ended).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SET = ROOT / "missions" / "set.toml"

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux") or len(os.sched_getaffinity(0)) < 2,
                                reason="forked helpers and /proc: Linux with two or more cores")

#: a damping map: a report process from the start, then forked helpers, each busy for seconds
DAMPING_MAP = ("damping-map", str(SET), "--points", "3x3", "--gammas", "0.01", "--format", "html,json")
#: a sweep: its local workers, busy for a few seconds
SWEEP = ("sweep", str(SET), "--length", "100 m:300 m:30", "--spin", "0 rpm:0.3 rpm:20", "--no-cache",
         "--format", "json")


def _group(pgid: int) -> list[int]:
    """The running (not zombie) processes of process group ``pgid``."""
    out = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as fh:
                fields = fh.read().rsplit(b")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] not in (b"Z", b"X"):
            out.append(int(entry))
    return out


def _start(args: tuple[str, ...], tmp_path: Path) -> tuple[subprocess.Popen, Path]:
    out = tmp_path / "out"
    err = (tmp_path / "stderr").open("w")
    proc = subprocess.Popen([sys.executable, "-m", "etcheck", *args, "--out", str(out)], stdout=subprocess.DEVNULL,
                            stderr=err, start_new_session=True, cwd=tmp_path)
    return proc, out


def _wait_for_helpers(proc: subprocess.Popen, n: int) -> None:
    """Until the command has ``n`` helpers running (fails if it ends first)."""
    deadline = time.monotonic() + 120
    while len([p for p in _group(proc.pid) if p != proc.pid]) < n:
        assert proc.poll() is None, "the command ended before its helpers started"
        assert time.monotonic() < deadline, "no helpers started"
        time.sleep(0.02)


def _left(pgid: int, within: float) -> list[int]:
    """The group's processes still running ``within`` seconds from now (killed then, so that none is left)."""
    deadline = time.monotonic() + within
    while (left := _group(pgid)) and time.monotonic() < deadline:
        time.sleep(0.02)
    for pid in left:
        os.kill(pid, signal.SIGKILL)
    return left


@pytest.mark.parametrize(("args", "helpers"), [(DAMPING_MAP, 2), (SWEEP, 2)], ids=["damping-map", "sweep"])
def test_killed_leaves_no_helper_running(args, helpers, tmp_path):
    proc, _ = _start(args, tmp_path)
    try:
        _wait_for_helpers(proc, helpers)
        proc.kill()
        proc.wait()
    finally:
        left = _left(proc.pid, within=1.0)
    assert not left, f"{len(left)} helper(s) still running after the parent was killed"


@pytest.mark.parametrize(("args", "helpers"), [(DAMPING_MAP, 2), (SWEEP, 2)], ids=["damping-map", "sweep"])
def test_terminated_stops_its_helpers_and_writes_nothing(args, helpers, tmp_path):
    proc, out = _start(args, tmp_path)
    try:
        _wait_for_helpers(proc, helpers)
        proc.terminate()
        code = proc.wait(timeout=10)
    finally:
        left = _left(proc.pid, within=1.0)
    err = (tmp_path / "stderr").read_text()
    assert not left, f"{len(left)} helper(s) still running after SIGTERM"
    assert code == 128 + signal.SIGTERM, err
    assert "stopped by SIGTERM" in err and "Traceback" not in err, err
    assert not out.exists() or not [p for p in out.rglob("*") if p.is_file()]  # nothing written, no temporary file
