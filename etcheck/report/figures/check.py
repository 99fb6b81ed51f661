"""Report figures of the check (matplotlib, imported lazily), each drawn once as a PNG.

Every function takes the JSON-able results and returns the figure as an inline
``<img>`` (:func:`etcheck.report.figures.common.image`); axes are labelled with
units and the operating point is marked. Labels are plain Unicode (β₁, χ, √):
matplotlib's TeX parser would cost a third of a second per process.
"""

from __future__ import annotations

import math

from etcheck.report.figures.common import draw, legend_below
from etcheck.report.figures.common import image as _image
from etcheck.report.figures.common import pyplot as _plt
from etcheck.report.figures.diagram import branch_plot, shapes_plot

#: The paper's attachment as the results name it: the one whose characteristic function is chi of eq. (91).
PAPER_ENDS = ["welded", "welded"]


def _ends(results: dict) -> tuple[list[str], str]:
    """The tether's ends [lower, upper] as the results name them, and their description."""
    att = results["attachment"]
    return att["ends"], att["described"]


def chi_plot(results: dict) -> str:
    """chi(beta) e^{-sqrt3 beta} (or its analogue for other ends) with the critical betas and the operating beta."""
    plt = _plt()
    sr = results["straight_rod"]
    ends, described = _ends(results)
    welded = ends == PAPER_ENDS
    beta = sr["chi_curve"]["beta"]
    chi = sr["chi_curve"]["chi_scaled"]
    op = sr["operating_beta"]
    fig, ax = plt.subplots(figsize=(5.7, 2.8))
    ax.plot(beta, chi, color="#1f4e79", lw=1.4, label="χ(β) exp(−√3 β) (arXiv:0810.3668 eq. (91))" if welded
            else "2 g(β)² (its closed-form analogue for these ends)")
    for i, load in enumerate(sr["critical_loads"]):
        if load["beta"] <= beta[-1] and (i < 3 or op > beta[-1]):
            ax.axvline(load["beta"], color="#c0392b", ls=":", lw=1,
                       label="double zeros βₖ (buckling loads)" if i == 0 else None)
            ax.annotate(f"β{_subscript(load['k'])}", (load["beta"], 0.0),
                        xytext=(3, 28), textcoords="offset points", fontsize=7, color="#c0392b")
    top = max(chi) * 1.05
    if op <= beta[-1]:
        ax.axvline(op, color="#27ae60", lw=2, label=f"operating β = {op:.4g}")
    else:
        ax.plot([beta[-1]], [0.0], marker=">", color="#27ae60", ms=9, mec="k", clip_on=False, zorder=6, ls="none",
                label=f"operating β = {op:.4g} (off scale, to the right)")
    ax.set_xlim(0, beta[-1])
    ax.set_ylim(-0.05 * top, top)
    ax.set_xlabel("β = ∛(f B / √R)  (dimensionless)")
    ax.set_ylabel("scaled χ (dimensionless)")
    ax.set_title("Characteristic function of the straight welded tether (ω = 0, T = 0)" if welded else
                 f"Characteristic function of the straight tether, {described.split(' (')[0]} (ω = 0, T = 0)",
                 fontsize=9)
    fig.tight_layout()
    legend_below(ax, ncol=2)
    return _image(fig)


