"""Figures of bifurcation diagrams and buckled shapes as inline images (PNG at print resolution, drawn once for HTML and PDF).

Stable parts of a branch are thick and solid, unstable parts thin and dashed
(when stability was computed); branch labels sit at the branch ends; special
points are marked where they were located (BP: branch point on the straight
tether, ■: secondary pitchfork, ▲: fold). A branch is drawn through its
computed states by the monotone cubic (PCHIP) in the chord length of the
figure's coordinates: the continuation's steps grow where the branch is
nearly straight in the space of states, where the figure's measures may still
bend (a polyline would show corners there).
"""

from __future__ import annotations

import functools

import numpy as np

from etcheck.numerics.pchip import Pchip
from etcheck.report.figures.common import draw, legend_below
from etcheck.report.figures.common import image as _image
from etcheck.report.figures.common import pyplot as _plt

COLOURS = ["#1f4e79", "#c0392b", "#27ae60", "#8e44ad", "#d35400", "#16a085", "#7f8c8d", "#2c3e50"]
MARKERS = {"break": ("s", "secondary pitchfork"), "fold": ("^", "fold"), "bp": ("D", "branch point")}


def segments(x, y, stable, cuts=()):
    """Split a polyline where the stability flag changes (flags None: unknown): at a special point located between
    the two states (``cuts``: the (x, y) of each), where stability changes (Kelvin-Tait-Chetaev), else at the first
    state with the new flag; the pieces share that point, so the curve is continuous."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if stable is None:
        yield x, y, None
        return
    start, head, n = 0, None, len(x)
    for i in range(1, n + 1):
        if i < n and stable[i] == stable[start]:
            continue
        xs, ys, cut = x[start:i], y[start:i], None
        if i < n:
            lo, hi = sorted((x[i - 1], x[i]))
            cut = next(((xc, yc) for xc, yc in cuts if lo <= xc <= hi), None)
            xs, ys = np.append(xs, x[i] if cut is None else cut[0]), np.append(ys, y[i] if cut is None else cut[1])
        if head is not None:
            xs, ys = np.insert(xs, 0, head[0]), np.insert(ys, 0, head[1])
        yield xs, ys, stable[start]
        head, start = cut, i


def branch_plot(d: dict, xkey: str, ykey: str, xlabel: str, ylabel: str, title: str,
                pitchfork_key: str | None = None, mark: tuple | None = None, critical: tuple | None = None) -> str:
    """Branches of a diagram; ``mark`` = (x, y, label) draws the operating point, ``critical`` =
    (x, label) the first critical load (where b1 leaves the straight tether)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    seen: set[str] = set()
    labels = []
    for n, b in enumerate(d["branches"]):
        c = COLOURS[n % len(COLOURS)]
        labels.append(_draw_branch(ax, b, xkey, ykey, c))
        seen |= draw_special_points(ax, b, xkey, ykey, seen)
        if pitchfork_key and b.get(pitchfork_key) is not None:
            ax.plot([b[pitchfork_key]], [0.0], marker="o", color=c, ms=4, ls="none")
    _draw_marks(ax, mark, critical)
    if any(b.get("stable") is not None for b in d["branches"]):
        ax.plot([], [], color="k", lw=2.2, label="stable")
        ax.plot([], [], color="k", lw=0.9, ls="--", label="unstable")
    ax.axhline(0.0, color="#888", lw=0.8)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    fig.subplots_adjust(left=0.15)  # room for signed tick labels: the figure is drawn once (no second, cropping pass)
    _spread(ax, labels)
    if ax.get_legend_handles_labels()[0]:
        legend_below(ax, ncol=3)
    return _image(fig)


#: vertical step between branch labels that would fall on one another [points]
LABEL_STEP = 9.0


def _spread(ax, labels: list) -> None:
    """Move branch labels apart where their anchors fall within a label's height of each other (several
    branches ending at one point: b1, b2 and b3 on the axis of measure₂): stacked upwards in steps of
    LABEL_STEP points, in the order drawn."""
    ax.autoscale_view()
    to_points = 72.0 / ax.figure.dpi
    placed: list[tuple[float, float]] = []
    for text in labels:
        x, y = (v * to_points for v in ax.transData.transform(text.xy))
        k = 0
        while any(abs(x - px) < 3 * LABEL_STEP and abs(y + k * LABEL_STEP - py) < LABEL_STEP for px, py in placed):
            k += 1
        text.set_position((3.0, k * LABEL_STEP))
        placed.append((x, y + k * LABEL_STEP))


