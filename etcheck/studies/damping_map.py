"""Damping map of the coiled tether: the stability and damping of b1 over the (load, spin) plane.

For each damping of the paper's Fig. 19 (arXiv:0810.3668; or the user's), the
damping ratio of the least-damped mode of b1 over a (B, omega) grid below b1's
secondary-pitchfork curve B*(omega), and b1 at fixed load followed in spin with
its eigenvalue paths (the paper's Hopf test, Sec. VII B). Dimensionless work in
:mod:`etcheck.rod.buckled`; JSON-able results with SI counterparts.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

import numpy as np

from etcheck.checks.orbit_field import resolve
from etcheck.checks.results.header import results_header
from etcheck.checks.rungs.coil import eigenvalue_paths, path_spectra, secondary_pitchfork_at
from etcheck.errors import SolverError
from etcheck.input.mission import Mission
from etcheck.jsonable import finite_or_none, to_json
from etcheck.rod.buckled import pitchforks
from etcheck.rod.buckled.damping_map import HOPF_GAMMAS, DampingMap, damping_map
from etcheck.rod.buckled.secondary import b1_spin_branch
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import check_resolution
from etcheck.rod.straight.collocation.spectral import THRESHOLD, divergence_loads
from etcheck.runtime.parallel import split_map
from etcheck.scaling import Scales, scale
from etcheck.studies.diagram import refuse_outside_limit


def damping_study(params: RodParameters, scales: Scales, gammas=HOPF_GAMMAS, B_max: float | None = None,
                  omega_max: float = 4.0, n_B: int = 14, n_omega: int = 12, N: int = 24) -> dict[str, Any]:
    """Damping margin of b1 over (B, omega) for each gamma, with the secondary-pitchfork curve.

    B from 0 to ``B_max`` (default 5 times b1's pitchfork at rest) and omega
    from 0 to ``omega_max`` (dimensionless, grid ``n_B`` x ``n_omega``); the
    equilibria are computed once and reused for every gamma. The curve B*(omega)
    is located at N and at the check resolution (its error). Spin by spin on two
    cores (each spin's curve point and map column in one process). Returns JSON-able
    arrays of shape (gamma, omega, B) (None outside b1's stable region) and
    their SI counterparts.
    """
    t0 = time.perf_counter()
    pf0 = float(pitchforks.class_loads(params.with_(B=0.0, omega=0.0), "S1", N, n=1)[0])
    B_ref = 1.5 * pf0  # b1 is reached here and followed in spin (above its pitchfork, below B*)
    B_max = B_max or 5.0 * pf0
    B = np.linspace(0.0, B_max, n_B + 1)[1:]
    w = np.linspace(0.0, omega_max, n_omega)
    # b1 followed in spin at N and the check resolution (its states start every spin's continuation in load) and
    # b1's lift-off spin, once, before the spins are shared between two cores
    t_curve = time.perf_counter()
    spin_branch_failed = None
    for n in (N, check_resolution(N)):
        try:
            b1_spin_branch(params, B_ref, omega_max, n)
        except _UNANSWERED as exc:
            spin_branch_failed = f"b1 at B = {B_ref:.4g} was not followed in spin to {omega_max:g} at N = {n} ({exc})"
    try:
        lift = pitchforks.liftoff_spin(params.with_(gamma=0.0), "b1", 1, N=N)
    except _UNANSWERED:
        lift = None  # each spin's column finds it again and says why it failed
    t_curve = time.perf_counter() - t_curve
    columns = split_map(lambda wi: _spin_column(params, B, float(wi), gammas, N, B_ref, lift, spin_branch_failed),
                        list(w))
    curve = [c[0] for c in columns]
    t_curve += sum(c[1] for c in columns)  # seconds of work (the spins' share summed over both cores)
    m = _joined(B, w, gammas, N, [c[2] for c in columns])
    spin_reasons = [c[3] for c in columns]
    zeta = m.zeta
    # unstable as the stability module defines it (max Re lambda above its threshold, not merely > 0), and
    # by more than the two-resolution error of max Re lambda; a point above the threshold by less than that
    # error is not resolved (e.g. a tiny damping, whose decay rates lie below the solver's error)
    growth = np.nan_to_num(m.max_real, nan=-1.0)
    err = np.nan_to_num(m.error, nan=0.0)
    unstable = growth > THRESHOLD + err
    unresolved = (growth > THRESHOLD) & ~unstable
    # b1 at fixed load followed in spin: the paper's Hopf test (Sec. VII B, B = 1.2), at the smallest damping
    B_path = max(B_ref, min(1.2, 2.05 * pf0))  # the paper's B = 1.2 for SET
    try:
        paths = eigenvalue_paths(path_spectra(b1_spin_branch(params, B_path, omega_max, N), min(m.gammas)))
    except _UNANSWERED as exc:
        paths = {"computed": False, "parameter": "omega", "values": [], "gamma": min(m.gammas), "re": [], "im": [],
                 "labels": [], "error": None, "N": N, "N_check": check_resolution(N), "max_re": None, "time_s": 0.0,
                 "reason": f"b1 at B = {B_path:.4g} was not followed in spin to {omega_max:g} ({exc})"}
    paths["B"] = B_path
    first = divergence_loads(params.with_(B=0.0, omega=0.0), n=1, N=N)
    born_unstable = bool(first.size) and float(first[0]) < pf0 * (1 - 1e-6)
    note = (f"b1 is born unstable: at rest the straight tether first buckles at B = {float(first[0]):.6g} into "
            f"b2 (class S2), below b1's pitchfork B = {pf0:.6g} (end tension T = {params.T:.4g}), so b1 bifurcates "
            "from an already unstable straight state; the map gives its growth rates, not a stable region under B*"
            if born_unstable else
            "b1 is born stable at its pitchfork (the first of the straight tether) and, with damping, stays stable "
            "up to its secondary pitchfork B*(omega) (Sec. VII B)")
    return {
        "b1_born_unstable": born_unstable,
        "note": note,
        "spin_paths": paths,
        "model": "rungs 2-3: b1 (whirling equilibria) and the lowest eigenvalues about each state",
        "params": {k: getattr(params, k) for k in ("P", "R", "Gamma", "f", "T")},
        "gammas": list(m.gammas),
        "damping_time_s": [scales.damping_time(g) for g in m.gammas],
        "B": B.tolist(), "omega": w.tolist(),
        "IB0_N_per_m": scales.line_load(B).tolist(), "spin_rpm": scales.rpm(w).tolist(),
        "secondary_pitchfork_B": [c["B"] for c in curve],
        "secondary_pitchfork_error": [c["error"] for c in curve],
        "secondary_pitchfork_reason": [c["reason"] for c in curve],
        "secondary_pitchfork_IB0_N_per_m": [None if c["B"] is None else scales.line_load(c["B"]) for c in curve],
        "curve_time_s": t_curve,
        "primary_pitchfork_B": finite_or_none(m.primary_B),
        "max_real": finite_or_none(m.max_real), "decay_rate_per_s": finite_or_none(scales.rad_s(-m.max_real)),
        "damping_ratio": finite_or_none(zeta), "log_decrement": finite_or_none(m.log_decrement),
        "frequency_Hz": finite_or_none(scales.hz(m.frequency)), "error": finite_or_none(m.error),
        "spin_not_answered": spin_reasons,
        "unstable_points": int(np.count_nonzero(unstable)),
        "unresolved_points": int(np.count_nonzero(unresolved)),
        "unstable_threshold": THRESHOLD,
        "smallest_damping_ratio": [float(np.nanmin(zeta[i])) if np.isfinite(zeta[i]).any() else None
                                   for i in range(len(m.gammas))],
        "largest_error": float(np.nanmax(m.error)) if np.isfinite(m.error).any() else None,
        "N": m.N, "N_check": m.N_check,
        "timing": m.timing,
        "time_s": time.perf_counter() - t0,
    }


#: what a failed continuation or solve of one point raises: that point is "not answered", with the reason
_UNANSWERED = (ValueError, SolverError, np.linalg.LinAlgError, ArithmeticError)


def _spin_column(params: RodParameters, B: np.ndarray, omega: float, gammas, N: int, B_ref: float,
                 liftoff: float | None, failed: str | None) -> tuple[dict[str, Any], float, DampingMap | None, str | None]:
    """One spin of the study: B*(omega) (:func:`_curve_point`) and the seconds it took, then the map's column at
    that spin (None, with the reason, when b1 was not followed over the map's loads). In that order and in one
    process: the continuations of b1 up to B* at N that the curve makes (cached) serve the column."""
    t0 = time.perf_counter()
    point = _curve_point(params, omega, N, B_ref, failed)
    spent = time.perf_counter() - t0
    try:
        return point, spent, damping_map(params, B, np.array([omega]), gammas=gammas, N=N, B_ref=B_ref,
                                         liftoff=liftoff), None
    except _UNANSWERED as exc:
        return point, spent, None, f"b1 was not followed over the map's loads at this spin ({type(exc).__name__}: {exc})"


def _joined(B: np.ndarray, w: np.ndarray, gammas, N: int, columns: list[DampingMap | None]) -> DampingMap:
    """The damping map over the whole grid from its columns (one per spin; None: that spin not answered, left
    blank: NaN)."""
    done = [c for c in columns if c is not None]
    if not done:  # nothing answered: every point blank, every spin with its reason
        blank = np.full((len(tuple(gammas)), 1, B.size), np.nan)
        ref = DampingMap(B, np.asarray(w[:1], dtype=float), tuple(float(g) for g in gammas), N, check_resolution(N),
                         *([blank] * 6), np.zeros((1, B.size), dtype=bool), np.full((1, B.size), np.nan),
                         np.full(1, np.nan), np.full(1, np.nan), {"equilibria_s": 0.0, "spectra_s": 0.0, "points": 0})
        done = [ref]
    ref = done[0]

    def join(name: str, axis: int) -> np.ndarray:
        blank = np.full_like(getattr(ref, name), np.nan if getattr(ref, name).dtype.kind == "f" else False)
        return np.concatenate([getattr(c, name) if c is not None else blank for c in columns], axis=axis)

    per_gamma = {k: join(k, 1) for k in ("max_real", "decay", "zeta", "log_decrement", "frequency", "error")}
    per_spin = {k: join(k, 0) for k in ("inside", "measure1", "curve_B", "primary_B")}
    timing = {k: sum(c.timing[k] for c in columns if c is not None) for k in ref.timing}
    return replace(ref, omega=np.asarray(w, dtype=float), timing=timing, **per_gamma, **per_spin)


def _curve_point(params: RodParameters, omega: float, N: int, B_ref: float, failed: str | None) -> dict[str, Any]:
    """B*(omega) at one spin, or None with the reason it was not answered."""
    try:
        pt = secondary_pitchfork_at(params, omega, N, None, B_ref)
    except _UNANSWERED as exc:
        pt, failed = None, f"b1 was not followed to its secondary pitchfork at this spin ({exc})"
    if pt is not None:
        return {"omega": omega, "B": pt.B, "error": pt.error, "reason": None}
    return {"omega": omega, "B": None, "error": None,
            "reason": failed or (f"not found: b1, followed in load from B = {B_ref:.4g}, reaches no secondary "
                                 "pitchfork below B = 60 (or could not be followed that far)")}


def damping_results(mission: Mission, gammas=HOPF_GAMMAS, B_max: float | None = None, omega_max: float = 4.0,
                    n_B: int = 14, n_omega: int = 12, N: int = 24) -> dict[str, Any]:
    """:func:`damping_study` of the mission's tether (its P, R, Gamma, tension), as a results file."""
    resolved = resolve(mission)
    mission, scaled = resolved.mission, scale(resolved.scene)
    at_rest = scaled.params.with_(omega=0.0)
    # the thinnest boundary layers are at the fastest spin of the map; refused before any solve
    refuse_outside_limit(mission, at_rest, "the damping map")
    refuse_outside_limit(mission, at_rest.with_(omega=omega_max), f"the damping map up to spin {omega_max:g}",
                         "--spin-max")
    study = damping_study(scaled.params, scaled.scales, gammas, B_max, omega_max, n_B, n_omega, N)
    return to_json(results_header(mission)) | {"mission_gamma": scaled.params.gamma,
                                      "operating": {"B": scaled.params.B, "omega": scaled.params.omega},
                                      "study": study}
