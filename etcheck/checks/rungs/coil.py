"""Rung 3 for a mission: where the coiled (buckled) tether is stable, and how well damped.

The dimensionless work is in :mod:`etcheck.rod.buckled`; this module
asks the engineer's questions of the first post-buckling branch b1 and returns
JSON-able data in both the paper's numbers and SI (I·B0 in N/m, spin in rpm,
decay rates in 1/s, decay times in s):

* the stable region of b1 in the (load, spin) plane: above b1's primary
  pitchfork B_pf(omega) (where the coil appears) and below its secondary
  pitchfork B*(omega) (where it loses stability, independent of damping);
* the stability of every state of a branch (Kelvin-Tait-Chetaev: with
  damping, classified stretch by stretch between the static special points);
* the least-damped mode of a state and how it moves with the damping;
* the eigenvalue paths along a branch, labelled by mode type.
"""

from __future__ import annotations

import math
import time
from collections import Counter

import numpy as np

from etcheck.checks.results.sections_buckled import CoilRegion, DampingSensitivity
from etcheck.jsonable import finite_or_none
from etcheck.numerics.pchip import Pchip
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled import pitchforks
from etcheck.rod.buckled.branches import Branch
from etcheck.rod.buckled.secondary import b1_spin_branch, secondary_pitchfork
from etcheck.rod.buckled.spectra import BranchSpectra, branch_spectra, damped_operator, operator_eigenvalues
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import spectrum, spectrum_from
from etcheck.rod.straight.collocation.spectral import THRESHOLD
from etcheck.runtime.parallel import split_map
from etcheck.scaling import Scales

#: least-|lambda| pairs whose eigenvalues decide a state's stability, and the two-resolution tolerance they meet
STATE_K, STATE_TOL = 6, 1e-6


def state_stability(state: eq.Equilibrium, gamma: float, solved: tuple | None = None):
    """(stable or None when not converged, max Re lambda, its two-resolution error) of one state (rung 3).

    ``solved``: (eigenvalues at N, at N_check, N, N_check) of the state at damping gamma, the 2 STATE_K + 8
    nearest the shift, already computed (a branch's eigenvalue paths): used where they settle it as
    :func:`~etcheck.rod.core.spectrum.spectrum` would (its first two resolutions), else that is called."""
    sp = spectrum_from(*solved, STATE_K, STATE_TOL) if solved is not None else None
    if sp is None:
        sp = spectrum(state.params.with_(gamma=gamma), base=state, k=STATE_K, tol=STATE_TOL)
    g = float(np.max(sp.eigenvalues.real)) if sp.eigenvalues.size else math.nan
    err = float(np.max(sp.errors)) if sp.errors.size else None
    return (bool(g <= THRESHOLD) if sp.converged and math.isfinite(g) else None), g, err


