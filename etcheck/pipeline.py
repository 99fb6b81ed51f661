"""The library entry point: mission -> scene -> plan -> solve -> margins -> results.

``check(mission)`` returns a :class:`CheckResult` whose ``results`` are plain
JSON-able data; reports are rendered from those alone (see :mod:`etcheck.report`).
"""

from __future__ import annotations

import datetime as _dt
import math
import time
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from . import __version__
from .margins import FAIL, INCOMPLETE, PASS, Margin, incomplete_margin, overall_verdict, ratio_margin
from .mission import Mission, load_mission, mission_from_dict
from .plan import Plan, plan
from .rod import analytic
from .scaling import Scaled, Scene, scale, scene
from .whirl import DEFAULT_OPTIONS, RPM, WhirlOptions, accuracy, linear_stability

SCHEMA_VERSION = 1
EXIT_CODES = {PASS: 0, FAIL: 1, INCOMPLETE: 1}
N_LOADS = 5


@dataclass(frozen=True)
class CheckResult:
    """What a check produced: JSON-able ``results`` and the CLI exit code."""

    results: dict[str, Any]

    @property
    def verdict(self) -> str:
        return self.results["verdict"]

    @property
    def exit_code(self) -> int:
        return EXIT_CODES[self.verdict]


def check(mission: Mission | str | Path | dict, options: WhirlOptions = DEFAULT_OPTIONS) -> CheckResult:
    """Run the stability check of a mission (a Mission, a TOML path or a dict).

    ``options`` sets the resolution of the rung-1 answers (tolerances, map
    and Campbell grids, accuracy table).
    """
    if isinstance(mission, (str, Path)):
        mission = load_mission(mission)
    elif isinstance(mission, dict):
        mission = mission_from_dict(mission)
    started = time.perf_counter()
    sc = scene(mission)
    scaled = scale(sc)
    chosen = plan(scaled.params, mission.fidelity)
    static = static_buckling(scaled)
    static["limits"] = _static_limits(static, mission, sc)
    linear = accuracy_rows = None
    options = replace(options, N=mission.resolution, eig_tol=mission.tolerance)  # the mission's [check] rules
    if chosen.rung == 1:
        linear = linear_stability(scaled, options)
        accuracy_rows = accuracy(scaled, options.accuracy_N) if options.accuracy_N else None
    margins = _margins(mission, sc, scaled, chosen, static, linear)
    post = _postbuckling(mission, scaled, static, linear)
    if post and post.get("computed"):
        margins += _buckled_margins(post, sc, scaled, mission.required_margin)
    results = {
        "schema_version": SCHEMA_VERSION,
        "etcheck_version": __version__,
        "generated": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "mission": mission.echo(),
        "scene": _scene_dict(mission, sc),
        "scaled": asdict(scaled.params),
        "scales": {
            "length_m": scaled.scales.length,
            "reference_frequency_rad_s": scaled.scales.frequency,
            "force_N": scaled.scales.force,
            "load_N_per_m": scaled.scales.load,
        },
        "plan": {"rung": chosen.rung, "model": chosen.model, "reason": chosen.reason, "complete": chosen.complete},
        "straight_rod": static,
        "linear": linear,
        "postbuckling": post,
        "accuracy": accuracy_rows,
        "margins": [m.as_dict() for m in margins],
        "verdict": overall_verdict(margins),
        "validity": _validity(mission, scaled, chosen, post),
        "elapsed_s": time.perf_counter() - started,
    }
    return CheckResult(results=results)


