"""Rungs 2 and 3 for a mission: the buckled tether, in the numbers an engineer reads.

Everything is solved dimensionless in :mod:`etcheck.rod.buckled.branches` (whirling
equilibria, continuation, branch switching) and :mod:`etcheck.rod.core.spectrum`
(the linearisation about a buckled state); this module chooses what to ask
(which branches, how far, which shapes) and returns JSON-able data with the
dimensionless values and their SI counterparts (lengths in m, loads in N/m,
forces in N, moments in N m) from the mission's :class:`~etcheck.scaling.Scales`.

Branch labels follow the paper: b(2k-1) is the branch of the k-th pitchfork
in Fix(S1), b(2k) the one in Fix(S2), b(2k-1)(2k) the connecting branch that
leaves b(2k-1) at its symmetry-breaking (secondary) pitchfork. A branch whose
pitchfork has reached B = 0 (lift-off under spin) no longer starts on the
straight tether; the labels of the branches above it keep their numbers.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from etcheck.checks.results.sections_buckled import (
    BifurcationDiagram,
    BranchRecord,
    BuckledOperatingPoint,
    PostbucklingSection,
    Shape,
    SpecialPoint,
)
from etcheck.checks.rungs.coil import (
    branch_stability,
    coil_region,
    damping_sensitivity,
    eigenvalue_paths,
    path_spectra,
    spin_limit,
    state_stability,
)
from etcheck.errors import SolverError
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled.branches import (
    Branch,
    ResolutionCheck,
    class_starts,
    connecting_branch,
    continue_branch,
    locate,
    primary_branches,
    resolution_check,
    state_at,
)
from etcheck.rod.buckled.pitchforks import LiftoffSpin, class_loads, liftoff_estimate, pitchfork_loads
from etcheck.rod.buckled.secondary import secondary_pitchfork
from etcheck.rod.buckled.spectra import BranchSpectra
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import spectrum
from etcheck.rod.straight.collocation.spectral import THRESHOLD
from etcheck.runtime.parallel import split_map
from etcheck.scaling import Scales

#: arc-length samples of a drawn shape
SHAPE_POINTS = 121
#: relative cost per state of a primary branch, the weights by which the items are shared between two cores
#: (measured on SET at omega = 0.25, one core): its record with the eigenvalue paths and its stability from them,
#: without them, its stability then, and the continuation of the connecting branch that leaves it (about twice its
#: points, and the branch point where it ends)
COST = {"paths": 1.1, "record": 0.07, "stability": 0.13, "connect": 1.3}
#: expected seconds (the same measurement): a lift-off spin, a class's restricted pencil and loads, and the start
#: and continuation of one primary branch
COST_START = {"liftoff": 0.6, "class": 0.3, "primary": 0.6}


@dataclass(frozen=True)
class DiagramOptions:
    """What a bifurcation diagram contains (dimensionless settings).

    ``branches``: number of primary branches still attached to the straight
    tether at the scene's spin (b1, b2, ... in order; lifted-off ones are
    listed, not counted);
    ``B_max``: end of the load range (None: 3, or 1.3 x the highest pitchfork);
    ``N``: Chebyshev resolution of the equilibria; ``connect``: follow the
    connecting branches (b12, b34, ...); ``stability``: mark each point stable
    or unstable (rung 3, at the scene's damping); ``paths``: the labels of the
    branches whose eigenvalue paths are computed (default b1 and b12, the paper's
    Figs. 9 and 10; None: every branch; (): none); ``shape_measure``: measure_1
    at which the shapes are drawn (the paper's Fig.
    Fig. 7 uses 0.04).
    """

    branches: int = 3
    B_max: float | None = None
    N: int = 32
    connect: bool = True
    stability: bool = True
    shape_measure: float = 0.04
    max_points: int = 400
    paths: tuple[str, ...] | None = ("b1", "b12")

    def with_paths(self, label: str) -> bool:
        """Whether the eigenvalue paths of branch ``label`` are computed."""
        return self.stability and (self.paths is None or label in self.paths)


#: the default diagram (b1, b2, b3 with stability, paths of b1 and b12)
DEFAULT_DIAGRAM = DiagramOptions()


@dataclass(frozen=True)
class BranchStability:
    """The stability of each state of a branch at the scene's damping (rung 3): ``stable`` (None where the
    spectrum did not converge), the largest growth rate Re(lambda) and its two-resolution error (dimensionless)."""

    stable: list[bool | None]
    max_growth: list[float | None]
    growth_error: list[float | None]

    def entries(self) -> dict:
        """The stability keys of a branch's record."""
        return {"stable": self.stable, "max_growth": self.max_growth, "growth_error": self.growth_error}


