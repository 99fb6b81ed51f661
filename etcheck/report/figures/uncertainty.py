"""Tornado chart of the uncertainty study: how far each uncertain input moves each margin."""

from __future__ import annotations

from etcheck.report.figures.common import image as _image
from etcheck.report.figures.common import legend_below
from etcheck.report.figures.common import pyplot as _plt


def tornado_plot(results: dict) -> str:
    """One panel per margin: the margin with each uncertain input at the ends of its tolerance
    range (others nominal), longest bar on top; vertical lines at the nominal and required margins.
    Without tolerances (no swings) the bars are the elasticities d ln margin / d ln input."""
    plt = _plt()
    u = results["uncertainty"]
    panels = u["margins"]
    fig, axes = plt.subplots(len(panels), 1, figsize=(6.6, 0.9 + 0.42 * max(
        len(p["swings"]) or len(p["elasticities"]) for p in panels) * len(panels)), squeeze=False)
    for ax, p in zip(axes[:, 0], panels):
        nominal = p["nominal"]
        swung = [w for w in p["swings"] if w["margin_low"] is not None and w["margin_high"] is not None]
        if swung and nominal is not None:  # (a margin that is not re-evaluated has no swings)
            rows = sorted(swung, key=lambda w: abs(w["margin_high"] - w["margin_low"]))
            for i, w in enumerate(rows):
                lo, hi = w["margin_low"], w["margin_high"]
                ax.barh(i, (lo - nominal), left=nominal, color="#c0392b", height=0.6,
                        label="input at the low end of its range" if i == 0 else None)
                ax.barh(i, (hi - nominal), left=nominal, color="#1f4e79", height=0.6,
                        label="input at the high end" if i == 0 else None)
            ax.set_yticks(range(len(rows)), [w["label"] for w in rows], fontsize=7)
            ax.axvline(nominal, color="k", lw=1, label="nominal margin (each panel's)")
            ax.axvline(u["required_margin"], color="#27ae60", ls="--", lw=1.4,
                       label=f"required margin {u['required_margin']:g}")
            ax.set_xlabel("margin = critical / operating (dimensionless)")
        else:
            rows = sorted((e for e in p["elasticities"] if e["value"] is not None), key=lambda e: abs(e["value"]))
            ax.barh(range(len(rows)), [e["value"] for e in rows], color="#1f4e79", height=0.6)
            ax.set_yticks(range(len(rows)), [e["label"] for e in rows], fontsize=7)
            ax.axvline(0, color="k", lw=1)
            ax.set_xlabel("elasticity d ln margin / d ln input (dimensionless)")
        ax.set_title(f"{p['margin']} (nominal {nominal:.4g})" if nominal is not None else p["margin"], fontsize=9)
    fig.tight_layout()
    handles = axes[0, 0].get_legend_handles_labels()[0]
    if handles:
        legend_below(axes[-1, 0], handles=handles, ncol=2)
    return _image(fig)