def static_buckling(scaled: Scaled) -> dict[str, Any]:
    """Rung 0 answers for the scene: critical loads, frequencies, mode shape.

    All loads are at omega = 0, T = 0 (eq. ``char_welded``); dimensionless B
    and I B0 in N/m.
    """
    p, scales = scaled.params, scaled.scales
    roots = analytic.characteristic_roots(N_LOADS)
    loads = []
    for r, B in zip(roots, analytic.critical_loads(p.R, p.f, N_LOADS)):
        B = float(B)
        loads.append(
            {
                "k": r.k,
                "beta": r.beta,
                "B": B,
                "IB0_N_per_m": B * scales.load,
                "multiplicity": r.kernel_dimension,
                "chi_residual": r.residual,
                "chi_curvature": r.curvature,
                "relative_error": 3.0 * r.error,
            }
        )
    s = np.linspace(0.0, 1.0, 101)
    x, y = analytic.buckling_mode(1, p.R, s)
    op_beta = analytic.beta_of_load(p.B, p.R, p.f)
    beta_grid = np.linspace(0.0, min(max(1.25 * roots[2].beta, 1.15 * op_beta), 1.1 * roots[-1].beta), 600)
    # zeros of chi below the operating beta (asymptotically pi/3 + 2 pi n beyond the tabulated ones)
    exceeded = sum(r.beta <= op_beta for r in roots)
    if op_beta > roots[-1].beta:
        exceeded = int((op_beta - math.pi / 3) // (2 * math.pi))
    freq = {
        "bending_weak": analytic.bending_frequencies(p.P, p.R, p.f, 5, "weak"),
        "bending_stiff": analytic.bending_frequencies(p.P, p.R, p.f, 5, "stiff"),
        "torsion": analytic.torsion_frequencies(p.P, p.Gamma, p.f, 5),
    }
    wc = scales.frequency
    return {
        "model": "rung 0 (analytic)",
        "critical_loads": loads,
        "operating_beta": op_beta,
        "loads_exceeded": exceeded,
        "operating_B": p.B,
        "first_mode": {"s": s.tolist(), "x": x.tolist(), "y": y.tolist()},
        "chi_curve": {"beta": beta_grid.tolist(), "chi_scaled": analytic.chi_scaled(beta_grid).tolist()},
        "natural_frequencies": {
            name: [
                {"mu": float(m), "rad_s": float(m * wc), "Hz": float(m * wc / (2 * math.pi))}
                for m in values
                if math.isfinite(m)
            ]
            for name, values in freq.items()
        },
    }


def _postbuckling(mission: Mission, scaled: Scaled, static: dict, linear: dict | None) -> dict | None:
    """Rungs 2-3 when the operating point is past, or within the required margin of, the first critical load."""
    from .postbuckling import needs_postbuckling, postbuckling_check

    p = scaled.params
    if linear is not None:
        crit = linear["critical_load"]
        B_c = crit["value"] if crit["kind"] in ("divergence", "flutter") else (0.0 if crit["kind"] == "unstable at start" else None)
    else:
        B_c = static["critical_loads"][0]["B"] if p.omega == 0 and p.T == 0 else None
    if B_c is None or not needs_postbuckling(p.B, B_c, mission.required_margin):
        return None
    if B_c == 0.0:
        return {"computed": False, "B_c": 0.0, "load_ratio": None,
                "reason": "the straight tether is unstable without any magnetic load at this spin and tension "
                "(it whirls): no buckled branch grows from a stable straight state here"}
    return postbuckling_check(p, scaled.scales, B_c, mission.required_margin)


def _buckled_margins(post: dict, sc: Scene, scaled: Scaled, required: float) -> list[Margin]:
    """Load margin of the buckled tether on b1 up to its secondary pitchfork (rungs 2-3)."""
    B_star = post.get("secondary_pitchfork_B")
    op = post.get("operating")
    if op is None or not op.get("available"):
        return []
    if B_star is None:
        return [incomplete_margin("buckled tether (b1): load to its secondary pitchfork", "N/m", sc.load, required, 3,
                                  "no secondary pitchfork found on b1 in the computed range")]
    if not op["stable"]:
        return [ratio_margin("buckled tether (b1): load to its secondary pitchfork", "N/m", 0.0, sc.load, required, 3,
                             0.0, "the buckled state at the operating load is unstable (rung 3)")]
    return [ratio_margin("buckled tether (b1): load to its secondary pitchfork", "N/m",
                         post["secondary_pitchfork_IB0_N_per_m"], sc.load, required, 3,
                         post["secondary_pitchfork_error"],
                         "the buckled (coiled) tether on b1 stays stable up to its symmetry-breaking secondary "
                         "pitchfork at the operating spin and tension (rungs 2-3)")]


def _margins(mission: Mission, sc: Scene, scaled: Scaled, chosen: Plan, static: dict, linear: dict | None) -> list[Margin]:
    required = mission.required_margin
    first = static["critical_loads"][0]
    if linear is not None:
        return _linear_margins(sc, scaled, required, linear)
    if chosen.rung == 0 and chosen.complete:
        return [
            ratio_margin(
                "magnetic load |I B0|",
                "N/m",
                first["IB0_N_per_m"],
                sc.load,
                required,
                chosen.rung,
                first["relative_error"],
                "first (doubly degenerate) static buckling load of the straight welded tether, eq. char_welded",
            )
        ]
    return [incomplete_margin("magnetic load |I B0|", "N/m", sc.load, required, chosen.rung, chosen.reason)]


def _linear_margins(sc: Scene, scaled: Scaled, required: float, linear: dict) -> list[Margin]:
    """Load margin at the operating spin; spin margin at the operating load (rung 1)."""
    p = scaled.params
    load, spin = linear["critical_load"], linear["critical_spin"]
    window = ""
    if linear["operating_spectrum"]["stable"]:
        window = (
            "; the operating point itself is stable, inside a stability window that does not reach back to zero "
            "(gyroscopic stabilisation, which damping removes): a window is not counted as margin"
        )
    margins = [
        _margin_from_critical(
            "magnetic load |I B0| at the operating spin and tension",
            "N/m",
            load,
            load["IB0_N_per_m"],
            sc.load,
            scaled.scales.load,
            required,
            "the straight tether first loses stability as I B0 grows at the operating spin, tension and damping",
            "the straight tether is already unstable with no magnetic load at the operating spin and tension" + window,
        )
    ]
    if p.omega > 0:
        margins.append(
            _margin_from_critical(
                "spin rate at the operating load",
                "rpm",
                spin,
                spin["rpm"],
                sc.spin_rate * RPM,
                scaled.scales.frequency * RPM,
                required,
                "the straight tether first loses stability as the spin rate grows at the operating load",
                "the straight tether is already unstable without spin at the operating load (statically buckled)"
                + window,
            )
        )
    return margins


def _margin_from_critical(name, unit, point, critical, operating, scale_to_si, required, why, why_unstable) -> Margin:
    kind = point["kind"]
    if kind == "unstable at start":
        return ratio_margin(name, unit, 0.0, operating, required, 1, 0.0, why_unstable)
    if kind == "none found":
        hi = point["bracket"][1] * scale_to_si
        return ratio_margin(
            name, unit, hi, operating, required, 1, 0.0,
            f"stable over the whole scanned range (up to {hi:.4g} {unit}); the margin shown is a lower bound",
        )
    error = (point["error"] or 0.0) / point["value"] if point["value"] else 0.0
    return ratio_margin(name, unit, critical, operating, required, 1, error, f"{why} ({kind})")


def _static_limits(static: dict, mission: Mission, sc: Scene) -> dict[str, Any]:
    """Critical current at the worst field and critical length at the operating load.

    Static buckling (omega = T = 0): B ∝ L^3 and the static loads do not
    depend on P, so L_c = L (B_1 / B)^(1/3). SI; None where the operating
    value is zero (no limit).
    """
    critical = static["critical_loads"][0]["IB0_N_per_m"]
    field = mission.worst_field.to_value("T")
    return {
        "critical_IB0_N_per_m": critical,
        "critical_current_A": critical / field if field else None,
        "critical_length_m": sc.length * (critical / sc.load) ** (1 / 3) if sc.load else None,
    }


def _scene_dict(mission: Mission, sc: Scene) -> dict[str, float]:
    return {
        "worst_current_A": float(mission.worst_current.to_value("A")),
        "worst_field_T": float(mission.worst_field.to_value("T")),
        "length_m": sc.length,
        "EI1_N_m2": sc.EI1,
        "EI2_N_m2": sc.EI2,
        "GJ_N_m2": sc.GJ,
        "mass_per_length_kg_per_m": sc.mass_per_length,
        "P": sc.P,
        "load_N_per_m": sc.load,
        "spin_rate_rad_s": sc.spin_rate,
        "tension_N": sc.tension,
        "damping_time_s": sc.damping_time,
        "f": sc.f,
    }


def _after_buckling(post: dict | None) -> str:
    if post and post.get("computed"):
        return ("Past (or near) the first critical load the first post-buckling branch b1 is followed as nonlinear "
                "whirling equilibria (rung 2, Chebyshev collocation, Newton with the exact Jacobian, pseudo-arclength "
                "continuation) and each state's stability from its linearisation (rung 3); other branches (b2, b12, "
                "...) are in `etcheck diagram`. Every measure is checked at a second resolution.")
    return ("Linear stability of the straight tether: margins say where it first buckles or whirls; when the operating "
            "point is within the required margin of that load, the buckled tether is analysed too (rungs 2-3).")


def _validity(mission: Mission, scaled: Scaled, chosen: Plan, post: dict | None = None) -> list[str]:
    p = scaled.params
    items = [
        "Model: inextensible, unshearable, intrinsically straight Kirchhoff rod, welded (clamped) at both ends, "
        "uniform field along the undeformed axis (Valverde & van der Heijden).",
        _after_buckling(post),
        "The load is the worst case |I| x |B0| over the given ranges; field components across the tether "
        "(which drive the intended drag) are not part of this check.",
    ]
    if chosen.rung == 0:
        items.append(
            "Rung 0 roots of chi(beta) are located to ~1e-15 relative (a-posteriori Newton step); "
            "the static loads do not depend on P, damping or mass per length."
        )
    if chosen.rung == 1:
        items += [
            "Rung 1 linearises the full O(delta) equations (Sec. 5.2) about the straight tether and solves the "
            "damped gyroscopic eigenproblem by Chebyshev collocation; every eigenvalue and critical value is "
            "computed at two resolutions and their agreement is its error estimate (table below).",
            "Stability is judged on the lowest 12 eigenvalue pairs (Re lambda > 1e-9 counts as growing); higher "
            "modes are stiffened by bending. With damping, the straight tether can only lose stability where "
            "its static operator is singular (divergence, Kelvin-Tait-Chetaev); without damping, gyroscopic "
            "windows above the critical spin may appear and are lost with any damping.",
            "The stability map is exact with damping (each spin row cut at its static points) and sampled on a "
            "grid without (boundaries interpolated between grid points); the margins and critical values in the "
            "tables are located to 1e-10.",
        ]
        if p.gamma > 0:
            items.append(
                f"Eigenvalues left of -1/gamma = {-1 / p.gamma:.4g} on the real axis (the Kelvin-Voigt "
                "accumulation of heavily damped high modes) are not listed: they decay faster than the material "
                "relaxation rate."
            )
    if p.P > 1e-2:
        items.append(f"P = {p.P:.3g} is large for a slender rod; rod theory assumes P << 1.")
    return items
