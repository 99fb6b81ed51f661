"""The report figures are readable: no legend over the data, no label over another label, the operating
point on every map and diagram.

Every figure of the committed example reports (reports/: a spinning check with a stability map and a Campbell
diagram, a tape on its orbit, the buckled tether, an uncertainty study, the sweep, the bifurcation diagram and
the damping map) is drawn again from its results and inspected before it becomes a PNG
(:func:`etcheck.report.figures.common.inspecting`): the legend's box in display coordinates against the display
coordinates of every data point and line of every axes, and the boxes of the labels drawn in an axes against
each other.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from etcheck.report.figures import common
from etcheck.report.figures.common import inspecting, pyplot

REPORTS = Path(__file__).resolve().parents[2] / "reports"
#: points per segment when a line is sampled between its vertices (a line through a legend between two vertices)
DENSITY = 24


def _load(name: str) -> dict:
    return json.loads((REPORTS / name).read_text(encoding="utf-8"))


def _check_figures(name: str):
    from etcheck.report.figures.check import figures

    r = _load(name)
    return lambda: figures(r)


def _sweep_figures():
    from etcheck.report.figures.sweep import sweep_figures

    r = _load("set/sweep/sweep.json")
    return lambda: sweep_figures(r)


def _diagram_figures():
    from etcheck.report.figures.diagram import diagram_figures

    r = _load("set/diagram-w0.25/diagram.json")
    return lambda: diagram_figures(r["diagram"], r["scales"]["length_m"], r.get("operating"))


def _damping_figures():
    from etcheck.report.figures.diagram import damping_maps

    r = _load("set/damping-map/damping.json")
    return lambda: {"maps": damping_maps(r)}


FIGURE_SETS = {
    "set": lambda: _check_figures("set/results.json"),
    "tape": lambda: _check_figures("tape-tether/results.json"),
    "buckled": lambda: _check_figures("set-600-m/results.json"),
    "uncertainty": lambda: _check_figures("set-with-tolerances/results.json"),
    "sweep": _sweep_figures,
    "diagram": _diagram_figures,
    "damping": _damping_figures,
}


#: dots per inch of the inspection draw: display coordinates scale with it, data and boxes alike
INSPECT_DPI = 72


def _drawn(draw) -> list:
    """Every figure ``draw()`` makes, drawn once at INSPECT_DPI (layout final) and inspected; the figures' PNGs
    are not made (their pixels are tested in test_figures)."""
    seen = []

    def keep(fig):
        fig.set_dpi(INSPECT_DPI)
        fig.canvas.draw()
        seen.append((fig, _legend_problems(fig), _label_problems(fig), _has_operating_point(fig)))

    with pytest.MonkeyPatch.context() as mp, inspecting(keep):
        mp.setattr(common, "cropped_png", _blank_png)
        draw()
    return seen


def _blank_png(fig) -> bytes:
    import io

    from PIL import Image

    out = io.BytesIO()
    Image.new("RGB", (4, 3), "white").save(out, format="PNG")
    return out.getvalue()


def _densified(xy: np.ndarray) -> np.ndarray:
    if len(xy) < 2:
        return xy
    t = np.linspace(0.0, 1.0, DENSITY, endpoint=False)[:, None]
    steps = [a + t * (b - a) for a, b in zip(xy[:-1], xy[1:])]
    return np.vstack([*steps, xy[-1:]])


def _data_points(ax) -> np.ndarray:
    """Display coordinates of the data an axes shows: its lines (sampled between vertices), markers, scatter
    points and contour lines, within the axes' box; filled areas (backgrounds) are not data points here."""
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.contour import ContourSet

    pts = []
    for line in ax.get_lines():
        xy = np.asarray(line.get_xydata(), dtype=float)
        if not line.get_visible() or xy.size == 0:
            continue
        drawn_line = line.get_linestyle() not in ("None", "", " ")
        xy = _densified(xy) if drawn_line else xy
        pts.append(line.get_transform().transform(xy))
    for coll in ax.collections:
        if isinstance(coll, ContourSet) and not coll.filled:
            for path in coll.get_paths():
                pts.append(coll.get_transform().transform(_densified(path.vertices)))
        elif isinstance(coll, PathCollection) and len(coll.get_offsets()):
            pts.append(coll.get_offset_transform().transform(np.asarray(coll.get_offsets(), dtype=float)))
        elif isinstance(coll, LineCollection):
            for path in coll.get_paths():
                pts.append(coll.get_transform().transform(_densified(path.vertices)))
    if not pts:
        return np.empty((0, 2))
    p = np.vstack(pts)
    p = p[np.all(np.isfinite(p), axis=1)]
    box = ax.bbox
    inside = (p[:, 0] >= box.x0) & (p[:, 0] <= box.x1) & (p[:, 1] >= box.y0) & (p[:, 1] <= box.y1)
    return p[inside]


