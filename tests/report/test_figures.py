"""Figures are drawn once as opaque PNGs at print resolution, cropped like matplotlib's tight bounding box."""

from __future__ import annotations

import base64
import io
import re

import numpy as np
import pytest

from etcheck.report.figures.common import PAD_INCH, PRINT_DPI, image, pyplot

PIL = pytest.importorskip("PIL.Image")


def _decoded(fig_html: str):
    data = re.fullmatch(r'<img src="data:image/png;base64,([^"]+)" width="(\d+)" height="(\d+)" alt="">', fig_html)
    assert data, fig_html[:80]
    img = PIL.open(io.BytesIO(base64.b64decode(data.group(1))))
    assert img.size == (int(data.group(2)), int(data.group(3)))
    return img


def _figure(legend_below: bool):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    ax.plot([0, 1], [0, 1], label="a line")
    ax.set_xlabel("x [m]")
    if legend_below:
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.5))
    else:
        fig.tight_layout()  # everything inside the canvas: cropped from the one drawing
    return image(fig)


def test_a_figure_is_cropped_to_its_content_with_a_white_border():
    out = _figure(legend_below=False)
    img = _decoded(out)
    assert out.png and img.format == "PNG" and img.mode == "RGB"  # no alpha mask for the PDF writer
    w, h = img.size
    assert w < 4.0 * PRINT_DPI and h < 3.0 * PRINT_DPI  # the canvas's empty margins are cut away
    pixels = np.asarray(img)
    pad = round(PAD_INCH * PRINT_DPI) // 2  # line widths may reach past the layout boxes by a few pixels
    for border in (pixels[:pad], pixels[-pad:], pixels[:, :pad], pixels[:, -pad:]):
        assert border.min() == 255  # the white border around the content
    assert pixels[pad:-pad, pad:-pad].min() < 100  # ink inside it


def test_content_beyond_the_canvas_is_kept():
    img = _decoded(_figure(legend_below=True))
    assert img.size[1] > 3.0 * PRINT_DPI  # the legend below the axes grew the picture past the 3-inch canvas
    assert np.asarray(img)[-round(0.6 * PRINT_DPI):].min() < 100  # and its text is drawn


def test_coil_region_without_any_secondary_pitchfork_is_drawn():
    """Found by the scene-space exploration: b1 with no secondary pitchfork at any drawn spin (R near 1,
    strong load) made the coil-region figure index an empty curve (internal error, no report)."""
    from etcheck.report.figures.check import coil_region_plot

    rows = [{"spin_rpm": w, "pitchfork_IB0_N_per_m": 5.2e-5, "secondary_IB0_N_per_m": None} for w in (0.0, 1e-4, 2e-4)]
    results = {"scene": {"load_N_per_m": 9.1e-5, "tension_N": 0.0232},
               "postbuckling": {"region": {
                   "rows": rows, "operating_rpm": 1.7e-4, "liftoff_rpm": None,
                   "pitchfork_curve": {"spin_rpm": [0.0, 1e-4, 2e-4, 3e-4], "IB0_N_per_m": [5.2e-5] * 4},
                   "secondary_curve": {"spin_rpm": [], "IB0_N_per_m": []}}}}
    out = coil_region_plot(results)
    assert out.startswith("<img") or "base64" in out


def test_spin_margin_curve_of_the_damped_map_follows_the_exact_rows():
    """The critical spin at each load is interpolated between the spin rows' exact stability boundaries,
    not read off as the first unstable row (a staircase of one row's height); none where buckled at rest."""
    from etcheck.report.figures.check import shade_rows

    rpm = np.linspace(0.0, 1.0, 11)  # rows 0.1 rpm apart; stable for load < 1 - rpm^2
    rows = [{"spin_rpm": float(w), "IB0_N_per_m": [[0.0, 1.0 - w**2]] if w < 1.0 else []} for w in rpm]
    plt = pyplot()
    fig, ax = plt.subplots()
    _, _, cols, w_col = shade_rows(ax, rows, np.linspace(0.0, 1.2, 50))
    plt.close(fig)
    inside = (cols > 0.05) & (cols < 0.95)
    exact = np.sqrt(1.0 - cols[inside])
    assert np.max(np.abs(w_col[inside] - exact)) < 0.02  # a staircase is off by up to a row, 0.1
    assert np.all(np.isinf(w_col[cols > 1.0]))  # buckled at rest: no spin margin to draw