@dataclass(frozen=True, eq=False)
class Diagram:
    """A bifurcation diagram: its record (JSON-able: what the report draws and results.json holds), the
    continued primary branches by label and, where computed, their states' stability by label."""

    record: BifurcationDiagram
    branches: dict[str, Branch]
    stability: dict[str, BranchStability]


@lru_cache(maxsize=256)
def _liftoff_cached(P: float, R: float, Gamma: float, f: float, T: float, which: str, k: int) -> LiftoffSpin:
    return liftoff_estimate(RodParameters(P=P, R=R, Gamma=Gamma, f=f, T=T), which=which, k=k, N=24)


def liftoff_spin_estimate(params: RodParameters, which: str = "b1", k: int = 1) -> LiftoffSpin:
    """Spin at which the k-th branch of class b1 (S1) or b2 (S2) lifts off, with its two-resolution
    error (straight-rod pencils at N = 24 and 36; memoised)."""
    return _liftoff_cached(params.P, params.R, params.Gamma, params.f, params.T, which, k)


def liftoff(params: RodParameters, which: str = "b1", k: int = 1) -> float:
    """The lift-off spin of :func:`liftoff_spin_estimate` (NaN when the branch does not lift off)."""
    return liftoff_spin_estimate(params, which, k).omega


def _finite(x: float) -> float | None:
    return x if math.isfinite(x) else None


def _b1_to(params: RodParameters, N: int) -> tuple[Any, Branch | None, str]:
    """b1's start and its continuation to the operating load, or the reason why there is none."""
    w = liftoff(params)
    if math.isfinite(w) and params.omega >= w:
        return None, None, (f"b1 has lifted off at omega = {w:.6g} (operating omega = {params.omega:.6g}): "
                            "no buckled state grows from the straight tether here")
    start = next(s for s in primary_branches(params.with_(B=0.0), 1, N) if s.which == "S1")
    if params.B <= start.load:
        return start, None, "the operating load is below b1's pitchfork: the tether is straight"
    if params.B > MAX_LOAD_RATIO * start.load:
        return start, None, f"more than {MAX_LOAD_RATIO:g} times b1's pitchfork load (many coils): not assessed"
    branch = continue_branch(params, start, stop=(0.0, params.B * (1 + 1e-9)), N=N, max_points=800)
    if branch.values[-1] < params.B * (1 - 1e-9):
        return start, None, f"b1 could not be followed to the operating load ({branch.reason})"
    return start, branch, ""


def _labels(params: RodParameters, n: int, known: dict[int, LiftoffSpin] | None = None
            ) -> list[tuple[str, str, int, LiftoffSpin]]:
    """(label, symmetry, k-th pitchfork of its class, lift-off spin with its error) of branches b1, b2, ... until n of them
    are still attached to the straight tether at the scene's spin (lifted-off ones are listed too); ``known``:
    lift-off spins already computed, by branch number (the others are computed here)."""
    out, attached, j = [], 0, 0
    none = LiftoffSpin(math.nan, math.nan, 24, 36)
    known = dict(known or {})
    while attached < n and j < n + 8:
        j += 1
        which = "S1" if j % 2 else "S2"
        kk = (j + 1) // 2
        w = (known[j] if j in known else _liftoff_of(params, j)) if params.omega > 0 else none
        out.append((f"b{j}", which, kk, w))
        attached += not (math.isfinite(w.omega) and params.omega >= w.omega)
    return out


