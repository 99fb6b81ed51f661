"""Matplotlib set-up shared by every report figure: one style, deterministic inline SVG.

matplotlib is imported here lazily (only when a figure is drawn), so importing
etcheck, the solvers or a JSON-only run never loads it.
"""

from __future__ import annotations

import contextlib
import contextvars
import io

#: dots per inch of the PNG copies of the figures when a print version is wanted (None: SVG only)
_RASTER_DPI: contextvars.ContextVar[int | None] = contextvars.ContextVar("etcheck_raster_dpi", default=None)
#: print resolution of the figures embedded in the PDF (sharp on paper at the figures' printed size)
PRINT_DPI = 220


class FigureSource(str):
    """An inline SVG figure; ``png`` holds a PNG copy at print resolution when one was asked for."""

    png: bytes | None = None


@contextlib.contextmanager
def rasterised(dpi: int = PRINT_DPI):
    """Within the block every figure also keeps a PNG copy at ``dpi`` (for the PDF)."""
    token = _RASTER_DPI.set(dpi)
    try:
        yield
    finally:
        _RASTER_DPI.reset(token)


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(
        {
            "svg.hashsalt": "etcheck",
            "svg.fonttype": "none",
            "font.size": 9,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "figure.dpi": 100,
        }
    )
    return plt


def svg(fig) -> str:
    """The figure as inline SVG (a :class:`FigureSource`, with a PNG copy inside :func:`rasterised`)."""
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None})
    text = buf.getvalue()
    out = FigureSource(text[text.index("<svg") :])  # drop the XML prolog for inline use
    dpi = _RASTER_DPI.get()
    if dpi:
        png = io.BytesIO()
        fig.savefig(png, format="png", dpi=dpi, bbox_inches="tight", metadata={"Software": None})
        out.png = png.getvalue()
    pyplot().close(fig)
    return out