#: points drawn per step between two computed states of a branch
SMOOTH = 12


def smooth(x: np.ndarray, y: np.ndarray, span: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) through the points in order, by the monotone cubic (PCHIP) of each coordinate in the chord length of
    the points scaled by ``span`` (the branch's ranges in x and y: the figure's proportions), SMOOTH points per
    step; repeated points are dropped, and fewer than three (or any not finite) are joined by straight lines."""
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        return x, y
    t = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x) / span[0], np.diff(y) / span[1]))])
    keep = np.concatenate([[True], np.diff(t) > 0])
    if keep.sum() < 3:
        return x, y
    t, x, y = t[keep], x[keep], y[keep]
    fine = np.concatenate([np.linspace(a, b, SMOOTH, endpoint=False) for a, b in zip(t[:-1], t[1:])] + [t[-1:]])
    return Pchip.through(t, x)(fine), Pchip.through(t, y)(fine)


def _draw_branch(ax, b: dict, xkey: str, ykey: str, colour: str):
    """One branch, solid where stable (or unknown) and dashed where unstable, labelled at its end (the label
    returned)."""
    x, y = np.asarray(b[xkey], dtype=float), np.asarray(b[ykey], dtype=float)
    span = (float(np.ptp(x)) or 1.0, float(np.ptp(y)) or 1.0)
    mirror = ykey == "measure2" and b.get("symmetry") is None  # connecting branches come in mirror pairs
    cuts = [(q[_SPECIAL_X[xkey]], q[ykey]) for q in b.get("special", ())
            if xkey in _SPECIAL_X and q.get(ykey) is not None]
    for xs, ys, st in segments(x, y, b.get("stable"), cuts):
        xs, ys = smooth(xs, ys, span)
        style = {"lw": 2.2, "ls": "-"} if st in (True, None) else {"lw": 0.9, "ls": "--"}
        ax.plot(xs, ys, color=colour, **style)
        if mirror:
            ax.plot(xs, -ys, color=colour, alpha=0.6, **style)
    return ax.annotate(b["label"], (x[-1], y[-1]), xytext=(3, 0), textcoords="offset points", color=colour,
                       fontsize=8, fontweight="bold")


#: x key of a branch -> key of the same abscissa in its special points
_SPECIAL_X = {"values": "B", "IB0_N_per_m": "IB0_N_per_m"}


def draw_special_points(ax, b: dict, xkey: str, ykey: str, seen: set[str]) -> set[str]:
    """The branch's special points (pitchforks, folds, branch points) where they were located (results without
    the point's own ``ykey`` measure: on the nearest computed state); each kind labelled once over the figure
    (``seen``: kinds labelled before). Returns the kinds drawn."""
    drawn = set()
    if xkey not in _SPECIAL_X:
        return drawn
    x = np.asarray(b[xkey])
    for q in b["special"]:
        marker, name = MARKERS.get(q["kind"], ("o", q["kind"]))
        xv = q[_SPECIAL_X[xkey]]
        yv = q[ykey] if q.get(ykey) is not None else b[ykey][int(np.argmin(np.abs(x - xv)))]
        ax.plot([xv], [yv], marker=marker, color="k", ms=5, ls="none",
                label=name if name not in seen | drawn else None)
        drawn.add(name)
    return drawn


def _draw_marks(ax, mark: tuple | None, critical: tuple | None) -> None:
    """The first critical load (x, label) and the operating point (x, y, label), where given."""
    if critical is not None:
        ax.axvline(critical[0], color="#c0392b", ls=":", lw=1.2)
        ax.plot([critical[0]], [0.0], marker="o", color="#c0392b", mec="k", ms=7, ls="none", zorder=6,
                label=critical[1])
    if mark is not None:
        ax.plot([mark[0]], [mark[1]], marker="*", ms=13, color="#27ae60", mec="k", ls="none", zorder=7, label=mark[2])


def shapes_plot(shapes: list[tuple[str, dict]], length_m: float | None = None) -> str:
    """A large 3-D view and the e1-e3 and e2-e3 projections of the given shapes.

    ``shapes``: (label, shape dict with s, x, y, z dimensionless, and x_m...);
    in metres when ``length_m`` is given. The 3-D box has the true proportions
    of the shapes (each side at least 40 % of the longest, so a slight coil stays visible).
    """
    from matplotlib.ticker import MaxNLocator

    plt = _plt()
    fig = plt.figure(figsize=(7.2, 4.6))
    grid = fig.add_gridspec(2, 2, width_ratios=[1.55, 1.0], hspace=0.55, wspace=0.05)
    ax3 = fig.add_subplot(grid[:, 0], projection="3d")
    ax1 = fig.add_subplot(grid[0, 1])
    ax2 = fig.add_subplot(grid[1, 1])
    unit = "m" if length_m else "L"
    suffix = "_m" if length_m else ""
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for n, (label, sh) in enumerate(shapes):
        c = COLOURS[n % len(COLOURS)]
        x, y, z = (np.asarray(sh[k + suffix], dtype=float) for k in ("x", "y", "z"))
        ax3.plot(x, y, z, color=c, lw=1.8, label=label)
        ax3.plot([x[0], x[-1]], [y[0], y[-1]], [z[0], z[-1]], "o", color="k", ms=3)
        ax1.plot(z, x, color=c, lw=1.5, label=label)
        ax2.plot(z, y, color=c, lw=1.5, label=label)
        for k, v in enumerate((x, y, z)):
            lo[k], hi[k] = min(lo[k], v.min()), max(hi[k], v.max())
    span = np.maximum(hi - lo, 1e-12)
    ax3.set_box_aspect(tuple(np.maximum(span, span.max() / 2.5)))
    for axis in (ax3.xaxis, ax3.yaxis, ax3.zaxis):
        axis.set_major_locator(MaxNLocator(4))
    ax3.tick_params(labelsize=7, pad=1)
    ax3.set_xlabel(f"e1 [{unit}]", fontsize=8, labelpad=6)
    ax3.set_ylabel(f"e2 [{unit}]", fontsize=8, labelpad=6)
    ax3.set_zlabel(f"e3 [{unit}]", fontsize=8, labelpad=8)
    ax3.set_title("3-D view (dots: the welded ends)", fontsize=8)
    ax3.view_init(elev=18, azim=-58)
    for ax, name in ((ax1, "e1"), (ax2, "e2")):
        ax.set_xlabel(f"e3, along the undeformed tether [{unit}]", fontsize=8)
        ax.set_ylabel(f"{name} [{unit}]", fontsize=8)
        ax.set_title(f"{name}–e3 projection", fontsize=8)
        ax.tick_params(labelsize=7)
    # the 3-D axes draw below their box: room for them, so that the figure is drawn once
    fig.subplots_adjust(left=0.0, right=0.98, top=0.93, bottom=0.15)
    if len(shapes) > 1:
        legend_below(ax2, ncol=1)
    return _image(fig)


def eigen_paths_plot(paths: dict, xlabel: str, title: str) -> str:
    """Real and imaginary parts of the tracked eigenvalue paths, coloured by mode type."""
    plt = _plt()
    colour = {"bend-d1": "#1f4e79", "bend-d2": "#c0392b", "torsion": "#27ae60"}
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(7.2, 2.9))
    x = np.asarray(paths["values"], dtype=float)
    re = np.array(paths["re"], dtype=float)
    im = np.array(paths["im"], dtype=float)
    seen = set()
    for j, lab in enumerate(paths["labels"]):
        c = colour.get(lab, "#555")
        name = {"bend-d1": "bending about d1", "bend-d2": "bending about d2", "torsion": "torsion"}.get(lab, lab)
        a1.plot(x, re[:, j], color=c, lw=1.2, label=name if lab not in seen else None)
        a2.plot(x, im[:, j], color=c, lw=1.2)
        seen.add(lab)
    a1.axhline(0.0, color="k", lw=0.8)
    a1.set_ylabel("Re λ (growth rate, units of ω_ref)")
    a2.set_ylabel("Im λ (frequency, units of ω_ref)")
    for ax in (a1, a2):
        ax.set_xlabel(xlabel)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    legend_below(a1, ncol=3)
    return _image(fig)


def diagram_figures(d: dict, length_m: float, operating: dict | None = None) -> dict[str, str]:
    """The diagram report's figures by name, drawn two at a time in the report process (:func:`draw`);
    ``operating`` (B, IB0_N_per_m, label): the mission's operating load, marked on the straight tether."""
    def mark(key: str):
        return None if operating is None else (operating[key], 0.0, operating["label"])

    jobs = {
        "measure1": lambda: {"measure1": branch_plot(d, "values", "measure1", "B (dimensionless load)",
                                                     r"measure$_1 = \int_0^1 |x^0(s)|\,ds$",
                                                     "bifurcation diagram (cf. arXiv:0810.3668 Fig. 5)",
                                                     "pitchfork_B", mark=mark("B"))},
        "measure2": lambda: {"measure2": branch_plot(d, "values", "measure2", "B (dimensionless load)",
                                                     r"measure$_2 = \int_0^1 x^0 y^0\,ds$",
                                                     "connecting branches come in mirror pairs "
                                                     "(cf. arXiv:0810.3668 Fig. 6)", "pitchfork_B", mark=mark("B"))},
        "physical": lambda: {"physical": branch_plot(d, "IB0_N_per_m", "max_deflection_m", "I·B0 [N/m]",
                                                     "maximum lateral deflection [m]",
                                                     "the same branches in physical units", "pitchfork_IB0_N_per_m",
                                                     mark=mark("IB0_N_per_m"))},
    }
    for b in d["branches"]:
        if b.get("eigenvalue_paths"):
            jobs[f"paths_{b['label']}"] = functools.partial(_paths_figure, b)
    key = next((k for b in d["branches"] for k in b["shapes"] if k.startswith("measure1=")), None)
    chosen = [(f"{b['label']} (B = {b['shapes'][key]['B']:.4g})", b["shapes"][key])
              for b in d["branches"] if key in b["shapes"]]
    if chosen:
        jobs["shapes"] = lambda: {"shapes": shapes_plot(chosen, length_m)}
    return draw(jobs)


