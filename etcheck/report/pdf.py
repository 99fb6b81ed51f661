"""PDF from the same HTML (WeasyPrint): one document, two formats.

The figures are PNGs drawn once (:mod:`etcheck.report.figures.common`). A PDF
holds an RGB image as the same zlib stream as a PNG's IDAT chunks (FlateDecode
with PNG predictors), yet WeasyPrint decodes every PNG and encodes it again to
get that stream: a quarter to a third of the time it takes to typeset a report.
While a report is typeset, :func:`_figures_as_drawn` hands it the IDAT stream of
each 8-bit RGB, non-interlaced PNG as it is; anything else (alpha, palette,
16 bit, interlaced, a WeasyPrint without that step) takes WeasyPrint's own path.
The pages are the same pixels either way (tested by rasterising both PDFs).
"""

from __future__ import annotations

import contextlib
import io
import struct
import threading
from collections.abc import Iterator

from etcheck.errors import ReportError

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: one report typeset at a time while WeasyPrint's method is replaced (threads would restore each other's)
_TYPESETTING = threading.Lock()


def render_pdf(html: str) -> bytes:
    """Typeset the HTML report as PDF bytes.

    WeasyPrint needs the Pango system library; if it cannot load, the error
    says so and how to get HTML/JSON only.
    """
    try:
        import weasyprint
    except (ImportError, OSError) as exc:
        raise ReportError(
            f"the PDF engine (WeasyPrint) cannot load: {exc}. Install the Pango library "
            "(Debian: apt-get install libpango-1.0-0 libpangoft2-1.0-0) or run with --format html,json"
        ) from None
    with _TYPESETTING, _figures_as_drawn():
        return weasyprint.HTML(string=html).write_pdf()


def png_image_stream(png: bytes) -> bytes | None:
    """The image data of an 8-bit RGB, non-interlaced PNG as a PDF image holds it (the PNG's IDAT chunks
    joined: a zlib stream of rows, each led by its PNG filter byte), or None for any other image."""
    if not png.startswith(PNG_SIGNATURE):
        return None
    pos, chunks, header = len(PNG_SIGNATURE), [], None
    while pos + 8 <= len(png):
        length, kind = struct.unpack(">I4s", png[pos:pos + 8])
        body = png[pos + 8:pos + 8 + length]
        if len(body) != length:
            return None  # truncated
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            chunks.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + length  # length, type, data, CRC
    # bit depth 8, colour type 2 (RGB), compression 0, filter 0, no interlace
    if header is None or header[2:] != (8, 2, 0, 0, 0) or not chunks:
        return None
    return b"".join(chunks)


@contextlib.contextmanager
def _figures_as_drawn() -> Iterator[None]:
    """Within the block WeasyPrint embeds an RGB PNG's own image stream instead of decoding and re-encoding it
    (module docstring); its own method is back in place afterwards."""
    from weasyprint import images

    own = images.RasterImage.__dict__.get("_get_png_data")
    if not isinstance(own, staticmethod):  # another WeasyPrint: its own path
        yield
        return
    encode = own.__func__

    def as_drawn(pillow_image):
        fp = getattr(pillow_image, "fp", None)
        stream = png_image_stream(fp.getvalue()) if isinstance(fp, io.BytesIO) and pillow_image.mode == "RGB" else None
        return encode(pillow_image) if stream is None else stream

    images.RasterImage._get_png_data = staticmethod(as_drawn)
    try:
        yield
    finally:
        images.RasterImage._get_png_data = own
