"""O(1) base states (whirling relative equilibria) of the rod, dimensionless.

A base state is a solution of the stationary O(1) problem of Sec. V A of arXiv:0810.3668
(eqs. (49)-(57) with (58)-(69)), i.e. of eqs. (37)-(41) with
the time derivatives set to zero, in the frame rotating with omega e3.
The linearisation (:mod:`etcheck.rod.core.linear`) needs it only through point
evaluations at arbitrary arc lengths s in [0, 1]:

* ``x0(s)``      centreline, shape (n, 3), e-frame components;
* ``D0(s)``      directors, shape (n, 3, 3); column i is d_i^0 in the e-frame
                 (so ``D0 @ v_body`` maps body to e-frame components);
* ``F0(s)``      contact force, shape (n, 3), e-frame components;
* ``M0(s)``      contact moment, shape (n, 3), e-frame components;
* ``kappa0(s)``  Darboux vector, shape (n, 3), *body* components
                 (``kappa_j = kappa . d_j``, eq. (40)).

:class:`BaseState` is the protocol; :class:`CallableBaseState` wraps five
callables (a future nonlinear equilibrium solver can provide them, e.g. as
Chebyshev interpolants); :func:`straight` is the trivial solution
of eq. (86) with the erratum F0 = +T e3 (tension positive, consistent with
eq. (25); docs/errata.md, #5).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from etcheck.rod.core.parameters import RodParameters

__all__ = ["BaseState", "CallableBaseState", "StraightBaseState", "straight", "rotated"]

ArrayFn = Callable[[np.ndarray], np.ndarray]


@runtime_checkable
class BaseState(Protocol):
    """Evaluable O(1) equilibrium (all quantities dimensionless)."""

    def x0(self, s: np.ndarray) -> np.ndarray: ...

    def D0(self, s: np.ndarray) -> np.ndarray: ...

    def F0(self, s: np.ndarray) -> np.ndarray: ...

    def M0(self, s: np.ndarray) -> np.ndarray: ...

    def kappa0(self, s: np.ndarray) -> np.ndarray: ...


@dataclass(frozen=True)
class StraightBaseState:
    """Straight, untwisted rod x0 = s e3, D0 = I, F0 = +T e3, M0 = 0 (eq. (86), sign of F corrected).

    A relative equilibrium for every B, omega, gamma, P, R, Gamma (the Lorentz
    force d3 x e3 and the centrifugal force both vanish on the axis).
    """

    T: float = 0.0

    def x0(self, s: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s, dtype=float))
        out = np.zeros((s.size, 3))
        out[:, 2] = s
        return out

    def D0(self, s: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s, dtype=float))
        return np.broadcast_to(np.eye(3), (s.size, 3, 3)).copy()

    def F0(self, s: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s, dtype=float))
        out = np.zeros((s.size, 3))
        out[:, 2] = self.T
        return out

    def M0(self, s: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s, dtype=float))
        return np.zeros((s.size, 3))

    def kappa0(self, s: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s, dtype=float))
        return np.zeros((s.size, 3))


@dataclass(frozen=True)
class CallableBaseState:
    """A base state given by five vectorised callables of s (dimensionless)."""

    x0_fn: ArrayFn
    D0_fn: ArrayFn
    F0_fn: ArrayFn
    M0_fn: ArrayFn
    kappa0_fn: ArrayFn

    def x0(self, s: np.ndarray) -> np.ndarray:
        return np.asarray(self.x0_fn(np.atleast_1d(np.asarray(s, dtype=float))), dtype=float)

    def D0(self, s: np.ndarray) -> np.ndarray:
        return np.asarray(self.D0_fn(np.atleast_1d(np.asarray(s, dtype=float))), dtype=float)

    def F0(self, s: np.ndarray) -> np.ndarray:
        return np.asarray(self.F0_fn(np.atleast_1d(np.asarray(s, dtype=float))), dtype=float)

    def M0(self, s: np.ndarray) -> np.ndarray:
        return np.asarray(self.M0_fn(np.atleast_1d(np.asarray(s, dtype=float))), dtype=float)

    def kappa0(self, s: np.ndarray) -> np.ndarray:
        return np.asarray(self.kappa0_fn(np.atleast_1d(np.asarray(s, dtype=float))), dtype=float)


def straight(params: RodParameters) -> StraightBaseState:
    """The trivial straight state of eq. (86) (F0 = +T e3, erratum applied)."""
    return StraightBaseState(T=float(params.T))


def rotated(base: BaseState, Q: np.ndarray) -> CallableBaseState:
    """The base state seen in a frame rotated by the constant rotation Q.

    x0 -> Q x0, d_i -> Q d_i, F0 -> Q F0, M0 -> Q M0; body curvatures are
    unchanged. Used to exercise the general (D0 != I) linearisation: for a
    rotation about e3 this is again an equilibrium of the rotating-frame
    problem (the field B e3 and spin omega e3 are invariant).
    """
    Q = np.asarray(Q, dtype=float)
    return CallableBaseState(
        x0_fn=lambda s: base.x0(s) @ Q.T,
        D0_fn=lambda s: np.einsum("ab,nbc->nac", Q, base.D0(s)),
        F0_fn=lambda s: base.F0(s) @ Q.T,
        M0_fn=lambda s: base.M0(s) @ Q.T,
        kappa0_fn=lambda s: base.kappa0(s),
    )