def _subscript(k: int) -> str:
    """``k`` in Unicode subscript digits (β₁, β₁₂)."""
    return str(k).translate(str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉"))


def mode_plot(results: dict) -> str:
    """First static buckling mode: deflections x(s), y(s) along the tether [m]."""
    plt = _plt()
    sr = results["straight_rod"]
    length = results["scene"]["length_m"]
    s = [v * length for v in sr["first_mode"]["s"]]
    x, y = sr["first_mode"]["x"], sr["first_mode"]["y"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(6.6, 2.6), gridspec_kw={"width_ratios": [2.2, 1]})
    ax1.plot(s, x, color="#1f4e79", label="x (along d₁, weak-axis bending)")
    ax1.plot(s, y, color="#e67e22", ls="--", label="y (along d₂)")
    ax1.set_xlabel("arclength s [m]")
    ax1.set_ylabel("deflection / max (–)")
    ax1.set_title("First buckling mode (one of a double pair)", fontsize=9)
    ax2.plot(x, y, color="#7d3c98")
    ends, _ = _ends(results)
    ax2.plot([0], [0], "ko", ms=3, label="welded ends" if ends == PAPER_ENDS else
             "ends (" + ", ".join(dict.fromkeys(ends)) + ")")
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_xlabel("x / max (–)")
    ax2.set_ylabel("y / max (–)")
    ax2.set_title("End view (coil)", fontsize=9)
    fig.tight_layout()
    legend_below(ax1, ncol=2)
    legend_below(ax2, ncol=1)
    return _image(fig)


def _first_crossing(x, g, threshold):
    """First x where g rises above threshold (linear interpolation); 0 if
    unstable at x[0], inf if never."""
    if g[0] > threshold:
        return 0.0
    for i in range(1, len(x)):
        if g[i] > threshold:
            t = (threshold - g[i - 1]) / (g[i] - g[i - 1])
            return x[i - 1] + t * (x[i] - x[i - 1])
    return math.inf


def campbell_plot(results: dict) -> str:
    """Campbell diagram (frequency vs spin) and growth rates vs spin, SI units."""
    import numpy as np

    plt = _plt()
    lin = results["linear"]
    cd = lin["campbell"]
    rpm = np.array(cd["spin_rpm"])
    freq = np.array(cd["frequency_Hz"], dtype=float)
    grow = np.array(cd["growth_rate_per_s"], dtype=float)
    thr = lin["threshold"] * results["scales"]["reference_frequency_rad_s"]
    op = lin["operating"]["spin_rpm"]
    crit = lin["critical_spin"]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.6, 5.4), sharex=True, gridspec_kw={"height_ratios": [1.5, 1]})
    X = np.repeat(rpm[:, None], freq.shape[1], axis=1)
    unstable = grow > thr
    ax1.scatter(X[~unstable], freq[~unstable], s=6, color="#1f4e79", label="stable mode")
    ax1.scatter(X[unstable], freq[unstable], s=9, color="#c0392b", marker="x", label="growing mode (Re λ > 0)")
    ax2.scatter(X[~unstable], grow[~unstable], s=6, color="#1f4e79")
    ax2.scatter(X[unstable], grow[unstable], s=9, color="#c0392b", marker="x")
    shade_unstable_spin(ax1, lin, rpm, "unstable spin range")
    shade_unstable_spin(ax2, lin, rpm)
    for ax in (ax1, ax2):
        ax.axvline(op, color="#27ae60", lw=2, label=f"operating spin {op:.3g} rpm" if ax is ax1 else None)
        if crit["rpm"] is not None and crit["kind"] in ("divergence", "flutter"):
            ax.axvline(crit["rpm"], color="#c0392b", ls="--", lw=1.2,
                       label=f"critical spin {crit['rpm']:.4g} rpm ({crit['kind']})" if ax is ax1 else None)
    ax2.axhline(0, color="k", lw=0.8)
    ax1.set_ylabel("frequency |Im λ| [Hz]")
    ax2.set_ylabel("growth rate Re λ [1/s]")
    ax2.set_xlabel("spin rate [rpm]")
    ax1.set_title(f"Campbell diagram of the straight tether at the operating load\n"
                  f"(I·B0 = {lin['operating']['IB0_N_per_m']:.3g} N/m, rotating frame)", fontsize=9)
    ax1.set_xlim(rpm[0], rpm[-1])
    fig.tight_layout()
    handles, _ = ax1.get_legend_handles_labels()
    legend_below(ax2, handles=handles, ncol=3)
    return _image(fig)


def _stable_spin_ranges(lin) -> list[tuple[float, float]] | None:
    """The stable spin ranges [rpm] at the operating load, as the report states them: the scanned windows
    (undamped), else 0 up to the critical spin (with damping no window opens above it); None where unknown."""
    if lin.get("spin_windows_scanned_to_rpm") is not None:
        return [tuple(w["rpm"]) for w in lin["spin_windows"]]
    crit = lin["critical_spin"]
    if crit["kind"] == "never":
        return [(0.0, math.inf)]
    if crit["kind"] == "unstable at start":
        return []
    return None if crit["rpm"] is None else [(0.0, crit["rpm"])]


def shade_unstable_spin(ax, lin, rpm, label=None):
    """Shade the spin ranges where the straight tether is unstable at the operating load (nothing where they
    are not known)."""
    stable = _stable_spin_ranges(lin)
    if stable is None:
        return
    gaps, start = [], rpm[0]
    for a, b in stable:
        if a > start:
            gaps.append((start, a))
        start = max(start, b)
    if start < rpm[-1]:
        gaps.append((start, rpm[-1]))
    for i, (a, b) in enumerate(gaps):
        ax.axvspan(a, b, color="#c0392b", alpha=0.08, lw=0, label=label if i == 0 else None)


