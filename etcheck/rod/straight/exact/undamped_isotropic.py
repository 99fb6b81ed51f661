"""Rung 1u for R = 1: the undamped straight isotropic tether as one complex scalar problem.

For R = 1 the bending equations of :mod:`etcheck.rod.straight.exact.undamped`
(paper Sec. VI A, eq. (86) with F = +T e3, rotating frame; docs/model.md,
section 6) decouple in w = u + i v and w~ = u - i v. With normal modes
exp(lambda t), lambda = i Omega (Omega the frequency in the rotating frame):

    (1/f) w'''' - (T + P omega^2 - P Omega^2) w'' + i B w' - (Omega + omega)^2 w = 0,
    w = w' = 0 at s = 0 and s = 1 (w = w'' = 0 at a pinned end),

and w~ solves the same with -i B and (Omega - omega)^2. Every eigenvalue of
the rod is an eigenvalue Omega of one of the two, and the second's are minus
the complex conjugates of the first's: the rod is stable iff every root
Omega of the first, D+(Omega), is real. D+ is the determinant of the complex
problem of :mod:`etcheck.rod.straight.exact.roots` with c2 = T + P omega^2 -
P Omega^2, c0 = (Omega + omega)^2, c1 = B; for real Omega the operator is
self-adjoint (i d/ds is Hermitian with w = 0 at both ends, d^4/ds^4 with w' = 0 or w'' = 0 there) and D+ is
real.

Why this form: the real function E(mu) of the coupled problem is, for R = 1,
D+ D~ with D~(Omega) = D+(-Omega) conjugated: at omega = 0 it is a square, and with spin its roots
touch in pairs at every static point, where sign counts cannot tell two
roots from none. The roots of D+ are simple there.

**A gyroscopic stability bound.** In Omega the problem is the Hermitian
quadratic pencil F(Omega) = (Omega + omega)^2 + P Omega^2 (-d^2/ds^2) - K_B,
K_B = (1/f) d^4/ds^4 - T d^2/ds^2 + i B d/ds. At Omega = -omega, F = -K_B:
where K_B is positive definite (B below the first static load of the rod at
rest, T_s = 0) F(-omega) is negative definite, the pencil is hyperbolic
and every Omega is real: **an undamped isotropic rod below its static load at
rest is stable at every spin rate** (for P = 0 the spin is a change of frame
and this load is exactly critical at every spin). Past it the rotary inertia
P can stabilise the spinning rod gyroscopically.

Dimensionless and pure; numpy only.
"""

from __future__ import annotations

import math

import numpy as np

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.exact.determinant import bc_complex, isotropic_batch, isotropic_companion, schur, smoothing

__all__ = ["characteristic_plus", "characteristic_plus_counted"]


def characteristic_plus_counted(params: RodParameters, Omega, B=None, omega=None, T=None, route: str = "auto",
                         factor: float = 1.0, shift: int = 0,
                         schur_budget: float = math.inf) -> tuple[np.ndarray, int]:
    """:func:`characteristic_plus` and the number of points that took the Schur route."""
    if params.R != 1.0:
        raise ValueError("the scalar complex problem needs R = 1")
    B = params.B if B is None else B
    omega = params.omega if omega is None else omega
    T = params.T if T is None else T
    Om, B, omega, T = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float))
                                            for x in (Omega, B, omega, T)))
    shape = Om.shape
    Om, B, omega, T = (x.ravel() for x in (Om, B, omega, T))
    c4 = 1.0 / params.f
    c2 = T + params.P * (omega**2 - Om**2)
    c0 = (Om + omega) ** 2
    c1 = B
    # wavenumber scale, smooth in every coefficient (D+ is normalised in it)
    kap = factor * (1.0 + (1.0 + (c2 / c4) ** 2) ** 0.25 + (1.0 + (c0 / c4) ** 2) ** 0.125
                    + (1.0 + (c1 / c4) ** 2) ** (1.0 / 6.0))
    out = np.full(Om.size, np.nan, dtype=complex)
    if route != "schur":
        for group in (c0 == 0, c0 != 0):
            if np.any(group):
                value, _, m = isotropic_batch(c4, c2[group], c0[group], c1[group], kap[group], shift, small=False,
                                              ends=params.ends)
                out[group] = value * smoothing(m)
    slow = np.nonzero(~np.isfinite(out))[0] if route != "exponential" else np.zeros(0, dtype=int)
    if slow.size > schur_budget:
        raise ArithmeticError(f"the exponential basis does not apply at {slow.size} points (near-coincident "
                              f"exponents) and the Schur route's budget is spent")
    for i in slow:
        A = isotropic_companion(c4, c2[i], c0[i], c1[i], kap[i])
        out[i] = schur(A, bc_complex(params.ends), shift).value * smoothing(np.linalg.eigvals(A))
    return out.real.reshape(shape), int(slow.size)


def characteristic_plus(params: RodParameters, Omega, B=None, omega=None, T=None, route: str = "auto",
                        factor: float = 1.0, shift: int = 0) -> np.ndarray:
    """D+(Omega; B, omega, T) of an isotropic (R = 1) undamped rod: real for real Omega, zero exactly at
    the frequencies Omega (rotating frame) of the modes w = u + i v.

    ``Omega`` (array); B, omega, T default to the parameters' values and broadcast with it. ``route``:
    "auto" (exponential basis, Schur where it does not apply), "exponential" (NaN there) or "schur";
    ``factor``, ``shift``: other wavenumber scale and split (a second formulation). Dimensionless.
    """
    return characteristic_plus_counted(params, Omega, B, omega, T, route, factor, shift)[0]
