"""Figures of the field along the orbit: ground track coloured by the axial field,
and the axial field and the load margin against time (first orbit, whole window).

Every function takes the JSON-able check results (``results["orbit"]``, SI:
tesla, seconds, N/m; latitude and longitude in degrees) and returns the figure
as an inline PNG ``<img>``; fields are drawn in µT.
"""

from __future__ import annotations

import numpy as np

from etcheck.report.figures.common import image as _image
from etcheck.report.figures.common import legend_below
from etcheck.report.figures.common import pyplot as _plt


def _arr(values) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def ground_track_plot(results: dict) -> str:
    """Sub-satellite points on longitude/latitude axes, coloured by the worst axial field [µT]."""
    plt = _plt()
    o = results["orbit"]
    s = o["series"]
    lon, lat, b = _arr(s["longitude_deg"]), _arr(s["latitude_deg"]), _arr(s["axial_worst_T"]) * 1e6
    w = o["worst"]
    fig, ax = plt.subplots(figsize=(6.8, 3.6))
    sc = ax.scatter(lon, lat, c=b, s=4, cmap="viridis", vmin=0.0, vmax=float(np.nanmax(b)), linewidths=0)
    ax.plot([w["longitude_deg"]], [w["latitude_deg"]], marker="*", ms=13, color="#c0392b", mec="white", mew=0.8,
            ls="none", label=f"worst: {w['axial_field_T'] * 1e6:.4g} µT at {w['latitude_deg']:.2f}°, {w['longitude_deg']:.2f}°")
    cb = fig.colorbar(sc, ax=ax, pad=0.02)
    cb.set_label("axial field, worst over libration [µT]")
    top = min(90.0, max(10.0, float(np.nanmax(np.abs(lat))) + 8.0))
    ax.set_xlim(-180, 180)
    ax.set_ylim(-top, top)
    ax.set_xticks(np.arange(-180, 181, 60))
    ax.axhline(0.0, color="k", lw=0.5, alpha=0.5)
    ax.set_xlabel("longitude [deg E]")
    ax.set_ylabel("geodetic latitude [deg N]")
    ax.set_title(f"Ground track over {o['duration_s'] / 3600:.4g} h from {o['start'][:16]} UTC ({o['model']})", fontsize=9)
    legend_below(ax, ncol=1)
    return _image(fig)


def _time_panels(o: dict, series: dict, unit: float, unit_name: str, title: str) -> str:
    plt = _plt()
    t = _arr(series["time_s"]) / unit
    worst, nominal = _arr(series["axial_worst_T"]) * 1e6, np.abs(_arr(series["axial_nominal_T"])) * 1e6
    margin = series.get("load_margin")
    rows = 2 if margin is not None else 1
    fig, axes = plt.subplots(rows, 1, figsize=(6.6, 2.2 * rows + 0.4), sharex=True, squeeze=False)
    ax = axes[0, 0]
    ax.plot(t, worst, color="#1f4e79", lw=1.0, label="worst over the libration set (the load's field)")
    ax.plot(t, nominal, color="#e67e22", lw=0.8, ls="--", label="tether on the local vertical |B·up|")
    ax.axhline(o["worst"]["axial_field_T"] * 1e6, color="#c0392b", lw=0.8, ls=":",
               label=f"worst over the window {o['worst']['axial_field_T'] * 1e6:.4g} µT")
    ax.set_ylabel("axial field [µT]")
    ax.set_ylim(0, 1.1 * o["worst"]["axial_field_T"] * 1e6)
    ax.set_title(title, fontsize=9)
    if margin is not None:
        mg = _arr(margin)
        m = o["margin"]
        ax2 = axes[1, 0]
        positive = mg[mg > 0]
        log = positive.size > 0  # a margin of 0 all along (no load is safe) has no place on a log axis
        label = "load margin = critical I·B0 / (|I| B_axial(t))"
        if log:
            ax2.semilogy(t, np.where(mg > 0, mg, np.nan), color="#14632c", lw=1.0, label=label)
        else:
            ax2.plot(t, mg, color="#14632c", lw=1.0, label=label)
        ax2.axhline(m["required"], color="#c0392b", lw=1.2, ls="--", label=f"required {m['required']:g}")
        if m["smallest"] is not None and (m["smallest"] > 0 or not log):
            ax2.axhline(m["smallest"], color="k", lw=0.8, ls=":", label=f"smallest {m['smallest']:.4g}")
        ax2.set_ylabel("load margin (–)")
        hi = max(float(np.nanmax(mg)), m["required"])
        low = min(float(np.min(positive)), m["required"]) / 1.5 if log else 0.0
        ax2.set_ylim(low, hi * 1.5)
    axes[-1, 0].set_xlabel(f"time since {o['start'][:16]} UTC [{unit_name}]")
    fig.tight_layout()
    handles = [h for a in axes[:, 0] for h in a.get_legend_handles_labels()[0]]
    legend_below(axes[-1, 0], handles=handles, ncol=2)
    return _image(fig)


def first_orbit_plot(results: dict) -> str:
    """Axial field and load margin against time over the first orbit (full resolution)."""
    o = results["orbit"]
    return _time_panels(o, o["first_orbit"], 60.0, "min",
                        f"First orbit ({o['period_s'] / 60:.4g} min), every sample ({o['sampling']['step_s']:g} s)")


def window_plot(results: dict) -> str:
    """Axial field and load margin against time over the whole window."""
    o = results["orbit"]
    return _time_panels(o, o["series"], 3600.0, "h", f"The whole window ({o['duration_s'] / 3600:.4g} h)")


def orbit_figures(results: dict) -> dict[str, str]:
    """The figures of the section "The field along the orbit", keyed by name."""
    return {"orbit_track": ground_track_plot(results), "orbit_first": first_orbit_plot(results),
            "orbit_window": window_plot(results)}


__all__ = ["first_orbit_plot", "ground_track_plot", "orbit_figures", "window_plot"]
