"""Rung 1v: where and how the eigenvalues along a line are sought (dimensionless): the range of the search (the
expected first critical value and the stages up to the end asked for), the band of eigenvalues each point examines
(how many, around which shifts), the eigenvalue solve with its bounds, past which a search is not located, and
the eigenvalues as the structure of the spectrum allows them (round-off off the axis put on it).

Used by :mod:`etcheck.rod.straight.varying.circulatory`. Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from etcheck.numerics.eigen import sparse_qep_nearest
from etcheck.rod.straight.exact.mode_band import band_modes
from etcheck.rod.straight.varying.profiles import Tether, TetherFamily

__all__ = [
    "CHUNK",
    "K_MODES",
    "MAX_EIGENVALUES",
    "ORDER",
    "RESTARTS",
    "SIGMA",
    "STAGE",
    "Band",
    "NotLocated",
    "band",
    "band_scale",
    "default_hi",
    "eigenvalue_count",
    "forget_bands",
    "expected_end",
    "mean_params",
    "mirrored",
    "solve",
    "stages",
]

#: Least pairs of eigenvalues examined at each point.
K_MODES = 12

#: A line is scanned in stages: the first up to this many times the expected first critical value
#: (:func:`expected_end`), each next one this many times further, up to the end asked for.
STAGE = 4.0
#: Most eigenvalues one point of a line examines; a band of more modes (a tape without tension under a
#: load thousands of times its critical one reshapes hundreds of its soft modes) is not located.
MAX_EIGENVALUES = 240
#: ARPACK restarts per eigenvalue solve (a converging solve takes 2-5); eigenvalues not converged by then are
#: missing, and the point is not located.
RESTARTS = 60


class NotLocated(Exception):
    """A search that cannot be completed within its bounds; the message says why."""


def eigenvalue_count(tether: Tether, hi_params) -> int:
    """How many eigenvalues each point examines: the k least pairs and every mode the load and spin reshape
    (:func:`~etcheck.rod.straight.exact.mode_band.band_modes` at the end of the line)."""
    return max(2 * K_MODES + 4, 2 * band_modes(hi_params) + 4)


@dataclass(frozen=True)
class Band:
    """Where a line's eigenvalues are sought on one mesh: the k[i] nearest each shift sigmas[i], with lambda
    scaled by ``scale`` (the size of the lowest frequency). Without damping one shift next to 0 (the lowest
    modes, both members of each pair); with damping the Kelvin-Voigt cluster at -1/gamma, hundreds of
    eigenvalues on which ARPACK converges slowly, must stay out of reach: the same shift where the modes lie
    well below 1/gamma, else shifts i Omega along the band of modes, a few modes each (their
    members with Im > 0; a real eigenvalue reaches Re lambda > 0 only through 0, where the operator is
    singular: the static roots of the line in :mod:`etcheck.rod.straight.varying.circulatory`)."""

    sigmas: tuple[complex, ...]
    ks: tuple[int, ...]
    scale: float

    @property
    def upper(self) -> bool:
        return isinstance(self.sigmas[0], complex)


#: Largest ratio of the frequencies sought around one shift along the band of a damped line whose modes reach the
#: Kelvin-Voigt cluster (radius 0.4 of the middle).
CHUNK = 7.0 / 3.0


#: The undamped frequencies at zero load a band is cut from, by (undamped tether, mesh, omega, T, count).
_FREQUENCIES: dict = {}


def band_scale(fam: TetherFamily, point: dict) -> float:
    """The size of a line's lowest frequencies (``point``: its values of B, omega, T at the start), by which its
    eigenvalues are scaled in each solve: pi sqrt(mean tension), at least 1."""
    return max(1.0, math.pi * math.sqrt(max(point["T"], 0.0) * float(np.mean(fam.tether.tension(np.linspace(0, 1, 101))))))


def forget_bands() -> None:
    """Empty the memo of the bands' frequencies (a benchmark's runs start from nothing)."""
    _FREQUENCIES.clear()


def band(fam: TetherFamily, point: dict, nev: int) -> Band:
    """The :class:`Band` of a line on ``fam`` (``point``: its values of B, omega, T at the start)."""
    gamma = fam.tether.params.gamma
    scale = band_scale(fam, point)
    if gamma == 0:
        return Band((SIGMA * scale,), (nev,), scale)
    key = (fam.tether.with_(gamma=0.0), fam.mesh, point["omega"], point["T"], nev)
    if key not in _FREQUENCIES:  # the same for every damping: a damping map's lines share it
        lam = solve(fam.operator(0.0, point["omega"], point["T"], damped=False), nev, SIGMA * scale, scale,
                    "zero load")
        if len(_FREQUENCIES) >= 16:
            _FREQUENCIES.pop(next(iter(_FREQUENCIES)))
        _FREQUENCIES[key] = np.sort(np.abs(lam.imag[lam.imag > 0]))
    freq = _FREQUENCIES[key]
    if freq.size == 0 or 1.0 / gamma > 1.5 * freq[-1]:  # the cluster lies beyond the band: as without damping
        return Band((SIGMA * scale,), (nev,), scale)
    chunks = _chunks(freq)
    return Band(tuple(complex(0.0, 0.5 * float(c[0] + c[-1])) for c in chunks), tuple(c.size for c in chunks), scale)


def _chunks(freq: np.ndarray) -> list[np.ndarray]:
    """The band's frequencies (sorted) in chunks each sought around its middle i Omega_c: a chunk spans at most a
    factor :data:`CHUNK` (its radius at most 0.4 Omega_c), so the next frequencies and the Kelvin-Voigt cluster,
    at least Omega_c away, lie at least 2.5 radii from the shift and ARPACK converges fast; a frequency within 1e-6
    of the chunk's last (the double pairs of R = 1) joins it."""
    out, start = [], 0
    for i in range(1, freq.size + 1):
        if i == freq.size or (freq[i] > CHUNK * freq[start] and freq[i] > freq[i - 1] * (1 + 1e-6)):
            out.append(freq[start:i])
            start = i
    return out


