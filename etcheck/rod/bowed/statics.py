"""The bowed tether at rest: the nonlinear static equilibrium of the Kirchhoff rod under a field with a component
across the chord, its collocation, exact Jacobian and Newton solver (dimensionless, f-scaling of eq. (36)).

Equations (Sec. V A, eqs. (49)-(57) at omega = 0, the field B e3 replaced by B b of
:class:`etcheck.rod.bowed.field.CrossField`; erratum M_3^0 = Gamma (1 + R)/(2 f) kappa_3^0)::

    x'  = d3                                        (55)
    D K kappa - M = 0,  kappa = axial(D^T D')       (56), (57)
    F' + B i(s) d3 x b = 0                          (49)-(51) with e3 -> b
    M' + d3 x F = 0                                 (52)-(54) at omega = 0

with K = diag(1, R, Gamma (1+R)/2)/f. **End tension T**: the force along the chord at the sliding end,
F(0) . e3 = T (eq. (25), tension positive, as the paper's eqs. (58)-(69)); the lateral components of F(0) are the
reactions that hold that end on the chord. The ends stay on the chord: x1 = x2 = 0 at s = 0 and x = e3 at s = 1
(the chord has length 1). Welded ends hold the frame, d3 = e3 and d1 . e2 = 0 (eqs. (58)-(69)); pinned ends
(``params.ends``, :mod:`etcheck.rod.core.ends`) carry no bending moment, M . d1 = M . d2 = 0, and hold the twist,
d1 . e2 = 0.

Discretisation and Newton update are those of :mod:`etcheck.rod.buckled.equilibria` (the same
:class:`~etcheck.rod.buckled.equilibria.Equilibrium` states, rows and update (xi, a, phi, m)): its residual and
exact Jacobian are evaluated with B = 0 and welded ends, and the Lorentz rows (:func:`etcheck.rod.bowed.field.lorentz_block`)
and, for pinned ends, the moment rows (:func:`etcheck.rod.core.linear.end_rows`) are added here.

**At rest only.** With spin the field across the chord turns in the rotating frame: the load is time-periodic and
there is no relative equilibrium; omega != 0 raises ValueError.

**Resolution limit.** Under strong tension the rod is a string outside end layers of width
delta = sqrt(R/(f T)) (the weak axis's, the thinner; sqrt(EI2/T) in units). The layer's shape (an elastica,
~ arctan(exp(-s/delta))) has complex singularities a distance ~delta from the ends, so uniform Chebyshev
collocation converges geometrically in c = N sqrt(delta): measured, the end moments and the interior curvature agree
between resolutions to ~1e-4 (relative) at c = 4, ~1e-6 at c = 6, 1e-9 at c = 8. :func:`required_resolution` asks
for c >= LAYER_POINTS = 4, and N <= N_MAX = 256: the thinnest end layer resolved is
delta = (4/256)^2 = 2.4e-4 of the length (T <= 3.3e4 R in f-scaling with f = 500.56). Thinner layers (tapes,
R ~ 1e-6, under strong tension) need graded multi-domain collocation (as rung 1v's,
:mod:`etcheck.rod.straight.profiles`) and raise :class:`EndLayerError`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import scipy.linalg as sla

from etcheck.errors import SolverError
from etcheck.rod.bowed.field import CrossField, lorentz_block
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.ends import ALL_WELDED, PINNED, WELDED
from etcheck.rod.core.linear import NFIELDS, collocation, end_rows
from etcheck.rod.core.parameters import RodParameters

__all__ = [
    "LAYER_POINTS",
    "N_MAX",
    "EndLayerError",
    "end_layer",
    "required_resolution",
    "check_problem",
    "residual",
    "jacobian",
    "row_scale",
    "load_derivative",
    "solve",
]

#: Collocation points per 1/sqrt(delta) that resolve an end layer of width delta (module docstring).
LAYER_POINTS = 4.0
#: The finest resolution this module solves at (dense Jacobians of size 12 (N + 1)).
N_MAX = 256


class EndLayerError(ValueError):
    """The end layers are thinner than uniform Chebyshev collocation at N <= N_MAX resolves."""


def end_layer(params: RodParameters) -> float:
    """Width of the end layers sqrt(R / (f T)) (in units of the length; inf without tension)."""
    return math.sqrt(params.R / (params.f * params.T)) if params.T > 0 else math.inf


def required_resolution(params: RodParameters) -> int:
    """The least N that resolves the end layers (:data:`LAYER_POINTS` / sqrt(delta), at least 16)."""
    delta = end_layer(params)
    return 16 if not math.isfinite(delta) else max(16, math.ceil(LAYER_POINTS / math.sqrt(delta)))


def check_problem(params: RodParameters, N: int | None = None) -> None:
    """Raise ValueError for spin, ends other than welded or pinned, or (:class:`EndLayerError`) end layers that
    N (or N_MAX) cannot resolve."""
    if params.omega != 0.0:
        raise ValueError("the bowed tether is computed at rest only (omega = 0): with spin the field across the "
                         "chord turns in the rotating frame and the load is time-periodic (no relative equilibrium)")
    if any(e not in (WELDED, PINNED) for e in params.ends):
        raise ValueError(f"the bowed tether's ends must be welded or pinned, got {params.ends}")
    need = required_resolution(params)
    if need > N_MAX:
        raise EndLayerError(f"end layers of width {end_layer(params):.2e} need N >= {need} > {N_MAX}: uniform "
                            "Chebyshev collocation cannot resolve them (graded multi-domain collocation needed)")
    if N is not None and N < need:
        raise EndLayerError(f"end layers of width {end_layer(params):.2e} need N >= {need}, got N = {N}")


def _unloaded(params: RodParameters) -> RodParameters:
    """The parameters the buckled rung's residual sees: no field (added here), welded rows (replaced here)."""
    return params.with_(B=0.0, ends=ALL_WELDED)


