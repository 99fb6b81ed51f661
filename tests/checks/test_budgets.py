"""A check within its time and memory budgets: the margins always answered, the extras skipped with the reason."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import jsonschema
import pytest

from etcheck.checks.pipeline import check
from etcheck.checks.rungs.straight import DEFAULT_OPTIONS
from etcheck.report import results_json
from etcheck.runtime.timelimit import OutOfTime, within

ROOT = Path(__file__).resolve().parents[2]
SET = ROOT / "missions" / "set.toml"
SCHEMA = json.loads((ROOT / "docs" / "results.schema.json").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def full():
    return check(SET).results


def test_without_a_budget_nothing_is_skipped(full):
    assert full["resources"]["skipped"] == [] and full["resources"]["time_budget_s"] is None
    assert full["linear"]["campbell"] and full["linear"]["stability_map"] and full["accuracy"]


def test_past_the_time_budget_the_extras_are_skipped_and_the_margins_answered(full):
    """A budget spent before the extras start (1 us): every extra skipped with the reason, the same margins."""
    got = check(SET, replace(DEFAULT_OPTIONS, time_budget=1e-6)).results
    jsonschema.validate(json.loads(results_json(got)), SCHEMA)
    assert [(m["name"], m["value"], m["verdict"]) for m in got["margins"]] == \
        [(m["name"], m["value"], m["verdict"]) for m in full["margins"]]
    parts = {s["part"]: s["why"] for s in got["resources"]["skipped"]}
    assert set(parts) == {"operating spectrum", "Campbell diagram", "stability map", "accuracy table",
                          "how far the margin moves with each assumption", "design limits"}
    assert got["assumptions"] is None and got["design_limits"] is None
    assert "time budget (1e-06 s of computation" in parts["operating spectrum"]
    assert got["linear"]["operating_spectrum"] is None and got["linear"]["campbell"] is None
    assert got["linear"]["stability_map"] is None and got["accuracy"] is None
    assert got["resources"]["time_budget_s"] == 1e-6


def test_a_budget_that_runs_out_midway_keeps_what_was_finished(full):
    """0.3 s: whatever was finished by then is in the results, whole; each part either there or listed."""
    got = check(SET, replace(DEFAULT_OPTIONS, time_budget=0.3)).results
    jsonschema.validate(json.loads(results_json(got)), SCHEMA)
    skipped = {s["part"] for s in got["resources"]["skipped"]}
    lin = got["linear"]
    for part, value in (("operating spectrum", lin["operating_spectrum"]), ("Campbell diagram", lin["campbell"]),
                        ("stability map", lin["stability_map"]), ("accuracy table", got["accuracy"])):
        assert (part in skipped) == (value is None), part


def test_a_deadline_stops_the_work_and_its_helpers():
    def forever():
        while True:
            time.sleep(0.01)

    t0 = time.perf_counter()
    with pytest.raises(OutOfTime):
        within(time.perf_counter() + 0.2, forever)
    assert time.perf_counter() - t0 < 1.0
    assert within(None, lambda: 7) == 7
    with pytest.raises(OutOfTime):
        within(time.perf_counter() - 1.0, lambda: 7)  # already past: not started


def _etcheck(*args: str, budget: str, out: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "etcheck", *args, "--format", "json", "--out", str(out),
                           "--memory-budget", budget], capture_output=True, text=True, timeout=300, cwd=ROOT)


def test_within_a_small_memory_budget_the_margins_fall_back_to_routes_that_fit(full, tmp_path):
    """SET's damped pencils at 210 MB: the critical values from the exact determinant (no large matrix), the same
    verdict; the operating spectrum (and what is drawn at its resolution) skipped, saying what it would need."""
    proc = _etcheck(str(SET), budget="210 MB", out=tmp_path)
    assert proc.returncode == 0, proc.stderr
    got = json.loads((tmp_path / "set" / "results.json").read_text())
    assert got["verdict"] == full["verdict"] == "pass"
    for a, b in zip(got["margins"], full["margins"]):
        assert a["value"] == pytest.approx(b["value"], rel=1e-8)
    assert got["resources"]["memory_budget_bytes"] == 210_000_000
    why = {s["part"]: s["why"] for s in got["resources"]["skipped"]}["operating spectrum"]
    assert why.startswith("not answered: the spectrum at N = 24 would need") and "past the budget of 210 MB" in why
    assert "skipped operating spectrum: not answered" in proc.stdout


def test_what_no_route_can_answer_within_the_budget_is_not_answered_with_exit_1(tmp_path):
    """A bifurcation diagram's spectra do not fit 201 MB (1 MB beside the baseline): exit 1 and the reason."""
    proc = _etcheck("diagram", str(SET), budget="201 MB", out=tmp_path)
    assert proc.returncode == 1
    assert proc.stderr.startswith("etcheck: not answered: ") and "would need" in proc.stderr
    assert "Traceback" not in proc.stderr and not any(tmp_path.rglob("*.json"))


def test_a_budget_that_is_not_a_size_is_a_usage_error(tmp_path):
    proc = _etcheck(str(SET), budget="lots", out=tmp_path)
    assert proc.returncode == 2 and "--memory-budget: cannot read 'lots' as a memory size" in proc.stderr


def test_an_undamped_sign_off_past_its_budget_has_the_same_margins_without_its_spin_windows():
    from helpers import set_like

    data = set_like(name="undamped", damping_time="0 s", spin_rate="0.1041 rpm")
    full = check(data).results
    cut = check(data, replace(DEFAULT_OPTIONS, time_budget=1e-6)).results
    assert [(m["value"], m["verdict"]) for m in cut["margins"]] == [(m["value"], m["verdict"]) for m in full["margins"]]
    assert "stable spin windows" in {s["part"] for s in cut["resources"]["skipped"]}
    assert full["linear"]["spin_windows_scanned_to_rpm"] > cut["linear"]["spin_windows_scanned_to_rpm"]


def test_a_slow_check_says_where_its_time_went_and_a_slow_sign_off_offers_the_draft(full):
    """The margins' own time is in the results (never budgeted, at most the whole check's); a sign-off past its
    target says how long, how much of it the margins took on which model, and offers --draft; a draft past its
    second says how long and by which models; a quick one of either says nothing."""
    from etcheck.cli.check import DRAFT_SECONDS, SIGN_OFF_SECONDS, slow_check

    res = full["resources"]
    assert 0 < res["margins_s"] <= full["elapsed_s"]
    assert slow_check(full) == ""
    slow = {**full, "elapsed_s": SIGN_OFF_SECONDS + 2.5, "resources": {**res, "margins_s": 11.0}}
    line = slow_check(slow)
    assert "12.5 s" in line and "11.0 s of it the margins" in line and "--draft" in line
    assert full["margins"][0]["model"] in line
    draft = {**full, "fidelity": {**full["fidelity"], "name": "draft"}}
    assert slow_check({**draft, "elapsed_s": 0.5 * DRAFT_SECONDS}) == ""
    line = slow_check({**draft, "elapsed_s": DRAFT_SECONDS + 1.5})
    assert "this draft took 2.5 s" in line and full["margins"][0]["model"] in line and "--draft" not in line
