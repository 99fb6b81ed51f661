"""The band of modes that load and spin reshape on the undamped straight rod (dimensionless).

Above a coupling wavenumber the bending stiffness of a mode outweighs the Lorentz coupling B k and the
spin terms (eq. (86) on the straight rod; docs/model.md, section 6): such modes stay where the
unloaded, unspun rod has them, on the imaginary axis. An undamped instability (divergence or flutter)
therefore lies in the band below the cut mu_cut (mu = -lambda^2): the exact undamped determinant counts
its roots there, and the collocation stability indicator must look at every eigenvalue in it.

Pure; numpy only.
"""

from __future__ import annotations

import math

import numpy as np

from etcheck.rod.core.parameters import RodParameters

__all__ = ["mode_count", "coupling_wavenumber", "cut", "band_modes"]


def mode_count(params: RodParameters, mu: np.ndarray, T: float) -> np.ndarray:
    """Weyl estimate of the number of u and v modes with eigenvalue below mu >= 0, for any ends (welded or
    pinned move the count by less than one per axis; the roots of the undamped determinant are about one apart
    in this variable)."""
    R, f, P = params.R, params.f, params.P
    out = np.zeros_like(np.asarray(mu, dtype=float))
    for c4, pc in ((R / f, P * R), (1.0 / f, P)):
        c2 = max(T, 0.0) - pc * mu  # c4 k^4 + (T - pc mu) k^2 - mu = 0
        k2 = (-c2 + np.sqrt(c2**2 + 4 * c4 * mu)) / (2 * c4)
        out += np.sqrt(np.maximum(k2, 0.0)) / math.pi
    return out


def coupling_wavenumber(params: RodParameters, B: float, omega: float, T: float) -> float:
    """Wavenumber up to which load and spin reshape the modes: where B k (or omega^2) equals the
    geometric mean of the u and v stiffness symbols (R/f k^4 + |a| k^2)(k^4/f + |b| k^2)."""
    R, f, P = params.R, params.f, params.P
    a, b = abs(T + P * R * omega**2), abs(T + P * omega**2)
    k = np.geomspace(1e-2, 1e8, 801)
    stiff = np.sqrt((R / f * k**4 + a * k**2) * (k**4 / f + b * k**2))
    over = (abs(B) * k >= stiff) | (4 * omega**2 >= stiff)
    return float(k[np.nonzero(over)[0][-1]]) if np.any(over) else 0.0


def _mu_at(params: RodParameters, k: float, omega: float) -> float:
    """The larger of the u and v eigenvalues mu of a mode of wavenumber k at spin omega (its stiffness
    symbol over its inertia 1 + pc k^2)."""
    R, f, P, T = params.R, params.f, params.P, params.T
    return max((c4 * k**4 + abs(T + pc * omega**2) * k**2 + omega**2) / (1 + pc * k**2)
               for c4, pc in ((R / f, P * R), (1.0 / f, P)))


def cut(params: RodParameters, ends: list[RodParameters]) -> float:
    """mu_cut of a line whose ends are ``ends`` (T, P, R, f from params): the eigenvalue mu of the modes at
    twice the coupling wavenumber (at least 3 pi), and at least (4 omega)^2."""
    w_max = max(abs(e.omega) for e in ends)
    kc = max(3 * math.pi, 2.0 * max(coupling_wavenumber(params, e.B, e.omega, params.T) for e in ends))
    return max(_mu_at(params, kc, w_max), 16 * w_max**2)


def band_modes(params: RodParameters) -> int:
    """Number of u and v modes up to 1.5 x the coupling wavenumber at params' (B, omega, T), at least those
    below (2 omega)^2: the modes an undamped instability can involve (the lines of the exact determinant
    count to twice the wavenumber, a margin that collocation at moderate N does not resolve)."""
    k = 1.5 * coupling_wavenumber(params, params.B, params.omega, params.T)
    mu = max(_mu_at(params, k, params.omega), 4 * params.omega**2)
    return int(math.ceil(float(mode_count(params, np.array([mu]), params.T)[0])))
