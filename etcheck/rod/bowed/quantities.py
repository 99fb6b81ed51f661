"""What an engineer signs for on a bowed equilibrium: the bow in and out of the plane of the load, the end forces
and moments, the lowest natural frequency and stability, each with a two-resolution error (dimensionless,
f-scaling of eq. (36); lengths in units of L, forces f EI1/L^2, moments f EI1/L, frequencies omega_c).

Bow: the largest lateral distance of the centreline from the chord (the e3 axis through both ends),
max_s sqrt(x1^2 + x2^2); in-plane: max_s |x . n| with n = :attr:`~etcheck.rod.bowed.field.CrossField.in_plane`
(the direction of the load on the straight tether); out-of-plane (coiling): max_s |x . c| with c =
:attr:`~etcheck.rod.bowed.field.CrossField.out_of_plane`. Maxima of the Chebyshev interpolant (sampled, then
refined by a bounded minimisation).

Frequencies: the O(delta) linearisation of :func:`etcheck.rod.core.linear.linear_operator` about the state
(eqs. (71)-(75), (76)-(81)) at B = 0 plus the Lorentz term of eq. (71) with e3 replaced by b,
phi' = -B i(s) (a x d3) x b (:func:`etcheck.rod.bowed.field.lorentz_block`), undamped (gamma = 0). Its
eigenvalues nearest 0 (:func:`etcheck.rod.core.spectrum.lowest_eigenvalues`); the lowest natural frequency is the
least Im lambda > 0; the state is stable when no Re lambda exceeds round-off (1e-8 of the largest |lambda|
computed).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from etcheck.numerics.optimize import minimize_scalar
from etcheck.rod.bowed import statics
from etcheck.rod.bowed.field import CrossField, lorentz_block
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.linear import NFIELDS, collocation, linear_operator
from etcheck.rod.core.spectrum import check_resolution, lowest_eigenvalues

__all__ = ["Quantities", "Assessment", "linearisation", "quantities", "assess", "largest_distance"]

#: Eigenvalues computed for the frequency and the stability test.
NEV = 12
#: Re lambda below this times max |lambda| counts as zero (round-off of the undamped spectrum).
ROUNDOFF = 1e-8


@dataclass(frozen=True)
class Quantities:
    """One state's engineering quantities (module docstring for units): ``bow``, ``in_plane``,
    ``out_of_plane``, ``end_shortening`` (x3(0)), ``F0``, ``F1``, ``M0``, ``M1`` (force and moment at s = 0, 1,
    e-frame), ``frequency`` (lowest natural frequency), ``max_real`` (largest Re lambda), ``stable``."""

    B: float
    bow: float
    in_plane: float
    out_of_plane: float
    end_shortening: float
    F0: tuple
    F1: tuple
    M0: tuple
    M1: tuple
    frequency: float
    max_real: float
    stable: bool

    def vector(self) -> np.ndarray:
        """The real quantities in one array (for differences between resolutions)."""
        return np.array([self.bow, self.in_plane, self.out_of_plane, self.end_shortening, *self.F0, *self.F1,
                         *self.M0, *self.M1, self.frequency])


@dataclass(frozen=True)
class Assessment:
    """The quantities at N (``value``) and their two-resolution ``error`` (absolute, same fields as
    :meth:`Quantities.vector`, from the state re-solved at ``N_check``)."""

    value: Quantities
    error: Quantities
    N: int
    N_check: int


def largest_distance(state: eq.Equilibrium, direction: np.ndarray | None = None) -> float:
    """max_s of |x . direction| (or of the distance from the chord, sqrt(x1^2 + x2^2), for None) of the
    interpolant."""

    def size(s) -> np.ndarray:
        x = state.x0(np.atleast_1d(s))
        return np.hypot(x[:, 0], x[:, 1]) if direction is None else np.abs(x @ direction)

    grid = np.linspace(0.0, 1.0, 8 * state.N + 1)
    v = size(grid)
    i = int(np.argmax(v))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    res = minimize_scalar(lambda s: -float(size(s)[0]), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-12})
    return max(float(v[i]), -float(res.fun))


def linearisation(state: eq.Equilibrium, field: CrossField):
    """(A0, A1, A2) of the undamped linearisation about the bowed ``state`` (module docstring)."""
    params = state.params.with_(gamma=0.0)
    N = state.N
    col = collocation(N)
    A0, A1, A2 = linear_operator(params.with_(B=0.0), state, N)
    ode = A0[: NFIELDS * N].reshape(NFIELDS, N, NFIELDS, N + 1)
    ode[6:9, :, 3:6, :] += lorentz_block(params.B, field, col.t, state.D0(col.t)[:, :, 2], col.P)
    return A0, A1, A2


def quantities(state: eq.Equilibrium, field: CrossField) -> Quantities:
    """The :class:`Quantities` of one bowed state."""
    lam = lowest_eigenvalues(state.params.with_(gamma=0.0), state, state.N, NEV,
                             operator=linearisation(state, field))
    lam = np.asarray(lam, dtype=complex)
    scale = float(np.max(np.abs(lam))) if lam.size else 1.0
    oscillating = lam.imag > ROUNDOFF * scale
    max_real = float(np.max(lam.real)) if lam.size else float("nan")
    return Quantities(
        B=state.params.B,
        bow=largest_distance(state),
        in_plane=largest_distance(state, field.in_plane),
        out_of_plane=largest_distance(state, field.out_of_plane),
        end_shortening=float(state.x[0, 2]),
        F0=tuple(state.F[0]), F1=tuple(state.F[-1]), M0=tuple(state.M[0]), M1=tuple(state.M[-1]),
        frequency=float(np.min(lam.imag[oscillating])) if np.any(oscillating) else float("nan"),
        max_real=max_real,
        stable=bool(max_real <= ROUNDOFF * scale),
    )


def assess(state: eq.Equilibrium, field: CrossField, N_check: int | None = None) -> Assessment:
    """The quantities of ``state`` and their two-resolution errors: the state re-solved at ``N_check`` (default
    :func:`etcheck.rod.core.spectrum.check_resolution` of N) by Newton (a regular point of the path)."""
    M = check_resolution(state.N) if N_check is None else int(N_check)
    fine = statics.solve(state.params, field, state, M)
    q, qf = quantities(state, field), quantities(fine, field)
    d = np.abs(q.vector() - qf.vector())
    error = Quantities(B=0.0, bow=d[0], in_plane=d[1], out_of_plane=d[2], end_shortening=d[3],
                       F0=tuple(d[4:7]), F1=tuple(d[7:10]), M0=tuple(d[10:13]), M1=tuple(d[13:16]),
                       frequency=d[16], max_real=abs(q.max_real - qf.max_real), stable=q.stable == qf.stable)
    return Assessment(value=q, error=error, N=state.N, N_check=M)
