"""Figures of a sweep report as inline images (PNG at print resolution): margin maps, critical length, 1-D margins.

Each function takes the JSON-able sweep results; axes carry units, the
mission's operating point is marked, failed points are drawn (never
interpolated over).
"""

from __future__ import annotations

import numpy as np

from etcheck.input.sweep_axes import AXES
from etcheck.report.figures.common import image as _image
from etcheck.report.figures.common import legend_below
from etcheck.report.figures.common import pyplot as _plt
from etcheck.report.sweep_files import grid_array

STABLE, UNSTABLE, BUCKLED, NOANSWER = "#d8efdd", "#f6d5d1", "#d6e4f5", "#9a9a9a"


def _axis(results: dict, k: int) -> tuple[np.ndarray, str, bool]:
    a = results["axes"][k]
    return np.asarray(a["display_values"]), f"{a['label']} [{a['unit']}]", a["spacing"] == "log"


def _operating(results: dict, k: int) -> float:
    """The mission's value of the k-th swept quantity, in display units."""
    a = results["axes"][k]
    return results["operating"][a["name"]] * AXES[a["name"]].to_display


def _log_margin(results: dict, field: str) -> np.ndarray:
    m = grid_array(results, field)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.log10(np.clip(m, 1e-6, 1e6))
    return out


def margin_map(results: dict, field: str, title: str) -> str:
    """Regions and margin contours over the two swept quantities."""
    plt = _plt()
    x, xlabel, xlog = _axis(results, 0)
    y, ylabel, ylog = _axis(results, 1)
    region = np.array(results["grid"]["region"], dtype=object)
    req = results["required_margin"]
    fig, ax = plt.subplots(figsize=(6.6, 4.3))
    _shade_regions(ax, results, field, region, x, y)
    exact = _margin_contours(ax, results, field, x, y, xlog, ylog)
    if not exact:
        ax.plot([], [], color="k", lw=2, label="stability boundary (margin 1)")
    ax.plot([], [], color="#1f4e79", lw=2.6, ls="--", label=f"required margin {req:g}")
    ax.plot([], [], color="#555555", lw=0.8, label="margin 0.1, 10, 100, 1000 (labelled)")
    if xlog:
        ax.set_xscale("log")
    if ylog:
        ax.set_yscale("log")
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(y[0], y[-1])
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    legend_below(ax, handles=_region_handles(region) + ax.get_legend_handles_labels()[0], ncol=2)
    return _image(fig)


def _shade_regions(ax, results: dict, field: str, region: np.ndarray, x: np.ndarray, y: np.ndarray) -> None:
    """Background: two regions split by the exactly located critical length where the load map has one,
    otherwise each grid point's own category colour (no invented in-between category)."""
    edge = _exact_edge(results, x) if field == "load_margin" and not (region == "buckled-stable").any() else None
    if edge is not None:
        ax.set_facecolor(UNSTABLE)
        ax.fill_betweenx(edge[1], x[0], edge[0], color=STABLE, lw=0)
        return
    from matplotlib.colors import ListedColormap

    code = np.select([region == "straight-stable", region == "buckled-stable", region == "straight-unstable"],
                     [2.0, 1.0, 0.0], np.nan)
    X, Y = np.meshgrid(x, y, indexing="ij")
    ax.pcolormesh(X, Y, code, shading="nearest", cmap=ListedColormap([UNSTABLE, BUCKLED, STABLE]), vmin=-0.5,
                  vmax=2.5)