@dataclass(frozen=True)
class _Primary:
    """A primary branch of a diagram: its label, class, place k among its class's pitchforks, lift-off spin,
    pitchfork load (check resolution) with its error, and the branch continued from there."""

    label: str
    which: str
    k: int
    liftoff: LiftoffSpin
    load: tuple[float, float]
    branch: Branch


def _load_range(loads: list[float]) -> float:
    """End of a diagram's load range: 3, or 1.3 times the highest pitchfork drawn."""
    return max(3.0, 1.3 * max(loads, default=0.0))


def _primaries(params: RodParameters, options: DiagramOptions) -> tuple[list[_Primary], list[dict], float]:
    """The attached primary branches of a diagram (continued), the lifted-off ones, and the end of the load range.

    The lift-off spins of b1..bn decide which branches are attached; beside them (on two cores) the primary
    branches are started and continued as if none had lifted off: the k-th attached branch of a class starts at
    its class's k-th pitchfork whatever its label, so that work is kept unless lift-offs change the count of a
    class or the load range (then the branches concerned are continued again).
    """
    p0 = params.with_(B=0.0)
    n = options.branches
    guess = {"S1": tuple(range(1, (n + 1) // 2 + 1)), "S2": tuple(range(1, n // 2 + 1))}
    B_guess = options.B_max or _load_range(
        [float(x) for c, ks in guess.items() if ks for x in class_loads(p0, c, options.N, len(ks))])
    tasks = [("liftoff", j) for j in range(1, n + 1) if params.omega > 0] + [
        ("class", c, (k,)) for c, ks in guess.items() for k in ks]  # one branch per task: balanced

    def run(task):
        if task[0] == "liftoff":
            return _liftoff_of(params, task[1])
        try:
            return _class_branches(params, task[1], task[2], options, B_guess)
        except (ValueError, SolverError) as exc:  # a guessed branch that may not be needed: raised below if it is
            return exc

    done = split_map(run, tasks, weights=[COST_START["liftoff"] if t[0] == "liftoff" else
                                          COST_START["class"] + COST_START["primary"] * len(t[2]) for t in tasks])
    made = {(t[1], k): one for t, r in zip(tasks, done) if t[0] == "class" and not isinstance(r, Exception)
            for k, one in zip(t[2], r)}
    labels = _labels(params, n, {t[1]: r for t, r in zip(tasks, done) if t[0] == "liftoff"})
    lifted = [{"label": lab, "liftoff_omega": w.omega, "liftoff_omega_error": _finite(w.error)}
              for lab, _, _, w in labels if math.isfinite(w.omega) and params.omega >= w.omega]
    # the k-th attached branch of a class starts at that class's k-th pitchfork (lifted ones are gone)
    count = {"S1": 0, "S2": 0}
    order = []
    for lab, which, _, w in labels:
        if not (math.isfinite(w.omega) and params.omega >= w.omega):
            count[which] += 1
            order.append((lab, which, count[which], w))
    B_max = options.B_max or _load_range(
        [float(class_loads(p0, c, options.N, count[c])[-1]) for c in count if count[c]])
    todo = [(which, k) for _, which, k, _ in order if (which, k) not in made or B_max != B_guess]
    for (c, k), (again,) in zip(todo, split_map(lambda ck: _class_branches(params, ck[0], (ck[1],), options, B_max),
                                                todo)):
        made[(c, k)] = again
    attached = [_Primary(lab, which, k, w, made[(which, k)][1], made[(which, k)][2]) for lab, which, k, w in order]
    return attached, lifted, B_max


def _class_branches(params: RodParameters, which: str, ks: tuple[int, ...], options: DiagramOptions, B_max: float
                    ) -> list[tuple[Any, tuple[float, float], Branch]]:
    """(start, pitchfork load at the check resolution and its error, continued branch) of the k-th pitchforks
    of a class, k in ``ks`` (the load at resolution N and error inf where the check resolution has no k-th)."""
    p0 = params.with_(B=0.0)
    starts = class_starts(p0, which, ks, options.N)
    pl = pitchfork_loads(p0, which, options.N, max(ks))
    out = []
    for k, st in zip(ks, starts):
        load = (float(pl.loads[k - 1]), float(pl.errors[k - 1])) if pl.loads.size >= k else (st.load, math.inf)
        out.append((st, load, continue_branch(params, st, stop=(0.0, B_max), N=options.N,
                                              max_points=options.max_points)))
    return out


def _liftoff_of(params: RodParameters, j: int) -> LiftoffSpin:
    """Lift-off spin of branch b<j> (odd j: class b1 (S1), even j: class b2 (S2)), with its error."""
    return liftoff_spin_estimate(params, "b1" if j % 2 else "b2", (j + 1) // 2)


def _shape(state: eq.Equilibrium, scales: Scales) -> Shape:
    s = np.linspace(0.0, 1.0, SHAPE_POINTS)
    x = state.x0(s)
    return {"s": s.tolist(), "x": x[:, 0].tolist(), "y": x[:, 1].tolist(), "z": x[:, 2].tolist(),
            "x_m": scales.distance(x[:, 0]).tolist(), "y_m": scales.distance(x[:, 1]).tolist(),
            "z_m": scales.distance(x[:, 2]).tolist()}


def _branch_data(branch: Branch, label: str, scales: Scales, options: DiagramOptions, gamma: float,
                 check: ResolutionCheck | None = None, stability: bool = True
                 ) -> tuple[BranchRecord, BranchStability | None]:
    """The record of a branch and the stability of its states where the record has it (``check``: its resolution
    check, when already made; ``stability=False``: without its stability, which :func:`_with_stability` adds,
    unless its eigenvalue paths are computed: their spectra give it)."""
    t0 = time.perf_counter()
    check = resolution_check(branch) if check is None else check
    out = branch.summary() | {
        "label": label,
        "points": len(branch.values),
        "IB0_N_per_m": scales.line_load(np.asarray(branch.values)).tolist(),
        "max_deflection_m": scales.distance(branch.max_deflection).tolist(),
        "measure1_error": check.measure1_error,
        "deflection_error": check.deflection_error,
        "N_check": check.N_check,
        "special": [_special_point(q, scales) for q in branch.special],
    }
    stab = None
    if options.stability:
        paths = path_spectra(branch, gamma) if options.with_paths(label) else None
        if stability or paths is not None:  # a branch's paths decide its probed states' stability as well
            stab = _stability(branch, gamma, paths)[0]
            out |= stab.entries()
        if paths is not None:
            out["eigenvalue_paths"] = eigenvalue_paths(paths)
    shapes = {}
    try:
        B, st = locate(branch, eq.measure1, options.shape_measure)
        shapes[f"measure1={options.shape_measure:g}"] = _shape(st, scales) | {"B": B, "measure1": eq.measure1(st)}
    except ValueError:
        pass
    shapes["end"] = _shape(branch.states[-1], scales) | {"B": float(branch.values[-1]),
                                                         "measure1": float(branch.measure1[-1])}
    out["shapes"] = shapes
    out["check_time"] = time.perf_counter() - t0
    return out, stab


def _special_point(q, scales: Scales) -> SpecialPoint:
    """A located special point of a branch with the measures of its state (the nearer end of its final bracket,
    within the located width of the point: where the figures mark it)."""
    ms = eq.measures(q.state)
    return {"kind": q.kind, "B": q.value, "IB0_N_per_m": scales.line_load(q.value), "measure1": q.measure1,
            "measure2": ms.measure2, "max_deflection_m": scales.distance(ms.max_deflection), "bracket": list(q.bracket)}


def _second_step(attached: list[_Primary], options: DiagramOptions) -> list[tuple[str, str]]:
    """The items of a diagram's second step, in the order of its records: per primary branch its record ("paths"
    when its eigenvalue paths are drawn, with its stability from their spectra; else "record" and its "stability"),
    and the "connect"ing branch that leaves its secondary pitchfork (S1 branches)."""
    jobs = []
    for a in attached:
        paths = options.with_paths(a.label)
        jobs.append((a.label, "paths" if paths else "record"))
        if options.stability and not paths:
            jobs.append((a.label, "stability"))
        if options.connect and a.which == "S1" and any(q.kind == "break" for q in a.branch.special):
            jobs.append((a.label, "connect"))
    return jobs


def _stability(branch: Branch, gamma: float, paths: BranchSpectra | None = None) -> tuple[BranchStability, float]:
    """The stability of a branch's states (:func:`~etcheck.checks.rungs.coil.branch_stability`, from the spectra of its
    eigenvalue ``paths`` where computed) and the seconds it took."""
    t0 = time.perf_counter()
    stable, growth, errs = branch_stability(branch, gamma, paths)
    return BranchStability(stable, growth, errs), time.perf_counter() - t0


def _with_stability(record: BranchRecord, stability: tuple[BranchStability, float]) -> BranchRecord:
    """A record made with ``stability=False`` and its branch's :func:`_stability`: the same record, in the same
    order, as one made in one go."""
    entries, spent = stability
    i = min(list(record).index(k) for k in ("eigenvalue_paths", "shapes") if k in record)  # where they stand
    items = list(record.items())
    out = dict(items[:i]) | entries.entries() | dict(items[i:])
    out["check_time"] = record["check_time"] + spent
    return out


def bifurcation_diagram(params: RodParameters, scales: Scales, options: DiagramOptions = DEFAULT_DIAGRAM
                        ) -> BifurcationDiagram:
    """Branches of whirling equilibria of the tether in the load B (rung 2), with stability (rung 3).

    ``params`` fixes omega, T, R, ... (B is the continuation parameter).
    Returns JSON-able data: per branch its label, symmetry class, pitchfork
    load (at the check resolution N + max(8, N // 2), with the change from N
    as its error; the branch itself starts at its N value), lift-off spin
    with its error, points (B, measure_1, measure_2, max deflection; I·B0 in
    N/m and deflection in m), special points (folds, branch points), shapes, cost,
    the two-resolution error and, with ``options.stability``, the stability
    of every point at the scene's damping.
    """
    return diagram(params, scales, options).record


def diagram(params: RodParameters, scales: Scales, options: DiagramOptions = DEFAULT_DIAGRAM) -> Diagram:
    """:func:`bifurcation_diagram`'s record with the continued primary branches and their states' stability."""
    t_all = time.perf_counter()
    attached, lifted, B_max = _primaries(params, options)
    kept: dict[str, Branch] = {a.label: a.branch for a in attached}
    info = {a.label: a for a in attached}

    def primary_record(lab: str) -> tuple[BranchRecord, BranchStability | None]:
        a = info[lab]
        B_pf, B_pf_error = a.load
        rec, stab = _branch_data(a.branch, lab, scales, options, params.gamma, stability=False)
        return rec | {
            "pitchfork_B": B_pf, "pitchfork_B_error": _finite(B_pf_error),
            "pitchfork_IB0_N_per_m": scales.line_load(B_pf), "symmetry": a.which,
            "liftoff_omega": _finite(a.liftoff.omega), "liftoff_omega_error": _finite(a.liftoff.error)}, stab

    def first(job):
        """A primary branch's record without its stability, or that stability (the spectra of its probe states),
        or the continuation of the connecting branch that leaves it (and its resolution check: serial work, done
        where the branch is)."""
        lab, kind = job
        if kind == "connect":
            con = connecting_branch(kept[lab], stop=(0.0, B_max), max_points=options.max_points)
            return con, resolution_check(con)
        if kind == "stability":
            return _stability(kept[lab], params.gamma)
        return primary_record(lab)

    jobs = _second_step(attached, options)
    # On two cores in two steps (each the same records as one by one): the primary branches' records and, as items
    # of their own, their stability, beside the connecting branches' continuations, balanced by their expected
    # cost (COST, per state of the parent branch: the last items to finish are small); then each connecting
    # branch's record, whose states' spectra are independent (split over both cores)
    weights = [len(kept[lab].states) * COST[kind] for lab, kind in jobs]
    firsts = dict(zip(jobs, split_map(first, jobs, weights=weights)))

    stabilities: dict[str, BranchStability] = {}

    def record(lab: str, kind: str) -> BranchRecord:
        done = firsts[(lab, kind)]
        if kind == "connect":
            return _branch_data(done[0], f"b{int(lab[1:])}{int(lab[1:]) + 1}", scales, options, params.gamma,
                                done[1])[0] | {"symmetry": None, "from": lab}
        rec, stab = done
        stability = firsts.get((lab, "stability"))
        if stability is not None:
            rec, stab = _with_stability(rec, stability), stability[0]
        if stab is not None:
            stabilities[lab] = stab
        return rec

    out_branches = [record(lab, kind) for lab, kind in jobs if kind != "stability"]
    if not out_branches and not lifted:
        raise SolverError("rung 2: no branch was found")
    return Diagram({
        "model": "rung 2 (whirling equilibria, pseudo-arclength continuation)"
        + (" + rung 3 (stability of each state)" if options.stability else ""),
        "params": {k: getattr(params, k) for k in ("P", "R", "Gamma", "f", "omega", "T", "gamma")},
        "B_max": B_max,
        "IB0_max_N_per_m": scales.line_load(B_max),
        "N": options.N,
        "branches": out_branches,
        "lifted_off": lifted,
        "paths_computed": [b["label"] for b in out_branches if "eigenvalue_paths" in b],
        "time_s": time.perf_counter() - t_all,
    }, kept, stabilities)


def operating_state(params: RodParameters, scales: Scales, N: int = 32, branch: Branch | None = None) -> BuckledOperatingPoint:
    """The post-buckled tether at the operating load on b1 (rung 2) and its stability (rung 3).

    For an operating B past b1's pitchfork at the operating spin and tension;
    ``branch`` is b1 already continued past the operating load (else it is
    continued here). Returns shape (m), maximum lateral deflection (m), end
    forces (N) and moments (N m) in the rotating frame, the least-damped
    eigenvalue (in 1/s and Hz, with damping ratio), and the two-resolution
    errors. Raises :class:`~etcheck.errors.SolverError` if b1 cannot be
    followed there.
    """
    t0 = time.perf_counter()
    if branch is None:
        start, branch, why = _b1_to(params, N)
        if branch is None:
            if start is not None and params.B > start.load:
                raise SolverError(f"rung 2: {why}")
            return {"available": False, "reason": why}
    lo, hi = float(np.min(branch.values)), float(np.max(branch.values))
    if not lo <= params.B <= hi:  # e.g. past the straight tether's first loss of stability, short of b1's pitchfork
        return {"available": False,
                "reason": f"b1 spans B = {lo:.6g} .. {hi:.6g} at this spin and tension and does not reach the operating "
                          f"load B = {params.B:.6g}: the straight tether first loses stability to another mode here"}
    st = state_at(branch, params.B)
    B = st.params.B
    check = resolution_check(branch)
    ms = eq.measures(st)
    sp = spectrum(st.params, base=st, k=8, tol=1e-6)
    lam = sp.eigenvalues
    i = int(np.argmax(lam.real)) if lam.size else None
    least = None
    if i is not None:
        z = lam[i]
        least = {"re": float(z.real), "im": float(z.imag), "growth_rate_per_s": float(scales.rad_s(z.real)),
                 "frequency_Hz": float(scales.hz(abs(z.imag))),
                 "damping_ratio": float(-z.real / abs(z)) if abs(z) else None,
                 "decay_time_s": float(-1.0 / scales.rad_s(z.real)) if z.real < 0 else None,
                 "error": float(sp.errors[i])}
    return {
        "damping_sensitivity": damping_sensitivity(st, scales),
        "available": True,
        "branch": "b1",
        "B": B,
        "measure1": ms.measure1,
        "max_deflection": ms.max_deflection,
        "max_deflection_m": scales.distance(ms.max_deflection),
        "end_shortening_m": scales.distance(ms.end_shortening),
        "end_force_N": {"s=0": [scales.tension(v) for v in ms.F0], "s=L": [scales.tension(v) for v in ms.F1]},
        "end_moment_N_m": {"s=0": [scales.moment(v) for v in ms.M0], "s=L": [scales.moment(v) for v in ms.M1]},
        "shape": _shape(st, scales),
        "deflection_error_m": scales.distance(check.deflection_error),
        "residual": st.residual_norm,
        "N": N,
        "N_check": check.N_check,
        "stable": bool(sp.converged and lam.size and np.max(lam.real) <= THRESHOLD),
        "spectrum_converged": bool(sp.converged),
        "least_damped": least,
        "points": len(branch.values),
        "time_s": time.perf_counter() - t0,
    }


#: beyond this multiple of the first critical load the tether has many coils: rung 2 is not attempted
MAX_LOAD_RATIO = 6.0


@dataclass(frozen=True)
class SecondaryPitchforkLoad:
    """b1's first secondary pitchfork B* (dimensionless) with its relative error, or None and the reason why
    there is none."""

    B: float | None
    error: float | None
    reason: str


NO_SECONDARY = SecondaryPitchforkLoad(None, None, "no secondary pitchfork on b1 in the computed range")


def _secondary_pitchfork(params: RodParameters, branch: Branch, N: int) -> SecondaryPitchforkLoad:
    """b1's first secondary pitchfork at the scene's spin: :func:`~etcheck.rod.buckled.secondary_pitchfork`
    (the one implementation of B*) on the diagram's b1 at N and b1 recomputed at 1.5 N; the value at 1.5 N,
    its relative error estimate (the change from N), or the reason why there is none."""
    try:
        pt = secondary_pitchfork(params, params.omega, N=N, N_check=N + N // 2, branch=branch)
    except ValueError:
        return NO_SECONDARY
    except SolverError as exc:
        return SecondaryPitchforkLoad(None, None, f"not converged: {exc}")
    return SecondaryPitchforkLoad(pt.B, pt.error / pt.B, "")


def postbuckling_check(params: RodParameters, scales: Scales, B_c: float, required: float, N: int = 32) -> PostbucklingSection:
    """Rung 2/3 answers for a scene near or past its first critical load B_c (dimensionless).

    The first branch b1 at the operating spin and tension (with stability at
    the scene's damping) up to past the operating load, its secondary
    pitchfork (the end of its stable part), and, past B_c, the buckled state
    at the operating load (:func:`operating_state`). JSON-able.
    """
    t0 = time.perf_counter()
    ratio = params.B / B_c if B_c > 0 else math.inf
    base = {"B_c": B_c, "load_ratio": ratio}
    if ratio > MAX_LOAD_RATIO:
        return base | {"computed": False,
                       "reason": f"the operating load is {ratio:.3g} times the first critical load: the buckled tether "
                       f"has many coils, beyond rung 2's validated range (up to {MAX_LOAD_RATIO:g} times)"}
    # far enough for a stable coil without a secondary pitchfork to prove the required margin (within rung 2's range)
    B_max = max(1.5 * params.B, 5.0 * B_c, min(1.02 * required * params.B, MAX_LOAD_RATIO * B_c))
    opts = DiagramOptions(branches=1, connect=False, stability=True, paths=(), N=N, B_max=B_max)
    d = diagram(params, scales, opts)
    out = base | {"computed": True, "diagram": d.record}
    b1 = d.branches.get("b1")
    if b1 is not None:
        values, stable = [float(v) for v in b1.values], d.stability["b1"].stable
        first_unstable = next((v for v, st in zip(values, stable) if st is False), None)
        star = _secondary_pitchfork(params, b1, N) if any(q.kind == "break" for q in b1.special) else NO_SECONDARY
        out["secondary_pitchfork_B"] = star.B
        out["secondary_pitchfork_error"] = star.error
        out["secondary_pitchfork_IB0_N_per_m"] = None if star.B is None else scales.line_load(star.B)
        if star.reason:
            out["secondary_pitchfork_reason"] = star.reason
        out["b1_first_unstable_B"] = first_unstable
        out["b1_stable_at_start"] = bool(stable[1]) if len(stable) > 1 else None
        # no secondary pitchfork and every state from the operating load on stable: b1 is stable up to its end
        past = [st for v, st in zip(values, stable) if v >= params.B]
        bound = float(max(values)) if star.B is None and past and all(st is True for st in past) else None
        out["b1_stable_to_B"] = bound
        out["b1_stable_to_IB0_N_per_m"] = None if bound is None else scales.line_load(bound)
    else:  # e.g. lifted off at this spin: b1 does not leave the straight tether
        out |= {"secondary_pitchfork_B": None, "secondary_pitchfork_error": None,
                "secondary_pitchfork_IB0_N_per_m": None, "b1_first_unstable_B": None, "b1_stable_at_start": None,
                "b1_stable_to_B": None, "b1_stable_to_IB0_N_per_m": None,
                "secondary_pitchfork_reason": "b1 was not found at the operating spin and tension"}
    out["operating"] = None
    if params.B > B_c:
        if b1 is not None and b1.values[-1] >= params.B:
            out["operating"] = operating_state(params, scales, N, branch=b1)
        else:
            out["operating"] = operating_state(params, scales, N)
    if out["operating"] and out["operating"].get("available"):
        lift = liftoff_spin_estimate(params)
        region = coil_region(params, scales, omega_max=max(1.0, 2.0 * params.omega), liftoff_omega=lift.omega)
        region["liftoff_omega_error"] = _finite(lift.error)
        low = spin_limit(region, params.B)
        region |= {"operating_rpm": scales.rpm(params.omega),
                   "lowest_stable_spin_rpm": None if low is None else scales.rpm(low)}
        out["region"] = region
    out["time_s"] = time.perf_counter() - t0
    return out


@dataclass(frozen=True)
class BuckledPoint:
    """Whether the coiled state on b1 is stable at a straight-unstable point (None: not assessed, ``reason`` says
    why), and its largest lateral deflection (units of L)."""

    stable: bool | None
    max_deflection: float | None
    reason: str


def buckled_point(params: RodParameters, N: int = 24) -> BuckledPoint:
    """Is the tether stable on b1 at this (straight-unstable) point? Dimensionless, for sweeps.

    b1 exists when its pitchfork has not lifted off at this spin; it is
    followed from its pitchfork to the point's load and the state there is
    classified by its spectrum (rung 3, the scene's damping).
    """
    start, branch, why = _b1_to(params, N)
    if branch is None:
        return BuckledPoint(False if start is None else None, None, why)
    st = state_at(branch, params.B)
    flag, _, _ = state_stability(st, params.gamma)
    return BuckledPoint(flag, eq.measures(st).max_deflection, "" if flag is not None else "spectrum not converged")