def stability_map_plot(results: dict) -> str:
    """Stability of the straight tether in the (I·B0, spin rate) plane."""
    import numpy as np
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    plt = _plt()
    lin = results["linear"]
    sm = lin["stability_map"]
    load = np.array(sm["IB0_N_per_m"])
    rpm = np.array(sm["spin_rpm"])
    required = results["mission"]["check"]["required_margin"]
    fig, ax = plt.subplots(figsize=(6.6, 4.4))
    ax.set_facecolor("#f6d5d1")
    if sm["stable_rows"]:
        b_row, rows_rpm, cols, w_col = shade_rows(ax, sm["stable_rows"], load)
        boundary = Line2D([], [], color="#1b1b1b", lw=1.4,
                          label="first loss of stability along the load (rung 1v)" if lin["route"] == "profiles"
                          else "stability boundary (exact, cut at static points)")
    else:
        b_row, rows_rpm, cols, w_col = _shade_grid(ax, load, rpm, np.array(sm["max_growth"]), lin["threshold"])
        boundary = Line2D([], [], color="#1b1b1b", lw=1.4, label="stability boundary (grid)")
    sp = sm["static_points"]
    ax.plot(sp["IB0_N_per_m"], sp["spin_rpm"], ".", color="#444444", ms=1.6)
    # required-margin curves: I·B0 = critical(spin) / m and spin = critical(I·B0) / m
    ok = np.isfinite(b_row)
    ax.plot(b_row[ok] / required, rows_rpm[ok], color="#1f4e79", ls="--", lw=1.2)
    ok = np.isfinite(w_col)
    ax.plot(cols[ok], w_col[ok] / required, color="#7d3c98", ls=":", lw=1.4)
    op = lin["operating"]
    ax.plot(op["IB0_N_per_m"], op["spin_rpm"], marker="*", color="#27ae60", ms=14, mec="k", zorder=5)
    cl, cs = lin["critical_load"], lin["critical_spin"]
    if cl["IB0_N_per_m"] is not None and cl["kind"] in ("divergence", "flutter"):
        ax.plot(cl["IB0_N_per_m"], op["spin_rpm"], marker="o", color="#c0392b", ms=6, zorder=5)
    if cs["rpm"] is not None and cs["kind"] in ("divergence", "flutter"):
        ax.plot(op["IB0_N_per_m"], cs["rpm"], marker="s", color="#c0392b", ms=6, zorder=5)
    handles = [
        Patch(color="#d5efdc", label="stable straight tether"),
        Patch(color="#f6d5d1", label="unstable (buckled, whirling or fluttering)" if lin["route"] == "profiles"
              else "unstable (buckled or whirling)"),
        boundary,
        *([Line2D([], [], marker=".", color="#444444", ls="", label="static (divergence) curves")]
          if sp["IB0_N_per_m"] else []),
        Line2D([], [], color="#1f4e79", ls="--", label=f"load margin = {required:g}"),
        Line2D([], [], color="#7d3c98", ls=":", lw=1.4, label=f"spin margin = {required:g}"),
        Line2D([], [], marker="*", color="#27ae60", mec="k", ms=12, ls="", label="operating point"),
        Line2D([], [], marker="o", color="#c0392b", ls="", label="critical load at operating spin"),
        Line2D([], [], marker="s", color="#c0392b", ls="", label="critical spin at operating load"),
    ]
    ax.set_xlabel("magnetic load I·B0 [N/m]")
    ax.set_ylabel("spin rate [rpm]")
    ax.ticklabel_format(style="sci", scilimits=(-3, 4), useMathText=True)  # a tape's 1e-4 N/m: "×10⁻⁴", not
    ax.set_xlim(load[0], load[-1])  # eight-digit tick labels running into each other
    ax.set_ylim(rpm[0], rpm[-1])
    if lin["route"] == "profiles":  # at the damping the verdict uses, the tension along the tether
        state = (f"profiles along it, smallest T = {results['scene']['tension_N']:.3g} N, "
                 f"γ = {results['profiles']['damping']['gamma']:.3g}")
    else:
        state = f"T = {results['scene']['tension_N']:.3g} N, γ = {results['scaled']['gamma']:.3g}"
    ax.set_title(f"Safe operating region of the straight tether ({state})", fontsize=9)
    fig.tight_layout()
    legend_below(ax, handles=handles, ncol=3)
    return _image(fig)


