"""Reports rendered from JSON-able check results: HTML, PDF and results.json.

All formats are rendered in memory first and then written atomically (temporary
file + rename), so a failure never leaves a half-written report behind.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from ..errors import ReportError

FILENAMES = {"html": "report.html", "pdf": "report.pdf", "json": "results.json"}


def render(results: dict, formats: tuple[str, ...]) -> dict[str, bytes]:
    """Render the requested formats to bytes (nothing is written)."""
    out: dict[str, bytes] = {}
    html = None
    if "html" in formats or "pdf" in formats:
        from .html import render_html

        html = render_html(results)
    if "html" in formats:
        out["html"] = html.encode("utf-8")
    if "pdf" in formats:
        from .pdf import render_pdf

        out["pdf"] = render_pdf(html)
    if "json" in formats:
        out["json"] = (json.dumps(results, indent=2, allow_nan=False, ensure_ascii=False, default=_json_default) + "\n").encode()
    return out


def write_reports(results: dict, folder: Path, formats: tuple[str, ...] = ("html", "pdf", "json")) -> list[Path]:
    """Render and atomically write the reports into ``folder``; returns the paths."""
    rendered = render(results, formats)
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ReportError(f"cannot create the report folder {folder}: {exc.strerror}") from None
    paths = []
    for fmt, data in rendered.items():
        path = folder / FILENAMES[fmt]
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


def _json_default(obj):
    import numpy as np

    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(f"not JSON-serialisable: {type(obj).__name__}")