def _margin_contours(ax, results: dict, field: str, x: np.ndarray, y: np.ndarray, xlog: bool, ylog: bool) -> bool:
    """Margin contours (0.1, 10, 100, 1000 labelled; 1 the stability boundary; the required margin), the
    points without an answer, the operating point and the exactly located critical length. Returns whether
    the boundary was drawn from the exact critical lengths (then no margin-1 contour)."""
    req = results["required_margin"]
    RX, RY, rlm = refined_log_margin(x, y, xlog, ylog, _log_margin(results, field))
    lo, hi = np.nanmin(rlm), np.nanmax(rlm)
    levels = [lv for lv in (-1, 1, 2, 3) if lo < lv < hi]
    if levels:
        cs = ax.contour(RX, RY, rlm, levels=sorted(set(levels)), colors="#555555", linewidths=0.8)
        ax.clabel(cs, fmt=lambda v: f"{10 ** v:.3g}", fontsize=7, inline=True, inline_spacing=4)
    cl = results.get("critical_length")
    exact = bool(cl) and field == "load_margin" and any(r["length_m"] is not None for r in cl)
    if lo < 0 < hi and not exact:
        ax.contour(RX, RY, rlm, levels=[0], colors="k", linewidths=2.0)
    if lo < np.log10(req) < hi:
        cs = ax.contour(RX, RY, rlm, levels=[np.log10(req)], colors="#1f4e79", linewidths=2.6, linestyles="--",
                        zorder=6)
        ax.clabel(cs, fmt=lambda v: f"required {req:g}", fontsize=8, inline=True, inline_spacing=6)
    bad = np.array(results["grid"]["status"], dtype=object) != "ok"
    if bad.any():
        X, Y = np.meshgrid(x, y, indexing="ij")
        ax.scatter(X[bad], Y[bad], marker="x", color="#8e1b10", s=22, zorder=5, label="no answer (failed / outside range)")
    if exact:
        a, b = zip(*[(r["length_m"], r["other_display"]) for r in cl if r["length_m"] is not None])
        ax.plot(a, b, "-o", ms=2.5, lw=2.0, color="k", zorder=6,
                label="stability boundary: critical length located exactly (Brent)")
    _bow_limit(ax, results, x, y)
    _mark_operating(ax, results, x, y)
    return exact


def _bow_limit(ax, results: dict, x: np.ndarray, y: np.ndarray) -> None:
    """Where the bow under the lateral Lorentz load reaches the model's limit (beyond it, away from the straight
    tether's region, the model does not describe the tether), where the grid crosses it."""
    if "bow_over_length" not in results["grid"]:
        return
    bow = grid_array(results, "bow_over_length")
    limit = results["grid"]["bow_limit"]
    if not (np.nanmin(bow) < limit < np.nanmax(bow)):
        return
    X, Y = np.meshgrid(x, y, indexing="ij")
    ax.contour(X, Y, np.log10(bow), levels=[np.log10(limit)], colors="#e67e22", linewidths=1.8, linestyles="-.",
               zorder=6)
    ax.plot([], [], color="#e67e22", lw=1.8, ls="-.",
            label=f"bow = {100 * limit:g} % of the length: past it, outside the model's validity")


def _region_handles(region: np.ndarray) -> list:
    """Legend entries of the regions present, by colour (a name written on the map would cover its contours
    and points)."""
    from matplotlib.patches import Patch

    return [Patch(color=colour, label=name) for name, colour in
            (("straight-stable", STABLE), ("buckled-stable", BUCKLED), ("straight-unstable", UNSTABLE))
            if (region == name).any()]


def _exact_edge(results: dict, x) -> tuple | None:
    """(critical length, other value) along the other axis from the exactly located critical
    lengths, with the swept ends where the tether is stable or unstable over the whole length range."""
    rows = results.get("critical_length") or []
    if not rows or any(r["length_m"] is None and r["status"] not in ("beyond range", "below range") for r in rows):
        return None
    if not any(r["length_m"] is not None for r in rows):
        return None
    lengths = [r["length_m"] if r["length_m"] is not None else (x[-1] if r["status"] == "beyond range" else x[0])
               for r in rows]
    return np.array(lengths), np.array([r["other_display"] for r in rows])


def refined_log_margin(x, y, xlog: bool, ylog: bool, lm: np.ndarray, factor: int = 6):
    """log10 margin on a grid ``factor`` times finer, for smooth contours.

    The margin field is smooth where the critical value is positive and drops
    discontinuously to 0 where the straight tether is unstable without any load
    or spin (there it is clipped to 1e-6); contouring across that jump draws the
    grid's staircase. So those points and non-finite ones are masked, the rest is
    interpolated by a cubic in the plotting coordinates (log where an axis is
    log), and refined points in a grid cell with a masked corner are masked.
    """
    from scipy.interpolate import RegularGridInterpolator

    u = np.log10(x) if xlog else np.asarray(x, dtype=float)
    v = np.log10(y) if ylog else np.asarray(y, dtype=float)
    bad = ~np.isfinite(lm) | (lm <= -5.999)
    if u.size < 4 or v.size < 4 or bad.all():
        X, Y = np.meshgrid(x, y, indexing="ij")
        return X, Y, np.where(bad, np.nan, lm)
    filled = np.where(bad, np.nanmax(np.where(bad, -np.inf, lm)), lm)
    fu, fv = np.linspace(u[0], u[-1], factor * (u.size - 1) + 1), np.linspace(v[0], v[-1], factor * (v.size - 1) + 1)
    FU, FV = np.meshgrid(fu, fv, indexing="ij")
    fine = RegularGridInterpolator((u, v), filled, method="cubic")(np.stack([FU, FV], axis=-1))
    iu = np.clip(np.searchsorted(u, fu, side="right") - 1, 0, u.size - 2)
    iv = np.clip(np.searchsorted(v, fv, side="right") - 1, 0, v.size - 2)
    cell_bad = bad[:-1, :-1] | bad[1:, :-1] | bad[:-1, 1:] | bad[1:, 1:]
    fine = np.where(cell_bad[np.ix_(iu, iv)], np.nan, fine)
    return (10.0 ** FU if xlog else FU), (10.0 ** FV if ylog else FV), fine