def shade_rows(ax, rows, load):
    """Damped map: exact stable intervals per spin row, drawn as bands (one collection of rectangles)."""
    import numpy as np
    from matplotlib.collections import PolyCollection

    rpm = np.array([r["spin_rpm"] for r in rows])
    h = (rpm[1] - rpm[0]) if rpm.size > 1 else 1.0
    edge_x, edge_y, bands = [], [], []
    b_row = np.full(rpm.size, np.inf)
    for i, r in enumerate(rows):
        y0, y1 = max(rpm[i] - h / 2, rpm[0]), min(rpm[i] + h / 2, rpm[-1])
        bands += [((a, y0), (b, y0), (b, y1), (a, y1)) for a, b in r["IB0_N_per_m"]]
        first = r["IB0_N_per_m"][0] if r["IB0_N_per_m"] else None
        b_row[i] = first[1] if first and first[0] == 0.0 else 0.0
        if first and first[0] == 0.0 and first[1] < load[-1]:
            edge_x.append(first[1])
            edge_y.append(rpm[i])
    ax.add_collection(PolyCollection(bands, facecolors="#d5efdc", edgecolors="none", linewidths=0),
                      autolim=False)
    ax.plot(edge_x, edge_y, color="#1b1b1b", lw=1.4)
    # first spin row at which each load is no longer stable
    cols = np.linspace(load[0], load[-1], 200)
    stable = np.zeros((len(rows), cols.size), dtype=bool)
    for i, r in enumerate(rows):
        for a, b in r["IB0_N_per_m"]:
            stable[i] |= (a <= cols) & (cols <= b)
    unstable = ~stable
    # critical spin of each column: between the last stable row and the first unstable one, where the rows'
    # exact boundaries (the end of their first stable interval) pass the column's load (linear in between)
    first = unstable.argmax(axis=0)
    w_col = np.where(unstable.any(axis=0) & (first > 0), rpm[first], np.inf)  # none drawn where buckled at rest
    for j in np.nonzero(unstable.any(axis=0) & (first > 0))[0]:
        i = first[j]
        b0, b1 = b_row[i - 1], b_row[i]
        if np.isfinite(b0) and b0 > b1:
            t = min(max((b0 - cols[j]) / (b0 - b1), 0.0), 1.0)
            w_col[j] = rpm[i - 1] + t * (rpm[i] - rpm[i - 1])
    return b_row, rpm, cols, w_col


def _shade_grid(ax, load, rpm, g, thr):
    """Undamped map: sampled growth rate, boundary interpolated between samples."""
    import numpy as np
    from matplotlib.colors import ListedColormap

    top = max(float(np.max(g)), thr) + 1.0
    ax.contourf(load, rpm, g, levels=[float(np.min(g)) - 1.0, thr, top], cmap=ListedColormap(["#d5efdc", "#f6d5d1"]))
    ax.contour(load, rpm, g - thr, levels=[0.0], colors="#1b1b1b", linewidths=1.4)
    b_row = np.array([_first_crossing(load, row, thr) for row in g])
    w_col = np.array([_first_crossing(rpm, col, thr) for col in g.T])
    return b_row, rpm, load, w_col


def postbuckling_plots(results: dict) -> dict[str, str]:
    """b1 in physical units with the operating point, and the buckled shape at the operating load."""
    post = results["postbuckling"]
    d = post["diagram"]
    op = post.get("operating")
    out = {"b1": branch_plot(d, "IB0_N_per_m", "max_deflection_m", "I·B0 [N/m]", "maximum lateral deflection [m]",
                             "first post-buckling branch b1 at the operating spin and tension",
                             "pitchfork_IB0_N_per_m", mark=_operating_mark(results, op),
                             critical=_critical_mark(results))}
    if post.get("region"):
        out["region"] = coil_region_plot(results)
    if op and op.get("available"):
        out["shape"] = shapes_plot([(f"b1 at I·B0 = {results['scene']['load_N_per_m']:.3g} N/m", op["shape"])],
                                   results["scales"]["length_m"])
    return out