@pytest.mark.parametrize("lin, shaded", [
    # damped (no windows scanned): unstable only above the critical spin (the whole axis was shaded)
    ({"spin_windows": [], "spin_windows_scanned_to_rpm": None,
      "critical_spin": {"kind": "divergence", "rpm": 0.31}}, [(0.31, 0.5)]),
    # undamped, windows scanned: unstable between and past them
    ({"spin_windows": [{"rpm": [0.0, 0.2]}, {"rpm": [0.3, 0.4]}], "spin_windows_scanned_to_rpm": 0.5,
      "critical_spin": {"kind": "flutter", "rpm": 0.2}}, [(0.2, 0.3), (0.4, 0.5)]),
    ({"spin_windows": [], "spin_windows_scanned_to_rpm": None,
      "critical_spin": {"kind": "never", "rpm": None}}, []),
    ({"spin_windows": [], "spin_windows_scanned_to_rpm": None,
      "critical_spin": {"kind": "unstable at start", "rpm": 0.0}}, [(0.0, 0.5)]),
    ({"spin_windows": [], "spin_windows_scanned_to_rpm": None,
      "critical_spin": {"kind": "not located", "rpm": None}}, []),
])
def test_campbell_shades_the_unstable_spins_the_report_states(lin, shaded):
    """The Campbell diagram's shading agrees with the report's 'stable spin ranges' sentence."""
    from etcheck.report.figures.check import shade_unstable_spin

    spans = []

    class Axes:
        def axvspan(self, a, b, **kw):
            spans.append((a, b))

    shade_unstable_spin(Axes(), lin, np.linspace(0.0, 0.5, 11))
    assert spans == shaded


@pytest.mark.parametrize(("ykey", "own"), [("measure1", 0.123), ("measure2", -0.004), ("max_deflection_m", 7.5)])
def test_a_special_point_is_marked_where_it_was_located_not_on_the_nearest_state(ykey, own):
    """A fold between two computed states far apart is marked at its own measure (the located state's); results
    without that measure (written before it was recorded) fall back to the nearest computed state."""
    from etcheck.report.figures.diagram import draw_special_points

    b = {"values": [0.5, 0.9], "IB0_N_per_m": [1.0, 1.8], ykey: [0.0, 1.0],
         "special": [{"kind": "fold", "B": 0.6, "IB0_N_per_m": 1.2, ykey: own}]}
    plt = pyplot()
    for key in ("values", "IB0_N_per_m"):
        fig, ax = plt.subplots()
        assert draw_special_points(ax, b, key, ykey, set()) == {"fold"}
        assert list(ax.lines[-1].get_xdata()) == [b["special"][0][{"values": "B"}.get(key, key)]]
        assert list(ax.lines[-1].get_ydata()) == [own]
        old = {**b, "special": [{k: v for k, v in b["special"][0].items() if k != ykey}]}
        draw_special_points(ax, old, key, ykey, set())
        assert list(ax.lines[-1].get_ydata()) == [0.0]  # the nearest state's
        plt.close(fig)


def test_a_branch_is_drawn_through_its_computed_states_without_overshoot():
    """The drawn curve passes through every computed state, and between two states it stays within their range
    (monotone cubic: no bumps the branch does not have), here a quarter circle sampled at five points."""
    from etcheck.report.figures.diagram import SMOOTH, smooth

    a = np.linspace(0.0, np.pi / 2, 5)
    x, y = np.cos(a), np.sin(a)
    xs, ys = smooth(x, y, (1.0, 1.0))
    assert xs.size == SMOOTH * 4 + 1
    np.testing.assert_allclose(xs[::SMOOTH], x, atol=1e-15)
    np.testing.assert_allclose(ys[::SMOOTH], y, atol=1e-15)
    for k in range(4):
        seg = slice(k * SMOOTH, (k + 1) * SMOOTH + 1)
        assert np.all(np.diff(xs[seg]) <= 1e-15) and np.all(np.diff(ys[seg]) >= -1e-15)
    # closer to the circle than the polyline through the same states
    assert np.max(np.abs(np.hypot(xs, ys) - 1.0)) < 0.5 * (1.0 - np.cos(np.pi / 16))  # measured: 0.26 of it
    two = smooth(np.array([0.0, 1.0]), np.array([0.0, 2.0]), (1.0, 2.0))
    assert [list(v) for v in two] == [[0.0, 1.0], [0.0, 2.0]]


def test_stable_and_unstable_parts_meet_at_the_located_special_point():
    """Stability changes at a located special point (a secondary pitchfork): the solid and dashed parts of a branch
    meet there, not at the first computed state past it; without one they meet at that state."""
    from etcheck.report.figures.diagram import segments

    x, y, st = [0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 2.0, 3.0], [True, True, False, False]
    (xa, ya, sa), (xb, yb, sb) = segments(x, y, st, [(1.4, 1.5)])
    assert (sa, sb) == (True, False) and list(xa) == [0.0, 1.0, 1.4] and list(xb) == [1.4, 2.0, 3.0]
    assert ya[-1] == yb[0] == 1.5
    (xa, _, _), (xb, _, _) = segments(x, y, st)
    assert list(xa) == [0.0, 1.0, 2.0] and list(xb) == [2.0, 3.0]
