"""Matplotlib set-up shared by every report figure: one style, each figure drawn once as a PNG.

A figure is drawn once, at print resolution, and the same PNG goes into the HTML
and the PDF: WeasyPrint draws vector figures point by point (seconds per
report), and a vector copy for the screen would cost a second full draw.
At 220 dpi the 7-pt labels and hairlines stay sharp on paper and on
high-density screens (the figures print about 18 cm wide, so the PNGs are
about 1450 pixels wide).

matplotlib is imported here lazily (only when a figure is drawn), so importing
etcheck, the solvers or a JSON-only run never loads it.
"""

from __future__ import annotations

import base64
import contextlib
import contextvars
import io
import os
import pickle
import threading
from collections.abc import Callable, Iterator

from etcheck.runtime.lifetime import die_with_parent, kill_and_reap

#: dots per inch of the figures (sharp on paper at the figures' printed size)
PRINT_DPI = 220
#: white border kept around the drawn content [inch] (matplotlib's default for a tight bounding box)
PAD_INCH = 0.1


class FigureImage(str):
    """A drawn figure as an inline ``<img>`` element (a PNG data URI); ``png`` holds the PNG bytes."""

    png: bytes = b""


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(
        {
            "font.size": 9,
            "axes.grid": True,
            "grid.alpha": 0.3,
            # drawn at print resolution from the start: layout passes (tight_layout) and the final draw share
            # one renderer and its cached text metrics
            "figure.dpi": PRINT_DPI,
        }
    )
    return plt


#: space under an axes for its tick labels and x-axis label [inch]: a legend below starts past it
BELOW_AXIS_INCH = 0.48


def legend_below(ax, handles=None, ncol: int = 2, fontsize: float = 7, axis_label: bool = True):
    """A legend under ``ax``, clear of the data and of the x-axis label (call it after the figure's layout:
    it reads the axes' final height). The figure's PNG grows to hold it (:func:`image` crops to the content)."""
    fig = ax.figure
    height = ax.get_position().height * fig.get_figheight()
    gap = (BELOW_AXIS_INCH if axis_label else 0.3) / height
    kw = {} if handles is None else {"handles": handles}
    return ax.legend(loc="upper center", bbox_to_anchor=(0.5, -gap), ncol=ncol, fontsize=fontsize, frameon=False,
                     borderaxespad=0.0, **kw)


#: called with every figure just before it is drawn (:func:`inspecting`); None: nothing
_INSPECT: contextvars.ContextVar[Callable | None] = contextvars.ContextVar("etcheck_inspect", default=None)


@contextlib.contextmanager
def inspecting(callback: Callable) -> Iterator[None]:
    """Within the block every figure is handed to ``callback(fig)`` before it is drawn (figures drawn in this
    process: the layout tests read where legends and labels fall against the data)."""
    token = _INSPECT.set(callback)
    try:
        yield
    finally:
        _INSPECT.reset(token)


def image(fig) -> FigureImage:
    """Draw ``fig`` once at :data:`PRINT_DPI` and return it as a PNG ``<img>``, cropped to its content plus
    :data:`PAD_INCH` (as matplotlib's ``bbox_inches="tight"``); the figure is closed."""
    from PIL import Image

    inspect = _INSPECT.get()
    if inspect is not None:
        inspect(fig)
    png = cropped_png(fig)
    pyplot().close(fig)
    width, height = Image.open(io.BytesIO(png)).size
    out = FigureImage(f'<img src="data:image/png;base64,{base64.b64encode(png).decode()}" '
                      f'width="{width}" height="{height}" alt="">')
    out.png = png
    return out


#: whether :func:`draw` may fork a helper (only in the report process, which has one thread)
_FORK_OK: contextvars.ContextVar[bool] = contextvars.ContextVar("etcheck_fork_ok", default=False)


@contextlib.contextmanager
def forking_allowed() -> Iterator[None]:
    """Within the block :func:`draw` may draw half of the figures in a forked helper (on two or more cores)."""
    token = _FORK_OK.set(True)
    try:
        yield
    finally:
        _FORK_OK.reset(token)


def draw(jobs: dict[str, Callable[[], dict[str, FigureImage]]]) -> dict[str, FigureImage]:
    """Run each job (one or a few figures each, keyed by figure name) and merge their figures.

    Inside :func:`forking_allowed` on two or more cores every second job runs in a forked helper at the same
    time (a figure is a few tenths of a second of matplotlib; the helper is a copy of this process, so the
    bytes are the same); if the helper fails, its jobs are run here.
    """
    names = list(jobs)
    if not (_FORK_OK.get() and len(names) > 1 and len(os.sched_getaffinity(0)) >= 2
            and threading.active_count() == 1):
        return {k: v for name in names for k, v in jobs[name]().items()}
    theirs = names[1::2]
    read, write = os.pipe()
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:  # the helper: draw its jobs, send the PNGs, leave without any clean-up of the parent's state
        code = 1
        try:
            die_with_parent(parent)
            os.close(read)
            out = {k: (str(v), v.png) for name in theirs for k, v in jobs[name]().items()}
            with os.fdopen(write, "wb") as fh:
                pickle.dump(out, fh)
            code = 0
        finally:
            os._exit(code)
    os.close(write)
    try:
        mine = {k: v for name in names[0::2] for k, v in jobs[name]().items()}
        with os.fdopen(os.dup(read), "rb") as fh:
            data = fh.read()
        _, status = os.waitpid(pid, 0)
    except BaseException:  # a failed figure here or a stop signal: the helper's figures are not needed
        kill_and_reap(pid)
        raise
    finally:
        os.close(read)
    if status != 0 or not data:  # the helper failed: draw its figures here (an error is raised here, with its traceback)
        return mine | {k: v for name in theirs for k, v in jobs[name]().items()}
    for k, (text, png) in pickle.loads(data).items():
        mine[k] = FigureImage(text)
        mine[k].png = png
    return mine


def cropped_png(fig) -> bytes:
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    fig.set_dpi(PRINT_DPI)
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()
    rgba = canvas.buffer_rgba()
    h, w = rgba.shape[:2]
    ink = np.asarray(rgba).view(np.uint32)[..., 0] != 0xFFFFFFFF  # anything but the opaque white background
    rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    tight = fig.get_tightbbox(canvas.get_renderer())  # inches: past the canvas where a legend lies wholly outside it
    beyond = tight.x0 < 0 or tight.y0 < 0 or tight.x1 > fig.get_figwidth() or tight.y1 > fig.get_figheight()
    if beyond or rows.size == 0 or rows[0] == 0 or cols[0] == 0 or rows[-1] == h - 1 or cols[-1] == w - 1:
        # content reaches past the canvas (e.g. a legend below the axes): draw again onto its tight bounding box
        bbox = tight.padded(PAD_INCH)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=PRINT_DPI, bbox_inches=bbox)
        crop = Image.open(buf)
    else:
        pad = round(PAD_INCH * PRINT_DPI)
        crop = Image.frombuffer("RGBA", (w, h), rgba, "raw", "RGBA", 0, 1).crop(
            (max(cols[0] - pad, 0), max(rows[0] - pad, 0), min(cols[-1] + pad + 1, w), min(rows[-1] + pad + 1, h)))
    out = io.BytesIO()
    # RGB without alpha: the PDF writer would otherwise split off and compress an alpha mask. zlib level 1:
    # much faster than the default level for slightly larger files (the PDF writer re-compresses anyway)
    crop.convert("RGB").save(out, format="PNG", compress_level=1)
    return out.getvalue()
