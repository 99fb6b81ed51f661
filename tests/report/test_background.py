"""The report process renders the same bytes as this process (the HTML is deterministic: same results, same
bytes), and its failures come back as errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy  # noqa: F401  (loaded, as in any test run: no fork from here)
import pytest

from etcheck.report.background import worth_a_process

ROOT = Path(__file__).resolve().parents[2]

PROBE = """
import json, sys
import etcheck.report.pdf
from etcheck.errors import ReportError
from etcheck.report import render
from etcheck.report.background import renderer

def no_engine(html):
    raise ReportError("the PDF engine cannot load")

etcheck.report.pdf.render_pdf = no_engine  # before the fork: the report process has no PDF engine either
results = json.loads(open(sys.argv[1]).read())
with renderer(("html", "json")) as remote:
    assert remote is not render, "no report process was started"
    got = remote(results, ("html", "json"), "check")
    try:
        remote({"broken": True}, ("html",), "check")
        raise AssertionError("the failure was not reported")
    except RuntimeError as exc:
        bug = str(exc)
    try:
        remote(results, ("pdf",), "check")
        raise AssertionError("the missing PDF engine was not reported")
    except ReportError as exc:
        assert str(exc) == "the PDF engine cannot load", exc
    again = remote(results, ("json",), "check")  # still serving after the errors
assert got == render(results, ("html", "json"), "check"), "different bytes"
assert again["json"] == got["json"]
print(bug)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the report process is a fork (Linux)")
def test_the_report_process_renders_the_same_bytes_and_reports_failures():
    run = subprocess.run([sys.executable, "-c", PROBE, str(ROOT / "reports" / "set-static" / "results.json")],
                         cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.stdout.startswith("KeyError"), run.stdout  # the missing key, named


def test_no_process_for_data_only_formats_or_after_numpy():
    assert not worth_a_process(("json",))
    assert not worth_a_process(("html", "pdf"))  # this test process has numpy loaded: rendered in place


def _plain(value) -> bool:
    if type(value) is dict:
        return all(type(k) is str and _plain(v) for k, v in value.items())
    if type(value) is list:
        return all(_plain(v) for v in value)
    return type(value) in (str, int, float, bool, type(None))


def test_another_process_is_sent_plain_json_types(tmp_path):
    """An enum or a numpy value would make the report process import the modules that define them when it
    unpickles the results (etcheck.checks.margins.margin loads astropy and scipy: 0.6 s of its time)."""
    import numpy as np

    from etcheck.checks.margins.margin import Verdict
    from etcheck.report import render, write_reports

    sent = []

    def spy(results, fmts, kind):
        sent.append(results)
        return render(results, fmts, kind)

    results = {"verdict": Verdict.PASS, "value": np.float64(1.5), "n": np.int64(3), "rows": np.arange(2.0),
               "flags": [np.bool_(True)], "nested": {"v": (Verdict.FAIL, 1)}}
    (path,) = write_reports(results, tmp_path, ("json",), renderer=spy)
    assert isinstance(sent[0], str) and not _plain(results)  # the text of results.json, serialised once
    assert json.loads(sent[0]) == {"verdict": "pass", "value": 1.5, "n": 3, "rows": [0.0, 1.0], "flags": [True],
                                   "nested": {"v": ["fail", 1]}}
    assert path.read_text() == render(results, ("json",))["json"].decode()


NICENESS = """
import os, sys, time
from etcheck.report.background import renderer
kind = sys.argv[1]
ours = os.getpriority(os.PRIO_PROCESS, 0)
want = min(ours + 19, 19) if kind != "check" else ours
with renderer(("html",), kind) as remote:
    deadline = time.monotonic() + 30
    while True:  # the report process sets its priority first thing: wait for it
        theirs = os.getpriority(os.PRIO_PROCESS, remote.pid)
        if theirs == want or time.monotonic() > deadline:
            break
        time.sleep(0.05)
    time.sleep(0.2)
    theirs = os.getpriority(os.PRIO_PROCESS, remote.pid)  # and keeps it
print(theirs - want)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the report process is a fork (Linux)")
@pytest.mark.parametrize("kind", ["diagram", "check",  # every study kind takes the same branch as the diagram:
                                  pytest.param("sweep", marks=pytest.mark.slow),
                                  pytest.param("damping", marks=pytest.mark.slow)])
def test_a_studys_report_process_takes_only_idle_cores(kind):
    """A study's report process at the lowest priority (nice 19), a check's at its parent's."""
    run = subprocess.run([sys.executable, "-c", NICENESS, kind], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-3000:]
    assert int(run.stdout.strip()) == 0, "report process priority off by " + run.stdout
