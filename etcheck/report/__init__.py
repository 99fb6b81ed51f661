"""Reports rendered from JSON-able check results: HTML, PDF and results.json.

All formats are rendered in memory first and then written atomically (temporary
file + rename), so a failure never leaves a half-written report behind.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

from etcheck.errors import ReportError

FILENAMES = {"html": "report.html", "pdf": "report.pdf", "json": "results.json"}
DAMPING_FILENAMES = {"html": "damping.html", "pdf": "damping.pdf", "json": "damping.json"}
DIAGRAM_FILENAMES = {"html": "diagram.html", "pdf": "diagram.pdf", "json": "diagram.json"}
SWEEP_FILENAMES = {"html": "sweep.html", "pdf": "sweep.pdf", "json": "sweep.json", "csv": "sweep.csv",
                   "nc": "sweep.nc"}


def render(results: dict | str, formats: tuple[str, ...], kind: str = "check") -> dict[str, bytes]:
    """Render the requested formats to bytes (nothing is written).

    ``results``: the results, or the text of results.json made from them (:func:`results_json`).
    ``kind`` is "check" (a mission check), "sweep" (a what-if sweep, which
    also has the data formats csv and nc), "diagram" (a bifurcation diagram) or
    "damping" (a damping map of the coiled tether).
    """
    out: dict[str, bytes] = {}
    text = results if isinstance(results, str) else results_json(results)
    results = json.loads(text)  # the reports show what results.json holds (plain JSON types only)
    html = None
    if "html" in formats or "pdf" in formats:
        # imported here: jinja2 and matplotlib are not needed for JSON or data files
        from etcheck.report.html import render_damping_html, render_diagram_html, render_html, render_sweep_html

        renderer = {"sweep": render_sweep_html, "diagram": render_diagram_html,
                    "damping": render_damping_html}.get(kind, render_html)
        html = renderer(results)  # figures drawn once, as PNG at print resolution, for both formats
    if "html" in formats:
        out["html"] = html.encode("utf-8")
    if "pdf" in formats:
        from etcheck.report.pdf import render_pdf  # WeasyPrint: only for a PDF

        out["pdf"] = render_pdf(html)
    if "json" in formats:
        out["json"] = text.encode()
    if "csv" in formats or "nc" in formats:
        from etcheck.report.sweep_files import to_csv, to_netcdf

        if "csv" in formats:
            out["csv"] = to_csv(results)
        if "nc" in formats:
            out["nc"] = to_netcdf(results)
    return out


def write_reports(results: dict, folder: Path, formats: tuple[str, ...] = ("html", "pdf", "json"),
                  kind: str = "check",
                  renderer: Callable[[dict | str, tuple[str, ...], str], dict[str, bytes]] | None = None
                  ) -> list[Path]:
    """Render and atomically write the reports into ``folder``; returns the paths.

    ``renderer``: a function like :func:`render` (default), e.g. the report process of
    :func:`etcheck.report.background.renderer`, which is handed the text of results.json: plain JSON types (an
    enum or a numpy value would make that process import the modules that define them; etcheck.checks.margins.margin
    loads astropy and scipy: ~0.6 s of its time), serialised once.
    """
    names = {"sweep": SWEEP_FILENAMES, "diagram": DIAGRAM_FILENAMES, "damping": DAMPING_FILENAMES}.get(kind, FILENAMES)
    rendered = renderer(results_json(results), formats, kind) if renderer is not None else render(results, formats, kind)
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ReportError(f"cannot create the report folder {folder}: {exc.strerror}") from None
    paths = []
    for fmt, data in rendered.items():
        path = folder / names[fmt]
        atomic_write(path, data)
        paths.append(path)
    return paths


def atomic_write(path: Path, data: bytes) -> None:
    """Write bytes to ``path`` via a temporary file in the same folder + rename."""
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as fh:
                fh.write(data)
                fh.flush()
                os.fsync(fh.fileno())
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except OSError as exc:
        raise ReportError(f"cannot write {path}: {exc.strerror}") from None


def results_json(results: dict) -> str:
    """The text of results.json: indented UTF-8 JSON without NaN, numpy values as plain numbers."""
    return json.dumps(results, indent=2, allow_nan=False, ensure_ascii=False, default=_json_default) + "\n"


def _json_default(obj):
    import numpy as np

    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(f"not JSON-serialisable: {type(obj).__name__}")