def _pinned_rows(params: RodParameters) -> list[tuple[int, int]]:
    """(end, node) of each pinned end: end 0 at node 0, end 1 at node -1."""
    return [(end, (0, -1)[end]) for end in (0, 1) if params.ends[end] == PINNED]


def residual(params: RodParameters, field: CrossField, state: eq.Equilibrium) -> np.ndarray:
    """Collocation residual, shape (12 (N+1),), rows as :func:`etcheck.rod.buckled.equilibria.residual`."""
    check_problem(params)
    N = state.N
    col = collocation(N)
    r = eq.residual(_unloaded(params), state)
    d3 = col.P @ state.D[:, :, 2]
    load = params.B * field.current_at(col.t)[:, None] * np.cross(d3, field.direction)
    r[6 * N:9 * N] += load.T.reshape(-1)
    for end, node in _pinned_rows(params):
        D, M = state.D[node], state.M[node]
        first = NFIELDS * N + 6 * end + 3
        r[first:first + 2] = M @ D[:, :2]  # M . d1, M . d2
    return r


def jacobian(params: RodParameters, field: CrossField, state: eq.Equilibrium) -> np.ndarray:
    """Exact derivative of :func:`residual` for the update (xi, a, phi, m) of
    :func:`etcheck.rod.buckled.equilibria.retract`, shape (12 (N+1), 12 (N+1))."""
    check_problem(params)
    N = state.N
    col = collocation(N)
    J = eq.jacobian(_unloaded(params), state)
    ode = J[: NFIELDS * N].reshape(NFIELDS, N, NFIELDS, N + 1)
    ode[6:9, :, 3:6, :] += lorentz_block(params.B, field, col.t, state.D[:, :, 2], col.P)
    if params.ends != ALL_WELDED:
        J[NFIELDS * N:] = end_rows(state.D[[0, -1]], N, params.ends, state.M[[0, -1]])
    return J


def row_scale(params: RodParameters, N: int) -> np.ndarray:
    """The size of each residual row's terms: max(1, B, |T|) for the force and moment balances and the end force
    (they carry the loads), 1 for the others (positions, constitutive rows, end frames and moments). Dividing by it
    makes one tolerance mean the same relative accuracy of every field under strong tension."""
    out = np.ones(NFIELDS * (N + 1))
    load = max(1.0, abs(params.B), abs(params.T))
    out[6 * N:NFIELDS * N] = load
    out[NFIELDS * N + 2] = load
    return out


def load_derivative(params: RodParameters, field: CrossField, state: eq.Equilibrium) -> np.ndarray:
    """d residual / d B: i(t_k) d3(t_k) x b in the force rows."""
    N = state.N
    col = collocation(N)
    out = np.zeros(NFIELDS * (N + 1))
    d3 = col.P @ state.D[:, :, 2]
    out[6 * N:9 * N] = (field.current_at(col.t)[:, None] * np.cross(d3, field.direction)).T.reshape(-1)
    return out


def solve(params: RodParameters, field: CrossField, guess: eq.Equilibrium, N: int | None = None,
          tol: float = 1e-10, max_iter: int = 30) -> eq.Equilibrium:
    """Newton's method at fixed parameters from ``guess`` (resampled to N if given). Converged when the max-norm of
    the residual divided by :func:`row_scale` is below ``tol``. Raises
    :class:`~etcheck.errors.SolverError` if it does not converge; works at regular points (use
    :mod:`etcheck.rod.bowed.path` through folds)."""
    state = guess if N is None or int(N) == guess.N else eq.resample_state(guess, int(N))
    check_problem(params, state.N)
    state = state.with_params(params)
    scale = row_scale(params, state.N)
    history = []
    for it in range(max_iter + 1):
        r = residual(params, field, state)
        rn = float(np.max(np.abs(r) / scale))
        history.append(rn)
        if rn < tol:
            return replace(state, residual_norm=rn, iterations=it, converged=True)
        if it == max_iter or not np.isfinite(rn):
            break
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", sla.LinAlgWarning)
            delta = sla.solve(jacobian(params, field, state), -r)
        state = eq.retract(state, delta, params)
    raise SolverError(f"bowed equilibrium: Newton did not converge at B = {params.B}, T = {params.T} "
                      f"(N = {state.N}): residual history " + ", ".join(f"{h:.1e}" for h in history[-6:]))
