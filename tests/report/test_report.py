"""Report rendering: escaping, atomic writes, content an engineer needs."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from helpers import set_like

from etcheck import check
from etcheck.checks.results.header import SCHEMA_VERSION
from etcheck.errors import ReportError
from etcheck.report import render, write_reports

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def set_results():
    return check(ROOT / "missions" / "set-static.toml").results


def test_html_escapes_mission_text():
    evil = '<script>alert("x")</script>'
    results = check(set_like(name=evil, description=evil + " & <b>bold</b>")).results
    html = render(results, ("html",))["html"].decode()
    assert "<script>" not in html
    assert "&lt;script&gt;" in html
    assert "<b>bold</b>" not in html


def test_html_has_the_engineering_content(set_results):
    html = render(set_results, ("html",))["html"].decode()
    for text in ("PASS", "SHA-256", set_results["mission"]["sha256"], "Validity and accuracy",
                 "rung 0 (analytic)", "0.0111", "operating"):
        assert text in html, text
    # both figures inline (PNG data), no external resources
    assert html.count('<img src="data:image/png;base64,') == html.count("<figure>") >= 2
    assert "src=\"http" not in html and "href=\"http" not in html


def test_json_is_strict_and_round_trips(set_results):
    data = render(set_results, ("json",))["json"]
    loaded = json.loads(data)
    assert loaded["schema_version"] == SCHEMA_VERSION
    assert loaded["straight_rod"]["critical_loads"][0]["B"] == pytest.approx(
        set_results["straight_rod"]["critical_loads"][0]["B"], rel=0, abs=0
    )


def test_pdf_is_a_pdf(set_results, tmp_path):
    pdf = render(set_results, ("pdf",))["pdf"]
    assert pdf.startswith(b"%PDF-") and len(pdf) > 10_000
    if shutil.which("pdfimages") and shutil.which("pdffonts"):  # poppler-utils
        (tmp_path / "r.pdf").write_bytes(pdf)
        images = subprocess.run(["pdfimages", "-list", str(tmp_path / "r.pdf")], capture_output=True, text=True,
                                check=True).stdout.splitlines()[2:]
        # one opaque RGB image per figure: no alpha masks (the PDF writer would compress each twice)
        assert len(images) == 2 and all(r.split()[2] == "image" and r.split()[5] == "rgb" for r in images), images
        fonts = subprocess.run(["pdffonts", str(tmp_path / "r.pdf")], capture_output=True, text=True,
                               check=True).stdout.splitlines()[2:]
        # one family (the footers too) and the monospace SHA-256: each embedded font costs a subsetting
        assert sorted(f.split()[0].split("+")[1] for f in fonts) == ["DejaVu-Sans", "DejaVu-Sans-Bold",
                                                                     "DejaVu-Sans-Mono"], fonts


def test_failed_render_writes_nothing(set_results, tmp_path, monkeypatch):
    import etcheck.report.pdf as pdf

    def broken(html):
        raise ReportError("PDF engine missing")

    monkeypatch.setattr(pdf, "render_pdf", broken)
    with pytest.raises(ReportError):
        write_reports(set_results, tmp_path / "set", ("html", "pdf", "json"))
    assert not (tmp_path / "set").exists() or not any((tmp_path / "set").iterdir())


def test_rewrite_replaces_atomically(set_results, tmp_path):
    paths = write_reports(set_results, tmp_path / "set", ("json",))
    first = paths[0].read_bytes()
    write_reports(set_results, tmp_path / "set", ("json",))
    assert paths[0].read_bytes() == first
    leftovers = [p for p in (tmp_path / "set").iterdir() if p.name.endswith(".tmp")]
    assert leftovers == []


def test_a_write_stopped_by_a_signal_leaves_the_old_report_and_no_temporary_file(set_results, tmp_path, monkeypatch):
    """SIGTERM while a report is being written (raised here where it is synced to disk) leaves the previous report
    whole and removes the temporary file."""
    import os
    import signal

    from etcheck.runtime.lifetime import Stopped

    paths = write_reports(set_results, tmp_path / "set", ("json",))
    before = paths[0].read_bytes()

    def stopped(fd):
        raise Stopped(signal.SIGTERM)

    monkeypatch.setattr(os, "fsync", stopped)
    with pytest.raises(Stopped):
        write_reports(set_results | {"verdict": "changed"}, tmp_path / "set", ("json",))
    assert paths[0].read_bytes() == before
    assert [p.name for p in (tmp_path / "set").iterdir()] == [paths[0].name]
