"""Report figures as deterministic inline SVG (matplotlib, imported lazily).

Every function takes the JSON-able results and returns an SVG string; axes are
labelled with units and the operating point is marked.
"""

from __future__ import annotations

import io
import math


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(
        {
            "svg.hashsalt": "etcheck",
            "svg.fonttype": "none",
            "font.size": 9,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "figure.dpi": 100,
        }
    )
    return plt


def _svg(fig) -> str:
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None})
    _plt().close(fig)
    text = buf.getvalue()
    return text[text.index("<svg") :]  # drop the XML prolog for inline use


def chi_plot(results: dict) -> str:
    """chi(beta) e^{-sqrt3 beta} with the critical betas and the operating beta."""
    plt = _plt()
    sr = results["straight_rod"]
    beta = sr["chi_curve"]["beta"]
    chi = sr["chi_curve"]["chi_scaled"]
    op = sr["operating_beta"]
    fig, ax = plt.subplots(figsize=(6.4, 2.8))
    ax.plot(beta, chi, color="#1f4e79", lw=1.4, label=r"$\chi(\beta)\,e^{-\sqrt{3}\beta}$ (eq. char_welded)")
    for i, load in enumerate(sr["critical_loads"]):
        if load["beta"] <= beta[-1] and (i < 3 or op > beta[-1]):
            ax.axvline(load["beta"], color="#c0392b", ls=":", lw=1,
                       label="double zeros $\\beta_k$ (buckling loads)" if i == 0 else None)
            ax.annotate(f"$\\beta_{load['k']}$", (load["beta"], 0.0),
                        xytext=(3, 28), textcoords="offset points", fontsize=7, color="#c0392b")
    top = max(chi) * 1.05
    if op <= beta[-1]:
        ax.axvline(op, color="#27ae60", lw=2, label=f"operating $\\beta$ = {op:.4g}")
    else:
        ax.annotate(f"operating $\\beta$ = {op:.4g} (off scale) →", (beta[-1], 0.85 * top),
                    ha="right", fontsize=8, color="#27ae60", fontweight="bold")
        ax.plot([], [], color="#27ae60", lw=2, label=f"operating $\\beta$ = {op:.4g} (off scale)")
    ax.set_xlim(0, beta[-1])
    ax.set_ylim(-0.05 * top, top)
    ax.set_xlabel(r"$\beta = (f B)^{1/3} / R^{1/6}$  (dimensionless)")
    ax.set_ylabel(r"scaled $\chi$ (dimensionless)")
    ax.legend(loc="upper left", fontsize=7, framealpha=0.9)
    ax.set_title("Characteristic function of the straight welded tether (ω = 0, T = 0)", fontsize=9)
    return _svg(fig)


def mode_plot(results: dict) -> str:
    """First static buckling mode: deflections x(s), y(s) along the tether [m]."""
    plt = _plt()
    sr = results["straight_rod"]
    length = results["scene"]["length_m"]
    s = [v * length for v in sr["first_mode"]["s"]]
    x, y = sr["first_mode"]["x"], sr["first_mode"]["y"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(6.6, 2.6), gridspec_kw={"width_ratios": [2.2, 1]})
    ax1.plot(s, x, color="#1f4e79", label="x (along $d_1$, weak-axis bending)")
    ax1.plot(s, y, color="#e67e22", ls="--", label="y (along $d_2$)")
    ax1.set_xlabel("arclength s [m]")
    ax1.set_ylabel("deflection / max (–)")
    ax1.legend(fontsize=7, loc="lower center")
    ax1.set_title("First buckling mode (one of a double pair)", fontsize=9)
    ax2.plot(x, y, color="#7d3c98")
    ax2.plot([0], [0], "ko", ms=3, label="welded ends")
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_xlabel("x / max (–)")
    ax2.set_ylabel("y / max (–)")
    ax2.legend(fontsize=7, loc="upper right")
    ax2.set_title("End view (coil)", fontsize=9)
    fig.tight_layout()
    return _svg(fig)


def figures(results: dict) -> dict[str, str]:
    """All figures the report shows, keyed by name."""
    out = {"chi": chi_plot(results), "mode": mode_plot(results)}
    return out


def fmt(x, digits: int = 4) -> str:
    """Engineering-friendly number formatting for tables (None -> em dash)."""
    if x is None:
        return "—"
    if isinstance(x, str):
        return x
    if x == 0:
        return "0"
    if not math.isfinite(x):
        return "∞" if x > 0 else "−∞"
    if 1e-3 <= abs(x) < 1e5:
        return f"{x:.{digits}g}"
    mant, exp = f"{x:.{digits - 1}e}".split("e")
    return f"{mant}×10^{int(exp)}"
