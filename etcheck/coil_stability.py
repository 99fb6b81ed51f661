"""Rung 3 for a mission: where the coiled (buckled) tether is stable, and how well damped.

The dimensionless work is in :mod:`etcheck.rod.branch_stability`; this module
asks the engineer's questions of the first post-buckling branch b1 and returns
JSON-able data in both the paper's numbers and SI (I·B0 in N/m, spin in rpm,
decay rates in 1/s, decay times in s):

* the stable region of b1 in the (load, spin) plane: above b1's primary
  pitchfork B_pf(omega) (where the coil appears) and below its secondary
  pitchfork B*(omega) (where it loses stability, independent of damping);
* the damping margin over that region: decay rate, damping ratio and
  logarithmic decrement of the least-damped mode, for given damping values
  (the tether's version of Fig. ``fig:hopf``).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .jsonable import finite_or_none
from .postbuckling import eigenvalue_paths, liftoff
from .rod import branches as br
from .rod.branch_stability import HOPF_GAMMAS, b1_spin_branch, damping_map, secondary_pitchfork
from .rod.parameters import RodParameters
from .rod.spectrum import check_resolution
from .scaling import Scales

RPM = 60.0 / (2.0 * math.pi)


def damping_study(params: RodParameters, scales: Scales, gammas=HOPF_GAMMAS, B_max: float | None = None,
                  omega_max: float = 4.0, n_B: int = 14, n_omega: int = 12, N: int = 24) -> dict[str, Any]:
    """Damping margin of b1 over (B, omega) for each gamma, with the secondary-pitchfork curve.

    B from 0 to ``B_max`` (default 5 times b1's pitchfork at rest) and omega
    from 0 to ``omega_max`` (dimensionless, grid ``n_B`` x ``n_omega``); the
    equilibria are computed once and reused for every gamma. The curve B*(omega)
    is located at N and at the check resolution (its error). Returns JSON-able
    arrays of shape (gamma, omega, B) (None outside b1's stable region) and
    their SI counterparts.
    """
    t0 = time.perf_counter()
    pf0 = float(br.class_loads(params.with_(B=0.0, omega=0.0), "S1", N, n=1)[0])
    B_ref = 1.5 * pf0  # b1 is reached here and followed in spin (above its pitchfork, below B*)
    B_max = B_max or 5.0 * pf0
    B = np.linspace(0.0, B_max, n_B + 1)[1:]
    w = np.linspace(0.0, omega_max, n_omega)
    m = damping_map(params, B, w, gammas=gammas, N=N, B_ref=B_ref)
    t_curve = time.perf_counter()
    curve = []
    for n in (N, check_resolution(N)):
        b1_spin_branch(params, B_ref, omega_max, n)  # one continuation in spin serves every point of the curve
    for wi in w:
        pt = _pitchfork(params, float(wi), N, None, B_ref, 3.0 * B_ref)
        curve.append({"omega": float(wi), "B": None if pt is None else pt.B, "error": None if pt is None else pt.error})
    t_curve = time.perf_counter() - t_curve
    wc = scales.frequency
    zeta = m.zeta
    unstable = np.nan_to_num(m.max_real, nan=-1.0) > 0
    # b1 at fixed load followed in spin: the paper's Hopf test (Sec. 7.2, B = 1.2), at the smallest damping
    B_path = max(B_ref, min(1.2, 2.05 * pf0))  # the paper's B = 1.2 for SET
    paths = eigenvalue_paths(b1_spin_branch(params, B_path, omega_max, N), min(m.gammas))
    paths["B"] = B_path
    return {
        "spin_paths": paths,
        "model": "rungs 2-3: b1 (whirling equilibria) and the lowest eigenvalues about each state",
        "params": {k: getattr(params, k) for k in ("P", "R", "Gamma", "f", "T")},
        "gammas": list(m.gammas),
        "damping_time_s": [g / wc for g in m.gammas],
        "B": B.tolist(), "omega": w.tolist(),
        "IB0_N_per_m": (B * scales.load).tolist(), "spin_rpm": (w * wc * RPM).tolist(),
        "secondary_pitchfork_B": [c["B"] for c in curve],
        "secondary_pitchfork_error": [c["error"] for c in curve],
        "secondary_pitchfork_IB0_N_per_m": [None if c["B"] is None else c["B"] * scales.load for c in curve],
        "curve_time_s": t_curve,
        "primary_pitchfork_B": finite_or_none(m.primary_B),
        "max_real": finite_or_none(m.max_real), "decay_rate_per_s": finite_or_none(-m.max_real * wc),
        "damping_ratio": finite_or_none(zeta), "log_decrement": finite_or_none(m.log_decrement),
        "frequency_Hz": finite_or_none(m.frequency * wc / (2 * math.pi)), "error": finite_or_none(m.error),
        "unstable_points": int(np.count_nonzero(unstable)),
        "smallest_damping_ratio": [float(np.nanmin(zeta[i])) if np.isfinite(zeta[i]).any() else None
                                   for i in range(len(m.gammas))],
        "largest_error": float(np.nanmax(m.error)) if np.isfinite(m.error).any() else None,
        "N": m.N, "N_check": m.N_check,
        "timing": m.timing,
        "time_s": time.perf_counter() - t0,
    }


def _pitchfork(params: RodParameters, omega: float, N: int, N_check: int | None, B_ref: float, B_max: float,
               B_limit: float = 60.0):
    """b1's secondary pitchfork at spin omega, looking up to B_max and doubling the range
    (continuing b1 far past B* is the expensive part); None if not found below B_limit."""
    while True:
        try:
            return secondary_pitchfork(params, omega, N=N, N_check=N_check, B_ref=B_ref, B_max=B_max)
        except ValueError:
            if B_max >= B_limit:
                return None
            B_max = min(2.0 * B_max, B_limit)


def coil_region(params: RodParameters, scales: Scales, omega_max: float, n: int = 4, N: int = 24) -> dict[str, Any]:
    """The stable region of b1 in the (load, spin) plane at the scene's tension (damping-independent).

    Its lower edge is b1's pitchfork on the straight tether (the class-S1
    static load), its upper edge the secondary pitchfork B*(omega), each at
    ``n`` spins from 0 to ``omega_max`` (dimensionless), located exactly at
    resolution N (one resolution: a drawing of the region; the margin at the
    operating spin is computed at two). With damping, stability changes only at
    these static points (Kelvin-Tait-Chetaev), so the region between them is the
    stable region of the coil. JSON-able, with SI.
    """
    t0 = time.perf_counter()
    lift = liftoff(params)
    rows = []
    # b1 is reached at B_ref by continuation in spin: above b1's pitchfork at rest (which falls with spin)
    # and below its secondary pitchfork (about 3.3 times it for SET)
    B_ref = 1.5 * float(br.class_loads(params.with_(B=0.0, omega=0.0), "S1", N, n=1)[0])
    b1_spin_branch(params, B_ref, omega_max, N)  # one continuation in spin serves every row
    for w in np.linspace(0.0, omega_max, n):
        p = params.with_(omega=float(w))
        attached = not (math.isfinite(lift) and w >= lift)
        loads = br.class_loads(p.with_(B=0.0), "S1", N, n=1) if attached else np.array([])
        pt = _pitchfork(p, float(w), N, N, B_ref, 3.0 * B_ref)
        star = pt.B if pt is not None else math.inf
        rows.append({"omega": float(w), "spin_rpm": float(w * scales.frequency * RPM),
                     "pitchfork_B": float(loads[0]) if loads.size else None,
                     "secondary_B": star if math.isfinite(star) else None})
    for r in rows:
        for k in ("pitchfork_B", "secondary_B"):
            r[k.replace("_B", "_IB0_N_per_m")] = None if r[k] is None else r[k] * scales.load
    return {"rows": rows, "N": N, "liftoff_omega": lift if math.isfinite(lift) else None,
            "liftoff_rpm": lift * scales.frequency * RPM if math.isfinite(lift) else None,
            "time_s": time.perf_counter() - t0}


def spin_limit(region: dict, B: float) -> float | None:
    """Lowest spin (dimensionless) at which the coil at load B is still below its secondary
    pitchfork, from the region's table (B*(omega) increases with spin, Sec. 8); 0 if stable
    at rest, None if B is above B* everywhere in the table."""
    rows = [r for r in region["rows"] if r["secondary_B"] is not None]
    if not rows:
        return None
    if B < rows[0]["secondary_B"]:
        return 0.0
    for a, b in zip(rows[:-1], rows[1:]):
        if a["secondary_B"] <= B < b["secondary_B"]:
            t = (B - a["secondary_B"]) / (b["secondary_B"] - a["secondary_B"])
            return a["omega"] + t * (b["omega"] - a["omega"])
    return None