def _paths_figure(b: dict) -> dict[str, str]:
    """The eigenvalue paths of branch ``b`` (the paper's Figs. 9 and 10 for b1 and b12; any branch whose paths
    were computed)."""
    p = b["eigenvalue_paths"]
    return {f"paths_{b['label']}": eigen_paths_plot(
        p, "B (dimensionless load)", f"lowest eigenvalues along {b['label']} (γ = {p['gamma']:.4g})")}


def damping_maps(r: dict) -> str:
    """Damping ratio of b1's least-damped mode over (B, omega), one panel per damping (cf. arXiv:0810.3668 Fig. 19)."""
    plt = _plt()
    from matplotlib.colors import LogNorm

    s = r["study"]
    B, w = np.asarray(s["B"]), np.asarray(s["omega"])
    zeta = np.array(s["damping_ratio"], dtype=float)
    n = len(s["gammas"])
    cols = min(3, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(2.5 * cols + 0.8, 2.3 * rows + 0.3), squeeze=False,
                             sharex=True, sharey=True)
    finite = zeta[np.isfinite(zeta) & (zeta > 0)]
    norm = LogNorm(vmin=max(finite.min(), 1e-5), vmax=finite.max()) if finite.size else None
    star = np.array([np.nan if v is None else v for v in s["secondary_pitchfork_B"]], dtype=float)
    prim = np.array([np.nan if v is None else v for v in s["primary_pitchfork_B"]], dtype=float)
    mesh = None
    for k, ax in enumerate(axes.ravel()):
        if k >= n:
            ax.set_visible(False)
            continue
        z = np.ma.masked_invalid(np.where(zeta[k] > 0, zeta[k], np.nan))
        if z.count():
            mesh = ax.pcolormesh(B, w, z, norm=norm, cmap="viridis", shading="nearest")
        bad = np.nan_to_num(np.array(s["max_real"], dtype=float)[k], nan=-1.0) > 0
        if bad.any():
            W, BB = np.meshgrid(w, B, indexing="ij")
            ax.plot(BB[bad], W[bad], "x", color="#c0392b", ms=4)
        ax.plot(star, w, color="k", lw=2, label="secondary pitchfork B*(ω)")
        ax.plot(prim, w, color="#888", lw=1.2, ls="--", label="b1 pitchfork (straight tether)")
        op = r["operating"]
        if 0.0 <= op["B"] <= B[-1] and w[0] <= op["omega"] <= w[-1]:  # the axes run from B = 0
            ax.plot([op["B"]], [op["omega"]], marker="*", color="#27ae60", mec="k", ms=10, ls="none", clip_on=False,
                    zorder=6, label="mission operating point")
        ax.set_title(f"γ = {s['gammas'][k]:g} (γ_v = {s['damping_time_s'][k]:.3g} s)", fontsize=8)
        ax.set_xlim(0, B[-1])
        ax.set_ylim(w[0], w[-1])
        if k % cols == 0:
            ax.set_ylabel("spin ω (dimensionless)")
        if k >= n - cols:
            ax.set_xlabel("load B (dimensionless)")
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7, loc="lower center", ncol=3, bbox_to_anchor=(0.45, -0.04))
    if mesh is not None:
        fig.colorbar(mesh, ax=axes.ravel().tolist(), label="damping ratio ζ of the least-damped mode", shrink=0.9)
    return _image(fig)
