"""Rung 1v's spectra along one line of load or spin on one mesh (dimensionless): the band's eigenvalues at each
point (memoised), the few near a given one, an eigenvalue tracked along the line, and the line's static points;
and when an eigenvalue counts as unstable. :mod:`etcheck.rod.straight.varying.circulatory` searches these lines
for the first loss of stability.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from etcheck.numerics.eigen import qep_newton, sparse_pencil_nearest, sparse_qep_nearest
from etcheck.rod.straight.varying.line_band import (
    MAX_EIGENVALUES,
    ORDER,
    RESTARTS,
    NotLocated,
    band,
    band_scale,
    eigenvalue_count,
    mean_params,
    mirrored,
    solve,
)
from etcheck.rod.straight.varying.profiles import Tether, family

__all__ = ["PAST", "RELATIVE", "RESOLVED", "STATIC_ROOTS", "THRESHOLD", "Line", "collides", "growth", "threshold"]

#: Re lambda above this (and above RELATIVE |lambda|) counts as unstable.
THRESHOLD = 1e-9
RELATIVE = 1e-8
#: Most spectra computed along one line on one mesh (a search takes 40-150).
MAX_SPECTRA = 1500
#: An eigenvalue tracked by inverse iteration may move at most this much (relative to its size plus one) per unit
#: relative step along the line; a larger jump is another eigenvalue, and ARPACK decides.
TRACK_STEP = 10.0
#: A mesh resolves a band of at most this many modes per point of a field (:attr:`Line.resolved`); the ladder
#: starts at the first of its meshes that does.
RESOLVED = 0.5
#: Static roots sought per line (the nearest to zero: every one on a line up to a few times its first).
STATIC_ROOTS = 16
#: Relative offset of the scan points either side of a static point.
PAST = 1e-6


def threshold(lam: np.ndarray) -> np.ndarray:
    return np.maximum(THRESHOLD, RELATIVE * np.abs(lam))


def growth(lam: np.ndarray) -> float:
    """max (Re lambda - threshold): positive when some eigenvalue counts as unstable."""
    return float(np.max(lam.real - threshold(lam))) if lam.size else -math.inf


class Line:
    """Spectra along one axis on one mesh (memoised): the eigenvalues of the band at each point, the few near
    a given one, and the static points of the line."""

    def __init__(self, tether: Tether, axis: str, N: int, hi: float):
        self.tether, self.axis, self.N, self.hi, self.lo = tether, axis, N, hi, 0.0
        p = tether.params
        ends = tether.with_(**{axis: hi})
        nev = eigenvalue_count(tether, mean_params(ends))
        if nev > MAX_EIGENVALUES:
            raise NotLocated(f"up to {axis} = {hi:.6g} the load and spin reshape {(nev - 4) // 2} modes, more than rung 1v "
                             f"examines ({MAX_EIGENVALUES} eigenvalues a point)")
        self.fam = family(ends, N)
        if (nev - 4) // 2 > self.fam.mesh.size:
            raise NotLocated(f"up to {axis} = {hi:.6g} the load and spin reshape {(nev - 4) // 2} modes, more than the mesh "
                             f"resolves ({self.fam.mesh.size} points per field at N = {N})")
        self.base = {"B": p.B, "omega": p.omega, "T": p.T}
        self.nev = nev
        self.memo: dict[float, np.ndarray] = {}
        self._static: np.ndarray | None = None
        self.tracked: list[tuple[float, complex, np.ndarray]] = []

    @cached_property
    def band(self):
        """Where the eigenvalues of the line are sought (:func:`~etcheck.rod.straight.varying.line_band.band`): set up
        on the first spectrum (a line on which stability changes only at static points may need none)."""
        return band(self.fam, self.point(0.0), self.nev)

    @property
    def resolved(self) -> bool:
        """Whether the mesh resolves the line's band: its modes at most :data:`RESOLVED` of its points per field
        (the eigenvalues of a mesh's top modes are not converged, and their collisions are spurious)."""
        return (self.nev - 4) // 2 <= RESOLVED * self.fam.mesh.size

    @cached_property
    def scale(self) -> float:
        """The size of the line's lowest frequencies, by which each solve scales lambda (the band's own)."""
        return band_scale(self.fam, self.point(0.0))

    def point(self, x: float) -> dict:
        return self.base | {self.axis: x}

    def spectrum(self, x: float) -> np.ndarray:
        """The band's eigenvalues at x."""
        if x not in self.memo:
            if len(self.memo) >= MAX_SPECTRA:
                raise NotLocated(f"the search along {self.axis} took more than {MAX_SPECTRA} spectra (N = {self.N})")
            A = self.fam.operator(**self.point(x))
            lam = [solve(A, k, sigma, self.band.scale, f"{self.axis} = {x:.6g}")
                   for sigma, k in zip(self.band.sigmas, self.band.ks)]
            lam = np.concatenate(lam)
            self.memo[x] = mirrored(lam, self.self_adjoint(x)) if collides(self.tether) else lam
        return self.memo[x]

    def self_adjoint(self, x: float) -> bool:
        """Whether the tether at x is undamped, at rest and under a conservative load: M lambda^2 + K with M and K
        symmetric (docs/model.md section 10), lambda^2 real."""
        p = self.tether.params
        return p.gamma == 0 and self.point(x)["omega"] == 0 and not self.tether.circulatory

    def growth(self, x: float) -> float:
        return growth(self.spectrum(x))

    def unstable(self, x: float) -> bool:
        """Whether the tether is unstable at x, given that it is stable just before the last static point below
        x: a band of the upper half-plane does not see the real eigenvalue that a static point sends into
        Re lambda > 0, which it does (a simple root of det A0 changes the sign of the product of the
        eigenvalues), so just past a static point it counts as unstable."""
        return self.growth(x) > 0 or (self.band.upper and self.just_past_static(x))

    def just_past_static(self, x: float) -> bool:
        r = self.static_roots()
        return bool(np.any((r < x) & (x <= r * (1 + 2 * PAST))))

    def near(self, x: float, z: complex, k: int = 2) -> np.ndarray:
        """The k eigenvalues nearest z at x (z real: a real shift next to it); two by default, the pair that meets
        or the crossing one and its neighbour: more could reach the Kelvin-Voigt cluster, at a distance of the
        frequency."""
        A = self.fam.operator(**self.point(x))
        off = 1e-3 * (1.0 + abs(z))
        sigma = complex(z.real + off, z.imag) if z.imag != 0 else z.real + off
        return sparse_qep_nearest(*A, k=k, sigma=sigma, scale=self.scale, ordering=ORDER, maxiter=RESTARTS)

    def track(self, x: float, z: complex) -> complex:
        """The eigenvalue at x that continues the one near z: nonlinear inverse iteration from the tracked
        eigenpair at the nearest x already seen (a few sparse LUs), ARPACK where that does not converge or
        lands far from where it started."""
        A = self.fam.operator(**self.point(x))
        if self.tracked:
            x0, lam0, y0 = min(self.tracked, key=lambda t: abs(t[0] - x))
            lam, y, ok = qep_newton(*A, lam0, y0, ordering=ORDER)
            if ok and abs(lam - lam0) <= TRACK_STEP * (abs(lam0) + 1.0) * max(abs(x - x0) / max(abs(x), 1e-300), 1e-3):
                self.tracked.append((x, lam, y))
                return lam
        off = 1e-3 * (1.0 + abs(z))
        lam, Y = sparse_qep_nearest(*A, k=2, sigma=complex(z.real + off, z.imag), scale=self.scale,
                                    ordering=ORDER, vectors=True, maxiter=RESTARTS)
        i = int(np.argmin(np.abs(lam - z)))
        self.tracked.append((x, complex(lam[i]), Y[:, i]))
        return complex(lam[i])

    def static_roots(self) -> np.ndarray:
        """The values in (0, hi] where the operator is singular at lambda = 0 (static points: a real eigenvalue
        passes through 0 there), sorted."""
        if self._static is None:
            A, Nx = self.fam.static(self.axis, **self.base)
            x = sparse_pencil_nearest(A, Nx, k=STATIC_ROOTS, shift=0.0, ordering=ORDER)
            x = x[np.abs(x.imag) <= 1e-8 * np.abs(x)].real
            if self.axis == "omega":
                x = np.sqrt(x[x > 0])
            self._static = np.sort(x[(x > 0) & (x <= self.hi)])
        return self._static


def collides(tether: Tether) -> bool:
    """Whether eigenvalues leave the imaginary axis only in colliding pairs: undamped, and either without spin
    (the spectrum is symmetric under lambda -> -lambda, the equations having lambda^2 only) or with a uniform
    load (gyroscopic and conservative: Hamiltonian). Otherwise an eigenvalue crosses the axis on its own."""
    p = tether.params
    return p.gamma == 0 and (p.omega == 0 or not tether.circulatory)
