"""Reports as a person sees them: each kind of HTML report in headless Chromium, every PDF page via pdftoppm.

Skipped when chromium or pdftoppm is missing (.ci/run installs them from
Debian packages: apt-get install chromium poppler-utils).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
REPORTS = ROOT / "reports"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
PDFTOPPM = shutil.which("pdftoppm")
#: one of each kind: the buckled tether's check, a sweep, a diagram, a damping map
KINDS = ["set-600-m/report", "set/sweep/sweep", "set/diagram-w0.25/diagram", "set/damping-map/damping"]
#: in Chromium by default: the check and the diagram (two Chromium runs of ~1.5 s each per report); the sweep and the
#: damping map share their templates' machinery, and their pages are checked below and in tests/report/test_pages.py
BROWSED = [k if k in KINDS[::2] else pytest.param(k, marks=pytest.mark.slow) for k in KINDS]


def _chromium(*args: str) -> subprocess.CompletedProcess:
    with tempfile.TemporaryDirectory() as profile:
        return subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                               "--disable-component-update", "--disable-sync", "--no-first-run",
                               f"--user-data-dir={profile}", *args], capture_output=True, text=True, timeout=60)


@pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium not installed (apt-get install chromium)")
@pytest.mark.parametrize("kind", BROWSED)
def test_html_renders_in_chromium_with_every_figure(kind, tmp_path):
    html = REPORTS / f"{kind}.html"
    assert html.exists(), "run scripts/regenerate-reports"
    source = html.read_text()
    figures = source.count("<figure>")
    assert figures > 0
    dom = _chromium("--dump-dom", html.as_uri())
    assert dom.returncode == 0, dom.stderr[-2000:]
    # every figure reached the rendered DOM as an inline PNG with its caption
    rendered = re.findall(r'<figure>\s*<img src="data:image/png;base64,[^"]+"[^>]*>\s*<figcaption>Figure \d+:', dom.stdout)
    assert len(rendered) == figures
    shot = tmp_path / "shot.png"
    run = _chromium("--hide-scrollbars", "--window-size=1200,1600", f"--screenshot={shot}", html.as_uri())
    assert run.returncode == 0 and shot.exists(), run.stderr[-2000:]
    from PIL import Image

    img = Image.open(shot).convert("L")
    assert img.size == (1200, 1600)
    assert img.getextrema()[0] < 100  # ink on the page (not blank)


@pytest.mark.skipif(PDFTOPPM is None, reason="pdftoppm not installed (apt-get install poppler-utils)")
@pytest.mark.parametrize("kind", KINDS)
def test_pdf_pages_render_with_every_figure_and_nothing_in_the_side_margins(kind, tmp_path):
    pdf = REPORTS / f"{kind}.pdf"
    figures = (REPORTS / f"{kind}.html").read_text().count("<figure>")
    run = subprocess.run([PDFTOPPM, "-r", "40", "-gray", str(pdf), str(tmp_path / "p")], capture_output=True, text=True,
                         timeout=60)
    assert run.returncode == 0 and not run.stderr.strip(), run.stderr
    pages = sorted(tmp_path.glob("p-*.pgm"))
    assert pages
    from PIL import Image

    for page in pages:
        img = Image.open(page)
        w, h = img.size
        margin = int(round(10 / 210 * w))  # the outer 10 mm of the 14 mm side margins of A4
        for box in ((0, 0, margin, h), (w - margin, 0, w, h)):
            assert img.crop(box).getextrema()[0] > 200, f"{page.name}: ink in a side margin (something overflows)"
    # the PDF embeds one PNG per figure, at print resolution
    images = subprocess.run(["pdfimages", "-list", str(pdf)], capture_output=True, text=True, timeout=60)
    if images.returncode == 0:
        rows = [line.split() for line in images.stdout.strip().splitlines()[2:] if line.split()[2] == "image"]
        assert len(rows) == figures and min(int(r[12]) for r in rows) >= 150, images.stdout  # x-ppi on the page
