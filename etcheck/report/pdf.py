"""PDF from the same HTML (WeasyPrint): one document, two formats."""

from __future__ import annotations

from etcheck.errors import ReportError


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
    return weasyprint.HTML(string=html).write_pdf()