def coil_region_plot(results: dict) -> str:
    """Stable region of the coiled tether (b1) in the (spin rate, I·B0) plane at the mission's tension.

    Lower edge: b1's pitchfork, located exactly at every drawn spin; upper edge:
    the secondary pitchfork, located exactly at the marked spins and drawn
    between them by the monotone cubic (PCHIP) interpolant.
    """
    import numpy as np

    plt = _plt()
    reg = results["postbuckling"]["region"]
    rows = reg["rows"]
    load = results["scene"]["load_N_per_m"]
    fig, ax = plt.subplots(figsize=(6.6, 3.8))
    if "pitchfork_curve" in reg:
        pc, sc = reg["pitchfork_curve"], reg["secondary_curve"]
        low_w = np.array(pc["spin_rpm"], dtype=float)
        low = np.array([v if v is not None else 0.0 for v in pc["IB0_N_per_m"]], dtype=float)
        top_w, top = np.array(sc["spin_rpm"], dtype=float), np.array(sc["IB0_N_per_m"], dtype=float)
    else:  # results without the stored curves (an older results file): the located rows only
        low_w = top_w = np.array([r["spin_rpm"] for r in rows], dtype=float)
        low = np.array([r["pitchfork_IB0_N_per_m"] or 0.0 for r in rows], dtype=float)
        top = np.array([r["secondary_IB0_N_per_m"] if r["secondary_IB0_N_per_m"] is not None else np.nan
                        for r in rows], dtype=float)
    ax.fill_between(low_w, 0.0, low, color="#d8efdd", lw=0, label="straight tether stable")
    if top_w.size:
        ax.fill_between(top_w, np.interp(top_w, low_w, low), top, color="#d6e4f5", lw=0,
                        label="coiled tether (b1) stable")
    ax.plot(low_w, low, "-", color="#555", lw=1.4, label="b1 leaves the straight tether (first critical load)")
    if top_w.size:
        ax.plot(top_w, top, "-", color="k", lw=2, label="secondary pitchfork of b1 (the coil loses stability)")
    else:
        ax.plot([], [], " ", label="no secondary pitchfork of b1 located at any drawn spin (see the table)")
    located = [(r["spin_rpm"], r["secondary_IB0_N_per_m"]) for r in rows if r["secondary_IB0_N_per_m"] is not None]
    if located:
        ax.plot(*zip(*located), "s", color="k", ms=4, ls="none", label="secondary pitchfork located exactly")
    w_end = max(top_w[-1] if top_w.size else 0.0, low_w[-1] if low_w.size else 0.0, reg["operating_rpm"]) or 1.0
    if reg.get("liftoff_rpm") is not None and reg["liftoff_rpm"] <= w_end:
        ax.axvline(reg["liftoff_rpm"], color="#888", ls=":", label="b1 lift-off (the straight tether whirls above)")
    ax.plot([reg["operating_rpm"]], [load], marker="*", ms=14, color="#27ae60", mec="k", ls="none", zorder=6,
            label="operating point", clip_on=False)
    ax.set_xlim(0.0, w_end)
    ax.set_ylim(0, 1.08 * max([v for v in (*top, *low) if np.isfinite(v)] + [load]))
    ax.set_xlabel("spin rate [rpm]")
    ax.set_ylabel("magnetic load I·B0 [N/m]")
    ax.set_title(f"Coil (b1): where the coiled tether is stable (T = {results['scene']['tension_N']:.3g} N; "
                 "independent of the damping)", fontsize=9)
    fig.tight_layout()
    legend_below(ax, ncol=2)
    return _image(fig)


def _critical_mark(results: dict):
    """The first critical load of the straight tether at the operating spin and tension (where b1 starts)."""
    post = results["postbuckling"]
    b1 = next((b for b in post["diagram"]["branches"] if b["label"] == "b1"), None)
    x = b1.get("pitchfork_IB0_N_per_m") if b1 else None
    if x is None:
        x = post["B_c"] * results["scales"]["load_N_per_m"]
    return (x, f"first critical load, I·B0 = {x:.4g} N/m")


def _operating_mark(results: dict, op: dict | None):
    load = results["scene"]["load_N_per_m"]
    if op and op.get("available"):
        return (load, op["max_deflection_m"], "operating point (buckled)")
    return (load, 0.0, "operating point (straight)")


def figures(results: dict) -> dict[str, str]:
    """All figures the report shows, keyed by name (drawn by :func:`~etcheck.report.figures.common.draw`)."""
    jobs = {"chi": lambda: {"chi": chi_plot(results)}, "mode": lambda: {"mode": mode_plot(results)}}
    lin = results.get("linear") or {}
    if lin.get("campbell"):  # neither in a draft; no Campbell diagram on the exact-determinant route
        jobs["campbell"] = lambda: {"campbell": campbell_plot(results)}
    if lin.get("stability_map"):
        jobs["map"] = lambda: {"map": stability_map_plot(results)}
    if results.get("profiles"):
        from etcheck.report.figures.profiles import profile_figures

        jobs["profiles"] = lambda: profile_figures(results)
    if (results.get("postbuckling") or {}).get("computed"):
        jobs["postbuckling"] = lambda: postbuckling_plots(results)
    if results.get("uncertainty"):
        from etcheck.report.figures.uncertainty import tornado_plot

        jobs["uncertainty"] = lambda: {"uncertainty": tornado_plot(results)}
    if results.get("orbit"):
        from etcheck.report.figures.orbit import orbit_figures

        jobs["orbit"] = lambda: orbit_figures(results)
    return draw(jobs)
