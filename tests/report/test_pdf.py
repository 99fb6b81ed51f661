"""The PDF embeds each RGB figure's own PNG image stream: the same pages, without WeasyPrint's decode and re-encode."""

from __future__ import annotations

import base64
import io
import shutil
import subprocess
import zlib

import numpy as np
import pytest

from etcheck.report import pdf

weasyprint = pytest.importorskip("weasyprint")
from PIL import Image  # noqa: E402 - WeasyPrint's own dependency

PDFTOPPM = shutil.which("pdftoppm")


def _png(mode: str, **options) -> bytes:
    rng = np.random.default_rng(7)
    width, height = 61, 23  # odd sizes: rows are not word-aligned
    channels = {"RGB": 3, "RGBA": 4, "L": 1}[mode]
    pixels = rng.integers(0, 256, (height, width, channels), dtype=np.uint8)
    pixels[5:9] = 255  # a flat stretch, as on a figure's white background
    image = Image.fromarray(pixels[..., 0] if channels == 1 else pixels, mode)
    out = io.BytesIO()
    image.save(out, format="PNG", **options)
    return out.getvalue()


def test_image_stream_of_an_rgb_png_is_its_idat_data():
    png = _png("RGB", compress_level=1)
    stream = pdf.png_image_stream(png)
    assert stream is not None and stream in png
    rows = zlib.decompress(stream)
    assert len(rows) == 23 * (1 + 3 * 61)  # each row: its filter byte, then RGB
    assert set(rows[:: 1 + 3 * 61]) <= {0, 1, 2, 3, 4}  # PNG filter types lead the rows


@pytest.mark.parametrize("png", [_png("RGBA"), _png("L"), _png("RGB", optimize=False)[:40], b"GIF89a...",
                                 _png("RGB").replace(b"IHDR", b"IHDX")])
def test_no_image_stream_for_anything_else(png):
    assert pdf.png_image_stream(png) is None


def test_interlaced_png_has_no_image_stream():
    png = bytearray(_png("RGB"))
    i = png.index(b"IHDR") + 4
    png[i + 12] = 1  # the interlace byte of IHDR (the CRC is not checked by the parser)
    assert pdf.png_image_stream(bytes(png)) is None


def _html(*pngs: bytes) -> str:
    imgs = "".join(f'<p><img src="data:image/png;base64,{base64.b64encode(p).decode()}" width="183" height="69"></p>'
                   for p in pngs)
    return f"<html><body><h1>figures</h1>{imgs}</body></html>"


def test_pdf_embeds_the_drawn_stream_and_restores_weasyprint():
    from weasyprint import images

    own = images.RasterImage.__dict__["_get_png_data"]
    rgb = _png("RGB", compress_level=1)
    out = pdf.render_pdf(_html(rgb, _png("RGBA")))
    assert pdf.png_image_stream(rgb) in out  # embedded as drawn, not re-encoded
    assert images.RasterImage.__dict__["_get_png_data"] is own


@pytest.mark.skipif(PDFTOPPM is None, reason="pdftoppm not installed (apt-get install poppler-utils)")
def test_pdf_pages_are_the_same_pixels(tmp_path):
    html = _html(_png("RGB", compress_level=1), _png("RGBA"), _png("L"), _png("RGB", compress_level=9))
    ours = pdf.render_pdf(html)
    theirs = weasyprint.HTML(string=html).write_pdf()
    assert ours != theirs
    pages = {}
    for name, data in (("ours", ours), ("theirs", theirs)):
        (tmp_path / f"{name}.pdf").write_bytes(data)
        subprocess.run([PDFTOPPM, "-r", "150", "-png", str(tmp_path / f"{name}.pdf"), str(tmp_path / name)],
                       check=True, capture_output=True, timeout=60)
        pages[name] = sorted(tmp_path.glob(f"{name}-*.png"))
    assert len(pages["ours"]) == len(pages["theirs"]) >= 1
    for a, b in zip(pages["ours"], pages["theirs"]):
        assert np.array_equal(np.asarray(Image.open(a)), np.asarray(Image.open(b)))
