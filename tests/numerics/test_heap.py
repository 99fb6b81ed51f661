"""glibc's malloc keeps the solvers' freed matrices for reuse in the CLI's process (etcheck.runtime.heap)."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

GLIBC = sys.platform.startswith("linux") and "glibc" in " ".join(__import__("platform").libc_ver())

# RSS (pages) after a 24 MiB block was allocated, touched and freed: glibc returns it at once by default (served
# by mmap above its threshold); kept, the heap holds on to it for the next matrix
PROBE = textwrap.dedent("""
    import sys
    if sys.argv[1] == "keep":
        from etcheck.runtime.heap import keep_freed_memory
        assert keep_freed_memory() is True
    def rss():
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[1])
    before = rss()
    block = bytearray(24 * 1024 * 1024)
    for i in range(0, len(block), 4096):
        block[i] = 1
    del block
    print(rss() - before)
""")


def _kept_pages(mode: str) -> int:
    out = subprocess.run([sys.executable, "-c", PROBE, mode], capture_output=True, text=True, check=True, timeout=60)
    return int(out.stdout.strip())


@pytest.mark.skipif(not GLIBC, reason="glibc's malloc only")
def test_freed_memory_is_kept_only_when_asked():
    block = 24 * 1024 * 1024 // 4096
    assert _kept_pages("default") < block // 4
    assert _kept_pages("keep") > block * 3 // 4


def test_cli_keeps_freed_memory(monkeypatch):
    from etcheck.cli import main as cli

    calls = []
    monkeypatch.setattr(cli, "keep_freed_memory", lambda: calls.append(1))
    with pytest.raises(SystemExit):
        cli.main(["--version"])
    assert calls == [1]


def test_outside_linux_nothing_is_done(monkeypatch):
    from etcheck.runtime import heap

    heap.keep_freed_memory.cache_clear()
    monkeypatch.setattr(heap.sys, "platform", "darwin")
    try:
        assert heap.keep_freed_memory() is False
    finally:
        heap.keep_freed_memory.cache_clear()
