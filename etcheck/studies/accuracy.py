"""The speed/accuracy trade of the solvers for one mission's scene, measured (not a test).

Rung 1: time of one solve and error of the lowest eigenvalue pairs and of the
first static load versus the Chebyshev resolution N (reference N = 96 up to N = 64,
48 up to N = 32: :func:`etcheck.rod.straight.collocation.convergence.reference_resolution`), and the
automatic two-resolution solve as the check runs it. Rung 2: time and error of
tracing b1 from its pitchfork to 4 times that load versus N (reference N = 48).
BLAS on one thread.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from etcheck.checks.results.sections_straight import AccuracyRow
from etcheck.checks.rungs.straight import accuracy
from etcheck.rod.buckled import branches as br
from etcheck.rod.buckled import pitchforks
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import spectrum
from etcheck.runtime.blas import single_blas_thread
from etcheck.scaling import Scaled


@dataclass(frozen=True)
class AutomaticSolve:
    """The check's automatic stability solve: best time of 3 [s], resolutions, convergence, largest error."""

    time_s: float
    N: int
    N_check: int
    converged: bool
    max_error: float


def rung1_accuracy(scaled: Scaled, Ns: tuple[int, ...], pairs: int) -> tuple[tuple[AccuracyRow, ...], AutomaticSolve]:
    """Rows of (N, time per solve, eigenvalue error, B_c error) and the automatic solve."""
    rows = accuracy(scaled, Ns, k=pairs)
    best = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        auto = spectrum(scaled.params, k=pairs)
        best = min(best, time.perf_counter() - t0)
    return rows, AutomaticSolve(best, auto.N, auto.N_check, bool(auto.converged),
                                max(auto.errors, default=math.nan))


@dataclass(frozen=True)
class BranchTrace:
    """b1 from its pitchfork to 4 times that load at resolution N (dimensionless measures).

    ``secondary_pitchfork_B`` is None where b1 has no secondary pitchfork below 4 B_1; where b1 has
    lifted off the straight tether at the scene's spin (``liftoff_omega``, Sec. VII B: its pitchfork
    has reached B = 0) there is no b1 to trace: ``points`` is 0 and the measures are None.
    """

    N: int
    time_s: float
    points: int
    measure1_end: float | None
    secondary_pitchfork_B: float | None
    liftoff_omega: float | None = None


@single_blas_thread
def trace_b1(params: RodParameters, N: int) -> BranchTrace:
    """Continue b1 at the scene's spin and tension from its pitchfork to 4 B_1 at resolution N.

    Past b1's lift-off spin the first remaining pitchfork of its class belongs to a higher branch
    (b3), not to b1: the trace then says b1 has lifted off instead of following that branch.
    """
    t0 = time.perf_counter()
    if params.omega > 0:
        lift = pitchforks.liftoff_spin(params.with_(gamma=0.0), "b1", 1, N, omega_max=params.omega + 0.1)
        if math.isfinite(lift) and params.omega >= lift:
            return BranchTrace(N, time.perf_counter() - t0, 0, None, None, float(lift))
    start = next(s for s in br.primary_branches(params.with_(B=0.0), 1, N) if s.which == "S1")
    b1 = br.continue_branch(params, start, stop=(0.0, 4.0 * start.load), N=N)
    brk = next((float(q.value) for q in b1.special if q.kind == "break"), None)
    return BranchTrace(N, time.perf_counter() - t0, len(b1.values), float(b1.measure1[-1]), brk)


def rung2_accuracy(params: RodParameters, Ns: tuple[int, ...] = (20, 24, 32, 40),
                   N_ref: int = 48) -> tuple[BranchTrace, list[BranchTrace]]:
    """The reference trace and one trace per N (compare their measures and pitchforks)."""
    return trace_b1(params, N_ref), [trace_b1(params, N) for N in Ns]
