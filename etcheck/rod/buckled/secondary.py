"""Rung 3: states of the first post-buckling branch b1 at a load and spin, and its secondary
(symmetry-breaking) pitchfork B*(omega) (Secs. VII A and VIII of arXiv:0810.3668): where b1
loses stability to the connecting branch b12. Dimensionless.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from etcheck.errors import SolverError
from etcheck.jsonable import jsonable
from etcheck.rod.buckled import branches as br
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import (
    check_resolution,
)
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.parallel import split_map

__all__ = [
    "b1_direct",
    "b1_in_B",
    "b1_spin_branch",
    "b1_state",
    "first_break",
    "PitchforkCurve",
    "PitchforkPoint",
    "secondary_pitchfork",
    "secondary_pitchfork_curve",
]


# --- b1 states and the secondary pitchfork curve -----------------------------------------


@dataclass(frozen=True)
class PitchforkPoint:
    """Secondary pitchfork of b1 at spin omega (dimensionless).

    Located as the symmetry-breaking branch point of the Fix(S1) continuation
    of b1 in B (a bracketed root of the restricted test function) at two
    resolutions: ``B`` is the value at the finer one, max(``N``,
    ``N_check``), ``B_check`` the value at the other; ``error`` = |B -
    B_check|: the change of the coarser value, which bounds the error of the
    finer one (the collocation converges spectrally; checked against a much
    finer resolution in the tests). NaN when N_check = N (one resolution).
    ``measure1`` of the state there (finer resolution)."""

    omega: float
    B: float
    B_check: float
    error: float
    N: int
    N_check: int
    measure1: float
    time: float


@dataclass(frozen=True)
class PitchforkCurve:
    """The curve B*(omega) of secondary pitchforks of b1 (Secs. VII A, VIII; Fig. 19)."""

    points: tuple

    @property
    def omega(self) -> np.ndarray:
        return np.array([p.omega for p in self.points])

    @property
    def B(self) -> np.ndarray:
        return np.array([p.B for p in self.points])

    @property
    def error(self) -> np.ndarray:
        return np.array([p.error for p in self.points])

    def at(self, omega: float) -> float:
        """B*(omega) by linear interpolation in the table."""
        return float(np.interp(omega, self.omega, self.B))

    def as_dict(self) -> dict:
        return jsonable({"omega": self.omega, "B": self.B, "error": self.error,
                          "points": [p.__dict__ for p in self.points]})


def _b1_reference(params: RodParameters, B_ref: float, N: int):
    """State on b1 at (B_ref, omega = 0) (Fix(S1) continuation from BP1)."""
    p0 = params.with_(omega=0.0, gamma=0.0, T=params.T)
    start = br.primary_branches(p0, 1, N)[0]
    b = br.continue_branch(p0, start, stop=(0.0, B_ref + 0.2), ds=0.05)
    return br.state_at(b, B_ref)


_OMEGA_BRANCH_CACHE: dict = {}


@dataclass(frozen=True, eq=False)
class _Single:
    """A one-state stand-in for an omega branch that stays at omega = 0."""

    state: eq.Equilibrium

    @property
    def states(self) -> tuple:
        return (self.state,)

    @property
    def values(self) -> np.ndarray:
        return np.array([0.0])


def b1_spin_branch(params: RodParameters, B_ref: float, omega_max: float, N: int = 32):
    """b1 at fixed B = B_ref continued in omega from 0 to omega_max inside Fix(S1)
    (Figs. 17 and 18 use B_ref = 1.2):
    BP1 -> (B_ref, 0) in B, then in omega. A :class:`~etcheck.rod.buckled.branches.Branch`
    (parameter "omega"); cached per (P, R, Gamma, f, T, B_ref, N). Dimensionless."""
    key = (params.P, params.R, params.Gamma, params.f, params.T, B_ref, N)
    got = _OMEGA_BRANCH_CACHE.get(key)
    if got is not None and got.values[-1] >= omega_max - 1e-12:
        return got
    ref = _b1_reference(params, B_ref, N)
    if omega_max <= 0:
        return _Single(ref)
    bw = br.continue_branch(ref.params, ref, parameter="omega", stop=(-1e-9, max(omega_max, 1e-3) + 1e-9),
                            which="S1", ds=0.05, ds_max=0.25)
    if len(_OMEGA_BRANCH_CACHE) > 8:
        _OMEGA_BRANCH_CACHE.clear()
    _OMEGA_BRANCH_CACHE[key] = bw
    return bw


def _spin_state(params: RodParameters, B_ref: float, omega: float, N: int) -> eq.Equilibrium:
    """b1 at exactly (B_ref, omega): Newton at that spin from the omega branch
    (:func:`~etcheck.rod.buckled.branches.state_at`), then in the full space at the exact parameters."""
    bw = b1_spin_branch(params, B_ref, omega, N)
    if omega == 0:
        return bw.states[0]
    st = br.state_at(bw, omega)
    return eq.solve_equilibrium(st.params.with_(omega=float(omega), B=float(B_ref)), st)


@single_blas_thread
def b1_state(params: RodParameters, B: float, omega: float, N: int = 32, B_ref: float = 1.2) -> eq.Equilibrium:
    """The b1 equilibrium (Fix(S1), Sec. VII) at (B, omega), reached by continuation:
    BP1 -> (B_ref, 0) in B, -> (B_ref, omega) in omega, then Newton at (B, omega)
    from there if B != B_ref (no fold of b1 in B lies between, Sec. VII B).
    Dimensionless; raises SolverError if Newton fails."""
    st = _spin_state(params, B_ref, omega, N)
    if B == B_ref:
        return st
    b = br.continue_branch(st.params, st, parameter="B", stop=(min(B, B_ref) - 1e-9, max(B, B_ref) + 1e-9),
                           which="S1", ds=0.05, ds_max=0.2, direction=1.0 if B > B_ref else -1.0)
    st = br.state_at(b, B)
    return eq.solve_equilibrium(st.params.with_(B=float(B)), st)


_UP_CACHE: dict = {}


def _b1_up(params: RodParameters, omega: float, N: int, B_ref: float, B_max: float):
    """b1 at fixed omega continued in B upward from B_ref to its first secondary pitchfork (or
    B_max); cached per (P, R, Gamma, f, T, omega, N, B_ref), a cached branch serving every B_max
    it reached (the damping map and the B*(omega) curve continue the same b1)."""
    key = (params.P, params.R, params.Gamma, params.f, params.T, float(omega), int(N), float(B_ref))
    got = _UP_CACHE.get(key)
    if got is not None and (got.reason == "special point (break)" or got.values[-1] >= B_max):
        return got
    st = _spin_state(params, B_ref, omega, N)
    up = br.continue_branch(st.params, st, parameter="B", stop=(B_ref - 1e-9, B_max), which="S1", ds=0.05,
                            ds_max=0.25, stop_on=("break",))
    if len(_UP_CACHE) > 64:
        _UP_CACHE.clear()
    _UP_CACHE[key] = up
    return up


def b1_in_B(params: RodParameters, omega: float, N: int, B_ref: float, B_max: float, lower: float | None = None):
    """b1 at fixed omega continued in B upward from B_ref to its first secondary pitchfork
    (or B_max; :func:`_b1_up`), and downward to ``lower``."""
    up = _b1_up(params, omega, N, B_ref, B_max)
    st = up.states[0]
    down = None
    if lower is not None and lower < B_ref:
        down = br.continue_branch(st.params, st, parameter="B", stop=(lower, B_ref + 1e-9), which="S1", ds=0.05,
                                  ds_max=0.25, direction=-1.0)
    return up, down


def first_break(branch, above: float = -math.inf) -> br.RodBranchPoint | None:
    """The first symmetry-breaking branch point ("break") of ``branch`` with B > ``above``
    (None if there is none); raises :class:`~etcheck.errors.SolverError` when it was
    bracketed but not located (bracket wider than ``LOCATE_WIDTH``)."""
    brk = next((q for q in branch.special if q.kind == "break" and q.value > above), None)
    if brk is not None and not brk.converged:
        raise SolverError(f"secondary pitchfork of {branch.name} at N = {branch.N} not located: {brk.reason} "
                          f"(bracketed in B = [{brk.bracket[0]:.10g}, {brk.bracket[1]:.10g}])")
    return brk


def b1_direct(params: RodParameters, N: int, B_max: float):
    """b1 from its pitchfork at the scene's omega and T, continued in B up to its first secondary
    pitchfork (or B_max; Fix(S1))."""
    start = next(s for s in br.primary_branches(params.with_(B=0.0), 1, N) if s.which == "S1")
    return br.continue_branch(params, start, stop=(0.0, B_max), N=N, stop_on=("break",))


def _b1_near(branch, N: int, B_first: float, B_ref: float | None = None):
    """b1 at resolution N from its state on ``branch`` (b1 at the other resolution) last below 0.9 B_first,
    resampled and re-solved at N, continued in B to 5 % past B_first (Fix(S1)): the branch point there
    without following b1 again from its pitchfork (``B_ref`` None) or from (B_ref, omega), which it does when
    the branch has no such state."""
    below = [s for s in branch.states if s.params.B < 0.9 * B_first]
    if not below:
        if B_ref is None:
            return b1_direct(branch.params, N, B_first * (1.0 + 0.05))
        return b1_in_B(branch.params, branch.params.omega, N, B_ref, B_first * (1.0 + 0.05))[0]
    start = eq.solve_equilibrium(below[-1].params, below[-1], N)
    return br.continue_branch(start.params, start, stop=(0.0, B_first * (1.0 + 0.05)), N=N, which="S1", ds=0.05,
                              ds_max=0.25, stop_on=("break",))


@single_blas_thread
def secondary_pitchfork(params: RodParameters, omega: float, N: int = 32, N_check: int | None = None,
                        B_ref: float = 1.2, B_max: float = 20.0, branch=None) -> PitchforkPoint:
    """Secondary (symmetry-breaking) pitchfork of b1 at spin omega (Secs. VII A, VIII).

    The one implementation of B* (the check's margin, the B*(omega) curve of
    the damping map and the benchmarks all come here). b1 is continued inside
    Fix(S1) in B, either from (B_ref, omega) reached through spin (works past
    b1's lift-off) or, when ``branch`` is given (b1 at this omega from its
    pitchfork, as the check's diagram continues it), from its pitchfork at
    the same omega at the other resolution; the first zero of the Jacobian
    restricted to the -1 eigenspace of S1 (kind "break") is located as a
    bracketed root (:func:`first_break`). Done at N and N_check (default
    check_resolution(N)); see :class:`PitchforkPoint` (value at the finer
    resolution, error = the change of the coarser one). Raises ValueError
    when no secondary pitchfork lies below B_max, SolverError when it is not
    located. Dimensionless.
    """
    t0 = time.perf_counter()
    Nc = check_resolution(N) if N_check is None else int(N_check)
    if branch is not None and (branch.parameter != "B" or branch.which != "S1"
                               or branch.params.omega != omega or branch.N != int(N)):
        raise ValueError("branch must be b1 (Fix(S1)) continued in B at the given omega and resolution N")
    got, first = {}, branch
    for n in sorted({int(N), Nc}, key=lambda k: k != (branch.N if branch is not None else int(N))):
        if first is not None and n == first.N:
            brk = first_break(first, above=-math.inf if branch is not None else B_ref)
        elif first is not None:  # the other resolution: from the first one's state just below its B*
            brk = first_break(_b1_near(first, n, got[first.N][0], B_ref if branch is None else None))
        else:
            first, _ = b1_in_B(params, omega, n, B_ref, B_max)
            brk = first_break(first, above=B_ref)
        if brk is None:
            lo = 0.0 if branch is not None else B_ref
            hi = branch.values.max() if branch is not None and n == branch.N else B_max
            raise ValueError(f"no secondary pitchfork of b1 between B = {lo:g} and {hi:g} at omega = {omega} "
                             f"(N = {n})")
        got[n] = (float(brk.value), float(brk.measure1))
    fine, coarse = max(got), min(got)
    err = abs(got[fine][0] - got[coarse][0]) if fine != coarse else math.nan
    return PitchforkPoint(float(omega), got[fine][0], got[coarse][0], err, int(N), Nc, got[fine][1],
                          time.perf_counter() - t0)


@single_blas_thread
def secondary_pitchfork_curve(params: RodParameters, omegas, N: int = 32, N_check: int | None = None,
                              B_ref: float = 1.2, B_max: float = 20.0) -> PitchforkCurve:
    """B*(omega) of b1 at each omega of ``omegas`` (each point located exactly, two
    resolutions; :func:`secondary_pitchfork`). Dimensionless."""
    omegas = [float(w) for w in omegas]
    # one omega continuation serves every omega (the check resolution starts from these states: none there);
    # made here, before the spins are shared with a forked helper (two cores)
    b1_spin_branch(params, B_ref, max(omegas), int(N))
    return PitchforkCurve(tuple(split_map(lambda w: secondary_pitchfork(params, w, N, N_check, B_ref, B_max), omegas)))