def _mark_operating(ax, results, x, y=None) -> None:
    ox = _operating(results, 0)
    if y is None:
        ax.axvline(ox, color="#27ae60", lw=1.5, label="mission operating point")
        return
    oy = _operating(results, 1)
    inside = x[0] <= ox <= x[-1] and y[0] <= oy <= y[-1]
    if inside:
        ax.plot([ox], [oy], marker="*", ms=13, color="#27ae60", mec="k", zorder=7, label="mission operating point")
    else:
        ax.plot([], [], " ", label=f"operating point off the map ({ox:.4g}, {oy:.4g})")


def critical_length_plot(results: dict) -> str:
    """Critical length against the other swept quantity, with the mission's length."""
    plt = _plt()
    rows = results["critical_length"]
    a = results["axes"][1]
    fig, ax = plt.subplots(figsize=(6.4, 3.0))
    pts = [(r["other_display"], r["length_m"]) for r in rows if r["length_m"] is not None]
    if pts:
        ox, oy = zip(*pts)
        ax.plot(ox, oy, "-o", ms=3, color="#1f4e79", label="critical length (straight tether loses stability)")
    below = [r["other_display"] for r in rows if r["status"] == "below range"]
    if below:
        ax.plot(below, [results["axes"][0]["start"]] * len(below), "v", color="#8e1b10", ms=4,
                label="unstable already at the shortest length swept")
    beyond = [r["other_display"] for r in rows if r["status"] == "beyond range"]
    if beyond:
        ax.plot(beyond, [results["axes"][0]["stop"]] * len(beyond), "^", color="#14632c", ms=4,
                label="stable up to the longest length swept")
    op = results["operating"]
    ax.plot([_operating(results, 1)], [op["length"]], marker="*", ms=12, color="#27ae60", mec="k",
            label="mission operating point", zorder=5)
    ax.set_yscale("log")
    if a["spacing"] == "log":
        ax.set_xscale("log")
    ax.set_xlabel(f"{a['label']} [{a['unit']}]")
    ax.set_ylabel("critical length [m]")
    fig.tight_layout()
    legend_below(ax, ncol=2)
    return _image(fig)


def margin_lines(results: dict) -> str:
    """1-D sweep: load and spin margins against the swept quantity."""
    plt = _plt()
    x, xlabel, xlog = _axis(results, 0)
    req = results["required_margin"]
    status = np.array(results["grid"]["status"], dtype=object)
    fig, ax = plt.subplots(figsize=(6.4, 3.2))
    for field, label, colour in (("load_margin", "load margin (at the point's spin)", "#1f4e79"),
                                 ("spin_margin", "spin margin (at the point's load)", "#8e44ad")):
        m = grid_array(results, field)
        m = np.where(np.isfinite(m), m, np.nan)
        if np.isfinite(m).any():
            ax.plot(x, np.clip(m, 1e-6, None), "-o", ms=2.5, color=colour, label=label)
    ax.axhline(1.0, color="k", lw=1.6, label="stability boundary (margin 1)")
    ax.axhline(req, color="#1f4e79", lw=1.2, ls="--", label=f"required margin {req:g}")
    bad = status != "ok"
    if bad.any():
        for xb in x[bad]:
            ax.axvline(xb, color=NOANSWER, lw=3, alpha=0.5)
        ax.plot([], [], color=NOANSWER, lw=3, label="no answer (failed / outside range)")
    _mark_operating(ax, results, x)
    ax.set_yscale("log")
    if xlog:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("margin = critical / operating [-]")
    fig.tight_layout()
    legend_below(ax, ncol=2)
    return _image(fig)


def sweep_figures(results: dict) -> dict[str, str]:
    if len(results["axes"]) == 1:
        return {"lines": margin_lines(results)}
    figs = {
        "load_map": margin_map(results, "load_margin", "load margin: critical I·B0 at the point's spin / I·B0"),
        "spin_map": margin_map(results, "spin_margin", "spin margin: critical spin at the point's load / spin"),
    }
    if results.get("critical_length"):
        figs["critical_length"] = critical_length_plot(results)
    return figs
