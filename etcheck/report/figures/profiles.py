"""Report figures of rung 1v (a current and a tension along the tether; docs/model.md section 10): the profiles,
the mode that crosses first, and the critical load against damping. matplotlib, imported lazily; each figure
from the JSON-able results alone."""

from __future__ import annotations

from etcheck.report.figures.common import image, legend_below
from etcheck.report.figures.common import pyplot as _plt


def profiles_plot(results: dict) -> str:
    """Current I(s) [A] and tension T(s) [N] along the tether, against the height above its lower end [m]."""
    plt = _plt()
    pr = results["profiles"]
    panels = [(key, pr[key]) for key in ("current", "tension") if pr.get(key)]
    fig, axes = plt.subplots(1, len(panels), figsize=(3.4 * len(panels) + 0.4, 2.7), squeeze=False)
    for ax, (key, data) in zip(axes[0], panels):
        if key == "current":
            ax.plot(data["height_m"], data["current_A"], color="#1f4e79", lw=1.6)
            ax.set_ylabel("current I(s) [A]")
            ax.set_title("Current along the tether", fontsize=9)
            ax.set_ylim(bottom=0)
        else:
            ax.plot(data["height_m"], data["tension_N"], color="#7d3c98", lw=1.6, label="gravity-gradient tension")
            low = min(data["tension_N"])
            ax.axhline(low, color="#7d3c98", ls=":", lw=1, label=f"smallest, {low:.3g} N (the bound)")
            ax.set_ylabel("tension T(s) [N]")
            ax.set_title("Tension along the tether", fontsize=9)
        ax.set_xlabel("height above the lower end [m]")
        ax.set_xlim(0, data["height_m"][-1])
    fig.tight_layout()
    for ax, (key, _) in zip(axes[0], panels):
        if key == "tension":
            legend_below(ax, ncol=1)
    return image(fig)


def critical_mode_plot(results: dict) -> str:
    """The mode that crosses first: |u| (weak axis) and |v| (stiff axis) along the tether, with the phase-resolved
    real parts, against the height above the lower end [m]."""
    plt = _plt()
    mode = results["profiles"]["mode"]
    L = results["scene"]["length_m"]
    h = [s * L for s in mode["s"]]
    u = [complex(a, b) for a, b in zip(mode["u_re"], mode["u_im"])]
    v = [complex(a, b) for a, b in zip(mode["v_re"], mode["v_im"])]
    fig, ax = plt.subplots(figsize=(6.6, 3.1))
    ax.plot(h, [abs(z) for z in u], color="#1f4e79", lw=1.6, label="|u| (along d₁: bending about the weak axis)")
    ax.plot(h, [abs(z) for z in v], color="#e67e22", lw=1.6, ls="--", label="|v| (along d₂: about the stiff axis)")
    ax.plot(h, [z.real for z in u], color="#1f4e79", lw=0.7, alpha=0.6, label="Re u, Re v (one phase)")
    ax.plot(h, [z.real for z in v], color="#e67e22", lw=0.7, alpha=0.6)
    ax.axhline(0, color="0.6", lw=0.5)
    what = (f"flutter at {mode['frequency_Hz']:.4g} Hz: the amplitude grows while it oscillates"
            if mode["kind"] == "flutter" else "divergence: a static deflection")
    ax.set_title(f"Mode that loses stability first ({what})", fontsize=9)
    ax.set_xlabel("height above the lower end [m]")
    ax.set_ylabel("deflection / largest (–)")
    ax.set_xlim(0, L)
    fig.tight_layout()
    legend_below(ax, ncol=3)
    return image(fig)


def damping_map_plot(results: dict) -> str:
    """The critical load I B0 [N/m] at the operating spin against the damping time [s] (log), with the undamped
    threshold, the operating load and the points where damping lowered the threshold."""
    plt = _plt()
    pr = results["profiles"]
    points = _drawable(pr["damping"]["map"])
    fig, ax = plt.subplots(figsize=(6.2, 2.8))
    t = [q["damping_time_s"] for q in points]
    load = [q["IB0_N_per_m"] for q in points]
    ax.plot(t, load, "o-", color="#1f4e79", lw=1.4, ms=4, label="critical load with damping")
    low = [(a, b) for a, b, q in zip(t, load, points) if q["destabilised"]]
    if low:
        ax.plot(*zip(*low), "v", color="#c0392b", ms=7, label="below the undamped one (destabilised by damping)")
    und = pr.get("undamped") or {}
    if (und.get("IB0_N_per_m") or 0.0) > 0:
        ax.axhline(und["IB0_N_per_m"], color="#27ae60", ls="--", lw=1.2,
                   label=f"undamped, {und['IB0_N_per_m']:.3g} N/m ({und['kind']})")
    ax.axhline(results["scene"]["load_N_per_m"], color="k", lw=1, ls=":", label="operating load")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("Kelvin–Voigt damping time γ_v [s]")
    ax.set_ylabel("critical I·B₀ [N/m]")
    ax.set_title("Critical load against damping (circulatory load)", fontsize=9)
    fig.tight_layout()
    legend_below(ax, ncol=2)
    return image(fig)


def profile_figures(results: dict) -> dict[str, str]:
    pr = results["profiles"]
    out = {}
    if pr.get("current") or pr.get("tension"):
        out["profiles"] = profiles_plot(results)
    if pr.get("mode"):
        out["profile_mode"] = critical_mode_plot(results)
    if _drawable(pr["damping"]["map"]):
        out["damping_map"] = damping_map_plot(results)
    return out


def _drawable(points: list[dict]) -> list[dict]:
    """The damping map's points a log-log plot can show: a located critical load above zero at a damping time above
    zero (a tether unstable at any load has none; the report's table lists every point)."""
    return [q for q in points if (q["IB0_N_per_m"] or 0.0) > 0 and q["damping_time_s"] > 0]
