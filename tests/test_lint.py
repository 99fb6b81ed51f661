"""The package passes ruff with the project's rules (pyproject.toml [tool.ruff.lint]), the McCabe
complexity limit of 10 included: every finding is listed when it fails."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_finds_nothing_in_the_package():
    run = subprocess.run([sys.executable, "-m", "ruff", "check", "--output-format", "concise", "--no-cache", "etcheck"],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    findings = [line for line in run.stdout.splitlines() if line.startswith("etcheck")]
    assert run.returncode == 0 and not findings, "ruff findings:\n" + (run.stdout + run.stderr)


def test_the_complexity_limit_is_enabled():
    """C901 is among the enabled rules at a limit of 10 (so the test above enforces it)."""
    run = subprocess.run([sys.executable, "-m", "ruff", "check", "--show-settings", "etcheck/__init__.py"],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    enabled = run.stdout.split("linter.rules.enabled = [", 1)[1].split("\n]", 1)[0]
    assert "complex-structure (C901)" in enabled
    assert "linter.mccabe.max_complexity = 10\n" in run.stdout