def branch_stability(branch: Branch, gamma: float, spectra: BranchSpectra | None = None) -> tuple[list, list, list]:
    """Stable flag, max Re lambda and its error at the points of a branch (rung 3); ``spectra``: the branch's
    eigenvalue paths at the same damping, when computed (their spectra then decide the probed states as their
    own solves would, :func:`state_stability`).

    With damping (gamma > 0) stability can change only where the static
    operator is singular (Kelvin-Tait-Chetaev): at the special points located
    on the branch (folds and branch points in the symmetric space, symmetry-
    breaking pitchforks in the antisymmetric one). Each stretch between them is
    then classified by its middle and last state (they must agree); the other
    points carry the stretch's flag and no eigenvalue (None). Without damping
    every state is checked (gyroscopic Krein collisions can occur anywhere).
    """
    n = len(branch.states)
    stable: list = [None] * n
    growth: list = [None] * n
    errors: list = [None] * n
    if gamma > 0:
        cuts = sorted({q.raw.index for q in branch.special})
        bounds = [0, *[c + 1 for c in cuts], n]
        stretches = [(a, b) for a, b in zip(bounds[:-1], bounds[1:]) if b > a]
    else:
        stretches = [(i, i + 1) for i in range(n)]
    probes = [sorted({(a + b) // 2, b - 1} - ({0} if b - a > 1 else set())) for a, b in stretches]
    wanted = sorted({i for probe in probes for i in probe})  # independent spectra: on two cores
    known = {}
    if (spectra is not None and spectra.k == STATE_K and spectra.gamma == gamma and len(spectra.states) == n
            and all(a is b for a, b in zip(spectra.states, branch.states))):
        known = {i: (*spectra.spectra[i], spectra.N, spectra.N_check) for i in wanted}
    solved = dict(zip(wanted, split_map(lambda i: state_stability(branch.states[i], gamma, known.get(i)), wanted)))
    for (a, b), probe in zip(stretches, probes):
        flags = []
        for i in probe:
            flag, g, err = solved[i]
            growth[i] = g if math.isfinite(g) else None
            errors[i] = err
            flags.append(flag)
        verdict = flags[0] if len(set(flags)) == 1 else None  # disagreement: leave unclassified
        for i in range(a, b):
            stable[i] = verdict
    return stable, growth, errors


def path_spectra(branch, gamma: float) -> BranchSpectra:
    """The STATE_K least-|lambda| eigenvalue paths along a branch (rung 3), tracked through crossings (their spectra
    also decide the branch's stability, :func:`branch_stability`)."""
    return branch_spectra(branch, gamma, k=STATE_K, stiffness=False)  # no stiffness index: the paths do not show it


def eigenvalue_paths(bs: BranchSpectra) -> dict:
    """The eigenvalue paths of :func:`path_spectra`, labelled by mode type (bending about d1 / d2, torsion);
    JSON-able (dimensionless)."""
    gamma = bs.gamma
    lam = np.asarray(bs.eigenvalues)
    labels = [Counter(bs.labels[:, j].tolist()).most_common(1)[0][0] for j in range(lam.shape[1])]
    return {"parameter": bs.parameter, "values": np.asarray(bs.values).tolist(), "gamma": gamma,
            "re": finite_or_none(lam.real), "im": finite_or_none(lam.imag), "labels": labels,
            "error": bs.error if math.isfinite(bs.error) else None, "N": bs.N, "N_check": bs.N_check,
            "max_re": float(np.nanmax(lam.real)) if np.isfinite(lam.real).any() else None,
            "time_s": bs.time}


#: damping multipliers of the sensitivity table (the mission's damping is often an estimate)
DAMPING_FACTORS = (0.25, 0.5, 1.0, 2.0, 4.0)


def damping_sensitivity(state: eq.Equilibrium, scales: Scales) -> list[DampingSensitivity]:
    """Least-damped mode of a state for the scene's damping times DAMPING_FACTORS (one operator, rung 3)."""
    op = damped_operator(state.params, state, state.N)
    rows = []
    for k in DAMPING_FACTORS:
        g = k * state.params.gamma
        lam = operator_eigenvalues(op, g, 20, False)
        z = lam[int(np.argmax(lam.real))]
        rows.append({"factor": k, "gamma": g, "damping_time_s": scales.damping_time(g), "growth_rate_per_s": float(scales.rad_s(z.real)),
                     "damping_ratio": float(-z.real / abs(z)) if abs(z) else None,
                     "decay_time_s": float(-1.0 / scales.rad_s(z.real)) if z.real < 0 else None,
                     "stable": bool(z.real <= THRESHOLD)})
    return rows


def secondary_pitchfork_at(params: RodParameters, omega: float, N: int, N_check: int | None, B_ref: float,
                           B_max: float = 60.0):
    """b1's secondary pitchfork at spin omega (b1 is continued from B_ref only up to its first
    secondary pitchfork); None if there is none below B_max."""
    try:
        return secondary_pitchfork(params, omega, N=N, N_check=N_check, B_ref=B_ref, B_max=B_max)
    except ValueError:
        return None


def coil_region(params: RodParameters, scales: Scales, omega_max: float, liftoff_omega: float, n: int = 6,
                N: int = 24, n_edge: int = 41) -> CoilRegion:
    """The stable region of b1 in the (load, spin) plane at the scene's tension (damping-independent).

    Its lower edge is b1's pitchfork on the straight tether (the class-S1
    static load), its upper edge the secondary pitchfork B*(omega). The lower
    edge is cheap (one linear eigenproblem per spin) and is located exactly at
    ``n_edge`` spins from 0 to ``omega_max`` (dimensionless; b1 lifts off at
    ``liftoff_omega``). The upper edge costs a continuation of b1 per spin: it
    is located exactly at ``n`` spins (the ``rows``) and drawn between them by
    the monotone cubic (PCHIP) interpolant through those points (B*(omega) is
    smooth and increasing); its interpolation error is estimated by leaving
    each interior point out and comparing the interpolant of the others with
    it. One resolution N (a drawing of the region; the margin at the
    operating spin is computed at two). With damping, stability changes only
    at these static points (Kelvin-Tait-Chetaev), so the region between them
    is the stable region of the coil. JSON-able, with SI.
    """
    t0 = time.perf_counter()
    lift = liftoff_omega
    rows = []
    # b1 is reached at B_ref by continuation in spin: above b1's pitchfork at rest (which falls with spin)
    # and below its secondary pitchfork (about 3.3 times it for SET)
    B_ref = 1.5 * float(pitchforks.class_loads(params.with_(B=0.0, omega=0.0), "S1", N, n=1)[0])
    b1_spin_branch(params, B_ref, omega_max, N)  # one continuation in spin serves every row

    def pitchfork(w: float) -> float | None:
        if math.isfinite(lift) and w >= lift:
            return None
        loads = pitchforks.class_loads(params.with_(B=0.0, omega=float(w)), "S1", N, n=1)
        return float(loads[0]) if loads.size else None

    for w in np.linspace(0.0, omega_max, n):
        p = params.with_(omega=float(w))
        pt = secondary_pitchfork_at(p, float(w), N, N, B_ref)
        star = pt.B if pt is not None else math.inf
        rows.append({"omega": float(w), "spin_rpm": float(scales.rpm(w)),
                     "pitchfork_B": pitchfork(float(w)),
                     "secondary_B": star if math.isfinite(star) else None})
    for r in rows:
        for k in ("pitchfork_B", "secondary_B"):
            r[k.replace("_B", "_IB0_N_per_m")] = None if r[k] is None else scales.line_load(r[k])
    edge_w = np.linspace(0.0, omega_max, n_edge)
    if math.isfinite(lift) and 0.0 < lift < omega_max:
        edge_w = np.sort(np.append(edge_w[edge_w < lift], lift))
    edge = [pitchfork(float(w)) for w in edge_w]
    edge = [0.0 if (e is None and math.isfinite(lift) and w >= lift) else e for w, e in zip(edge_w, edge)]
    curve, interp_error = secondary_curve(rows, n_edge)
    return {"rows": rows, "N": N, "liftoff_omega": lift if math.isfinite(lift) else None,
            "liftoff_rpm": lift * scales.spin_rpm if math.isfinite(lift) else None,
            "pitchfork_curve": {"omega": edge_w.tolist(), "spin_rpm": (edge_w * scales.spin_rpm).tolist(),
                                "B": edge, "IB0_N_per_m": [None if e is None else scales.line_load(e) for e in edge]},
            "secondary_curve": {"omega": curve[0], "spin_rpm": [w * scales.spin_rpm for w in curve[0]], "B": curve[1],
                                "IB0_N_per_m": [scales.line_load(b) for b in curve[1]],
                                "interpolation": "PCHIP through the rows",
                                "interpolation_error_B": interp_error,
                                "interpolation_error_IB0_N_per_m": None if interp_error is None
                                else scales.line_load(interp_error)},
            "time_s": time.perf_counter() - t0}


def _pchip(rows: list[dict]):
    pts = [(r["omega"], r["secondary_B"]) for r in rows if r["secondary_B"] is not None]
    if len(pts) < 2:
        return None, pts
    w, b = np.array(pts).T
    return Pchip.through(w, b), pts


def secondary_curve(rows: list[dict], n: int = 41) -> tuple[tuple[list, list], float | None]:
    """B*(omega) drawn through the exactly located rows (PCHIP: monotone, no overshoot) at ``n``
    spins, and its leave-one-out interpolation error (max over interior rows; None with < 4 rows)."""
    f, pts = _pchip(rows)
    if f is None:
        return ([p[0] for p in pts], [p[1] for p in pts]), None
    w = np.linspace(pts[0][0], pts[-1][0], n)
    err = None
    if len(pts) >= 4:
        wa, ba = np.array(pts).T
        err = max(abs(float(Pchip.through(np.delete(wa, i), np.delete(ba, i))(wa[i])) - ba[i])
                  for i in range(1, len(pts) - 1))
    return (w.tolist(), [float(v) for v in f(w)]), err


def spin_limit(region: dict, B: float) -> float | None:
    """Lowest spin (dimensionless) at which the coil at load B is still below its secondary
    pitchfork, on the region's PCHIP curve through its table (B*(omega) increases with spin, Sec. VIII); 0 if stable
    at rest, None if B is above B* everywhere in the table."""
    rows = [r for r in region["rows"] if r["secondary_B"] is not None]
    if not rows:
        return None
    if B < rows[0]["secondary_B"]:
        return 0.0
    f, _ = _pchip(rows)
    for a, b in zip(rows[:-1], rows[1:]):
        if a["secondary_B"] <= B < b["secondary_B"]:  # on the drawn (PCHIP) curve: monotone between the rows
            from scipy.optimize import brentq

            return float(brentq(lambda w: float(f(w)) - B, a["omega"], b["omega"], xtol=1e-12))
    return None
