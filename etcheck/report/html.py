"""HTML report: one jinja2 template (autoescaped), figures inline as PNG; the PDF is typeset from the same HTML."""

from __future__ import annotations

import functools
import math
from collections import Counter

import numpy as np
from markupsafe import Markup, escape

from etcheck.report.figures.check import figures
from etcheck.report.figures.diagram import damping_maps, diagram_figures, eigen_paths_plot


def sci(x, digits: int = 4) -> Markup:
    """Number for a table cell: plain below 1e5, a×10<sup>n</sup> otherwise."""
    if x is None:
        return Markup("—")
    if isinstance(x, str):
        return escape(x)
    if x == 0:
        return Markup("0")
    if not math.isfinite(x):
        return Markup("∞" if x > 0 else "−∞")
    if 1e-3 <= abs(x) < 1e5 and "e" not in f"{x:.{digits}g}":  # .4g of 31380 would print 3.138e+04
        return escape(f"{x:.{digits}g}")
    mant, exp = f"{x:.{digits - 1}e}".split("e")
    return Markup(f"{escape(mant)}×10<sup>{int(exp)}</sup>")


#: components smaller than this times the largest of their vector are round-off and print as 0
ROUNDOFF = 1e-12


def vec(values, digits: int = 4, unit: str = "") -> Markup:
    """A vector for a table cell: components below the round-off of the vector's own scale
    (ROUNDOFF times its largest component) print as 0, e.g. 1.4e-19 N next to 0.0075 N."""
    finite = [abs(v) for v in values if v is not None and math.isfinite(v)]
    scale = max(finite, default=0.0)
    parts = [sci(0.0 if (v is not None and math.isfinite(v) and abs(v) <= ROUNDOFF * scale) else v, digits)
             for v in values]
    text = Markup("(") + Markup(", ").join(parts) + Markup(")")
    return text + (Markup(" ") + escape(unit) if unit else Markup(""))


class FigureNumbers:
    """``fignum()`` (``secnum()``) in a template: the next figure (section) number, one counter per rendered
    document; ``.n`` the last one given."""

    def __init__(self) -> None:
        self.n = 0

    def __call__(self) -> int:
        self.n += 1
        return self.n


#: the template of each kind of report
TEMPLATES = {"check": "report.html.j2", "sweep": "sweep.html.j2", "diagram": "diagram.html.j2",
             "damping": "damping.html.j2"}


@functools.lru_cache(maxsize=1)
def environment():
    """The jinja2 environment of the report templates (one per process: each template is compiled once)."""
    from jinja2 import Environment, PackageLoader, select_autoescape

    env = Environment(
        loader=PackageLoader("etcheck.report", "templates"),
        autoescape=select_autoescape(["html", "j2"], default_for_string=True, default=True),
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters["sci"] = sci
    env.filters["vec"] = vec
    return env


def _fig(source: str) -> Markup:
    """Markup of one drawn figure (an inline PNG ``<img>``, the same bytes in the HTML and the PDF)."""
    return Markup(source)


def _render(template: str, **context) -> str:
    # one counter for the figures, one for the sections (secnum.n: the current section's number)
    return environment().get_template(template).render(fignum=FigureNumbers(), secnum=FigureNumbers(), **context)


def render_html(results: dict) -> str:
    """The self-contained HTML report for check results (JSON-able dict)."""
    figs = {name: _fig(fig) for name, fig in figures(results).items()}
    return _render(TEMPLATES["check"], r=results, figs=figs)


def render_sweep_html(results: dict) -> str:
    """The self-contained HTML report of a sweep (JSON-able sweep results)."""
    g = results["grid"]
    models = Counter(m for m in np.ravel(np.array(g["model"], dtype=object)) if m)
    failures = []
    grids = [a["display_values"] for a in results["axes"]]
    for idx in np.ndindex(*g["shape"]):
        status = np.array(g["status"], dtype=object)[idx]
        if status != "ok":
            failures.append({"values": [grids[k][i] for k, i in enumerate(idx)], "status": status,
                             "reason": np.array(g["reason"], dtype=object)[idx]})
    from etcheck.report.figures.sweep import sweep_figures  # here: its axis table loads astropy.units (~0.35 s)

    figs = {name: _fig(fig) for name, fig in sweep_figures(results).items()}
    return _render(TEMPLATES["sweep"], r=results, figs=figs, models=dict(models),
                                                               failures=failures[:50])


def render_diagram_html(results: dict) -> str:
    """The self-contained HTML report of a bifurcation diagram."""
    figs = {name: _fig(fig) for name, fig in diagram_figures(results["diagram"], results["scales"]["length_m"],
                                                             results.get("operating")).items()}
    return _render(TEMPLATES["diagram"], r=results, d=results["diagram"], figs=figs)


def render_damping_html(results: dict) -> str:
    """The self-contained HTML report of a damping map of the coiled tether."""
    paths = results["study"]["spin_paths"]
    figs = {"maps": _fig(damping_maps(results)),
            "paths": _fig(eigen_paths_plot(paths, "spin ω (dimensionless)",
                                             f"b1 at B = {paths['B']:g}, γ = {paths['gamma']:g}: lowest eigenvalues "
                                             "against spin"))}
    return _render(TEMPLATES["damping"], r=results, figs=figs)