#: SuperLU's ordering of the collocation matrices: their own (block-banded along the tether).
ORDER = "NATURAL"
#: Real shift of an undamped band, as a fraction of the lowest frequency's scale: next to 0, where a real eigenvalue
#: crosses, but not at it (the operator is singular there at static points, and next to them its LU then spreads
#: round-off of 1e-7 into every eigenvalue: R = 1 just below its double static point with a shift of 0.012).
SIGMA = 0.3


def solve(A, k: int, sigma, scale: float, where: str) -> np.ndarray:
    """The k eigenvalues of the operator A nearest sigma, all of them: ARPACK bounded by :data:`RESTARTS`, and a
    point where some did not converge is not located (a missing eigenvalue could be the unstable one)."""
    k = min(k, A[0].shape[0] // 2)
    lam = sparse_qep_nearest(*A, k=k, sigma=sigma, scale=scale, ordering=ORDER, maxiter=RESTARTS)
    if lam.size < k:
        raise NotLocated(f"the eigenvalue solver converged on {lam.size} of {k} eigenvalues near {sigma:.4g} at "
                         f"{where}")
    return lam


def mirrored(lam: np.ndarray, real_square: bool = False) -> np.ndarray:
    """The eigenvalues of a tether whose spectrum is symmetric under lambda -> -conj(lambda) (undamped, at rest or
    under one current: :func:`~etcheck.rod.straight.varying.line.collides`), an eigenvalue in Re lambda > 0 without
    its mirror image there (within its own real part) put on the imaginary axis: such an eigenvalue leaves the
    axis only together with its mirror (a collision, or a pair through 0), so a lone one's real part is round-off
    (up to 1e-7 of |lambda| at the top of a band on a fine mesh, above the relative threshold of instability).
    ``real_square``: lambda^2 is real (a self-adjoint problem: no flutter), each eigenvalue put on the nearer of
    the two axes (a double frequency of R = 1, split by round-off into a pair either side of the axis, is no
    collision). Dimensionless."""
    if real_square:
        return np.where(np.abs(lam.real) >= np.abs(lam.imag), lam.real + 0j, 1j * lam.imag)
    out = lam.copy()
    for i in np.flatnonzero(lam.real > 0):
        d = np.abs(lam + np.conj(lam[i]))
        d[i] = math.inf
        if not np.any(d <= lam[i].real):
            out[i] = complex(0.0, lam[i].imag)
    return out


def mean_params(tether: Tether):
    """The tether's parameters with its mean tension and mean |load| (for mode counts)."""
    s = np.linspace(0.0, 1.0, 201)
    p = tether.params
    return p.with_(T=p.T * float(np.mean(tether.tension(s))), B=p.B * float(np.mean(np.abs(tether.current(s)))))


def default_hi(tether: Tether, axis: str) -> float:
    """End of the line scanned when none is given: for the load, 3 x the expected first critical load of the
    tether under its mean tension with the uniform load of its mean current; for the spin, 2 x the expected
    critical spin (:func:`etcheck.rod.straight.exact.roots.root_scale`), at least 1.1 x the operating value."""
    return max(expected_end(tether, axis), 1.1 * (tether.params.B if axis == "B" else tether.params.omega))


def expected_end(tether: Tether, axis: str) -> float:
    """3 x the expected first critical load, 2 x the expected critical spin (:func:`default_hi`)."""
    from etcheck.rod.straight.exact.roots import root_scale

    mean = mean_params(tether)
    s = np.linspace(0.0, 1.0, 201)
    b = max(float(np.mean(np.abs(tether.current(s)))), 0.1)
    if axis == "B":
        return 3.0 * root_scale(mean.with_(B=0.0), "B", 1.0) / b
    return 2.0 * root_scale(mean.with_(omega=0.0), "omega", 1.0)


def stages(tether: Tether, axis: str, hi: float) -> list[float]:
    """The ends of the stages of a search up to ``hi``: :func:`expected_end`, then :data:`STAGE` times further
    each, the last ``hi``."""
    out, end = [], expected_end(tether, axis)
    while end < hi / STAGE ** 0.5:
        out.append(end)
        end *= STAGE
    return out + [hi]
