"""Damping map of the coiled tether: the stability and damping of b1 over the (load, spin) plane.

For each damping of the paper's Fig. 19 (arXiv:0810.3668; or the user's), the
damping ratio of the least-damped mode of b1 over a (B, omega) grid below b1's
secondary-pitchfork curve B*(omega), and b1 at fixed load followed in spin with
its eigenvalue paths (the paper's Hopf test, Sec. VII B). Dimensionless work in
:mod:`etcheck.rod.branch_stability`; JSON-able results with SI counterparts.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from etcheck.checks.coil import eigenvalue_paths, secondary_pitchfork_at
from etcheck.checks.results import results_header
from etcheck.input.mission import Mission
from etcheck.jsonable import finite_or_none
from etcheck.rod import branches as br
from etcheck.rod.branch_stability import HOPF_GAMMAS, b1_spin_branch, damping_map
from etcheck.rod.parameters import RodParameters
from etcheck.rod.spectrum import check_resolution
from etcheck.scaling import RPM, Scales, scale, scene


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
    # the curve first: its continuations of b1 up to B* at N are cached and serve the map's grid
    t_curve = time.perf_counter()
    curve = []
    for n in (N, check_resolution(N)):
        b1_spin_branch(params, B_ref, omega_max, n)  # one continuation in spin serves every point of the curve
    for wi in w:
        pt = secondary_pitchfork_at(params, float(wi), N, None, B_ref)
        curve.append({"omega": float(wi), "B": None if pt is None else pt.B, "error": None if pt is None else pt.error})
    t_curve = time.perf_counter() - t_curve
    m = damping_map(params, B, w, gammas=gammas, N=N, B_ref=B_ref)
    wc = scales.frequency
    zeta = m.zeta
    unstable = np.nan_to_num(m.max_real, nan=-1.0) > 0
    # b1 at fixed load followed in spin: the paper's Hopf test (Sec. VII B, B = 1.2), at the smallest damping
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


def damping_results(mission: Mission, gammas=HOPF_GAMMAS, B_max: float | None = None, omega_max: float = 4.0,
                    n_B: int = 14, n_omega: int = 12, N: int = 24) -> dict[str, Any]:
    """:func:`damping_study` of the mission's tether (its P, R, Gamma, tension), as a results file."""
    scaled = scale(scene(mission))
    study = damping_study(scaled.params, scaled.scales, gammas, B_max, omega_max, n_B, n_omega, N)
    return results_header(mission) | {"mission_gamma": scaled.params.gamma,
                                      "operating": {"B": scaled.params.B, "omega": scaled.params.omega},
                                      "study": study}
