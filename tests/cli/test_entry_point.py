"""The ``etcheck`` command ends its process at once after its work (no interpreter teardown): every exit code
and every line of output is still there."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from etcheck import __version__

ROOT = Path(__file__).resolve().parents[2]


def _etcheck(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "etcheck", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=120, **kwargs)


def test_version_and_usage_errors_keep_their_exit_codes():
    out = _etcheck("--version")
    assert out.returncode == 0 and out.stdout.strip() == f"etcheck {__version__}"
    bad = _etcheck("missions/set-static.toml", "--format", "bogus")
    assert bad.returncode == 2 and "--format" in bad.stderr and "Traceback" not in bad.stderr


def test_a_run_writes_everything_and_says_so(tmp_path):
    out = _etcheck("missions/set-static.toml", "--format", "json", "--out", str(tmp_path))
    assert out.returncode == 0, out.stderr
    written = tmp_path / "set-static" / "results.json"
    assert json.loads(written.read_text())["verdict"] == "pass"
    assert out.stdout.rstrip().endswith(f"wrote {written}")  # the last line, flushed before the process ends


def test_a_closed_pipe_is_no_error(tmp_path):
    """``etcheck ... | head -1``: the reader goes away; the command ends without a traceback, with the shell's
    code for SIGPIPE (141) where its summary could not be printed (the reports are written before it)."""
    proc = subprocess.Popen([sys.executable, "-m", "etcheck", "missions/set-static.toml", "--format", "json",
                             "--out", str(tmp_path)], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # nobody reads
    _, err = proc.communicate(timeout=120)
    assert proc.returncode in (0, 141) and b"Traceback" not in err, err
    assert (tmp_path / "set-static" / "results.json").exists()