def _legend_problems(fig) -> list[str]:
    renderer = fig.canvas.get_renderer()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    out = []
    for legend in legends:
        box = legend.get_window_extent(renderer)
        for ax in fig.axes:
            if ax.name == "3d":
                continue
            p = _data_points(ax)
            hit = (p[:, 0] >= box.x0) & (p[:, 0] <= box.x1) & (p[:, 1] >= box.y0) & (p[:, 1] <= box.y1)
            if hit.any():
                out.append(f"legend ({', '.join(t.get_text() for t in legend.get_texts())[:60]}...) over "
                           f"{int(hit.sum())} data points of the axes {ax.get_title()!r}")
    return out


def _label_problems(fig) -> list[str]:
    renderer = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        texts = [t for t in ax.texts if t.get_visible() and t.get_text().strip()]
        boxes = [t.get_window_extent(renderer) for t in texts]
        for i in range(len(texts)):
            for j in range(i + 1, len(texts)):
                if boxes[i].overlaps(boxes[j]):
                    out.append(f"labels {texts[i].get_text()!r} and {texts[j].get_text()!r} overlap in "
                               f"{ax.get_title()!r}")
    return out


def _has_operating_point(fig) -> bool:
    """A green star (the operating point's mark in every report figure) in some axes, or an operating line."""
    for ax in fig.axes:
        for line in ax.get_lines():
            if line.get_marker() == "*" or "operating" in str(line.get_label()):
                return True
    return False


@pytest.fixture(scope="module")
def drawn() -> dict[str, list]:
    pyplot()
    return {name: _drawn(make()) for name, make in FIGURE_SETS.items()}


@pytest.mark.parametrize("name", list(FIGURE_SETS))
def test_no_legend_over_data(drawn, name):
    problems = [p for _, legend, _, _ in drawn[name] for p in legend]
    assert not problems, problems


@pytest.mark.parametrize("name", list(FIGURE_SETS))
def test_no_label_over_another(drawn, name):
    problems = [p for _, _, labels, _ in drawn[name] for p in labels]
    assert not problems, problems


#: the figures that are maps or diagrams of the operating point's plane (titles as drawn)
MAPS = ("Safe operating region", "bifurcation diagram", "connecting branches", "the same branches",
        "first post-buckling branch", "Coil (b1)", "load margin", "spin margin", "γ_v =")


@pytest.mark.parametrize("name", list(FIGURE_SETS))
def test_every_map_and_diagram_marks_the_operating_point(drawn, name):
    missing = []
    for fig, _, _, has_op in drawn[name]:
        titles = " ".join(ax.get_title() for ax in fig.axes) + " " + fig.get_suptitle()
        if any(key.lower() in titles.lower() for key in MAPS) and not has_op:
            missing.append(titles[:80])
    assert not missing, missing


def test_the_layout_check_can_fail():
    """A legend placed on the data is found; two labels on one point are found."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.plot(np.linspace(0, 1, 50), np.linspace(0, 1, 50), label="a line through the middle")
    ax.legend(loc="center")
    ax.annotate("b1", (0.5, 0.5))
    ax.annotate("b2", (0.5, 0.5))
    fig.canvas.draw()
    assert _legend_problems(fig) and _label_problems(fig)
    plt.close(fig)


def test_a_damping_map_without_a_positive_critical_load_is_not_drawn():
    """A tether unstable at any load over its damping map (critical loads 0 or not located, the undamped one 0):
    no log-log figure of it (it raised 'Data cannot be log-scaled' and ended the check with an internal error);
    one positive point is drawn."""
    from etcheck.report.figures.profiles import profile_figures

    point = {"gamma": 0.01, "damping_time_s": 2.0, "IB0_N_per_m": None, "destabilised": False}
    results = {"scene": {"load_N_per_m": 1e-4, "length_m": 100.0},
               "profiles": {"damping": {"map": [point, point | {"IB0_N_per_m": 0.0}]},
                            "undamped": {"IB0_N_per_m": 0.0, "kind": "flutter"}}}
    assert "damping_map" not in profile_figures(results)
    results["profiles"]["damping"]["map"].append(point | {"IB0_N_per_m": 3e-5})
    assert profile_figures(results)["damping_map"]
