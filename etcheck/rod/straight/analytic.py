"""Rung 0: closed-form results for the straight welded rod (Secs. VI A, VI B of arXiv:0810.3668).

Everything here is dimensionless. Loads are given in the f-scaling of
eq. (36): the paper's Sec. VI is written with f = 1 and the conversion
is B_f = B_1 / f, omega_f = omega_1 / sqrt(f), lambda_f = lambda_1 / sqrt(f)
(docs/errata.md, #6).

Static buckling (omega = T = 0). With u = x, v = y and w = u + i v / sqrt(R)
the linear static problem (eq. (87) at lambda = 0) becomes the single
complex equation w'''' + i k w' = 0, k = f B / sqrt(R) = beta**3, clamped at
both ends. Its determinant D(beta) has simple zeros and chi(beta) of
eq. (91) is proportional to |D|**2, so every zero of chi is a double
zero: the kernel is two-dimensional (w and i w) and the pitchfork is doubly
degenerate for every R.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from etcheck.numerics.optimize import bracketed_roots, brentq

SQRT3 = math.sqrt(3.0)
#: Step of the complex-step derivative (exact to rounding, no cancellation).
_H = 1e-30


def chi_scaled(beta):
    """chi(beta) * exp(-sqrt(3) beta), eq. (91); dimensionless.

    Written with decaying exponentials only, so it neither overflows nor loses
    its zeros for large beta (tested to beta = 1000). Accepts real or complex
    arrays (complex for the complex-step derivative). For large beta it tends
    to 1 - cos(beta - pi/3), whose double zeros are beta = pi/3 + 2 pi n.
    """
    b = np.asarray(beta)
    a = SQRT3 * b
    e1 = np.exp(-0.5 * a)  # e^{-a/2}
    e2 = np.exp(-a)
    e3 = np.exp(-1.5 * a)
    e4 = np.exp(-2.0 * a)
    cosh_h = 0.5 * (e1 + e3)  # e^{-a} cosh(a/2)
    sinh_h = 0.5 * (e1 - e3)  # e^{-a} sinh(a/2)
    cosh_f = 0.5 * (1.0 + e4)  # e^{-a} cosh(a)
    sinh_f = 0.5 * (1.0 - e4)  # e^{-a} sinh(a)
    return (
        (2.0 * np.cos(b) + np.cos(2.0 * b)) * e2
        - 2.0 * (np.cos(0.5 * b) + np.cos(1.5 * b)) * cosh_h
        + (2.0 - np.cos(b)) * cosh_f
        - SQRT3 * np.sin(b) * sinh_f
        - 2.0 * SQRT3 * (np.sin(0.5 * b) - np.sin(1.5 * b)) * sinh_h
    )


def chi(beta):
    """chi(beta) of eq. (91) (unscaled; overflows past beta ~ 400)."""
    b = np.asarray(beta, dtype=float)
    return chi_scaled(b) * np.exp(SQRT3 * b)


def chi_scaled_derivative(beta):
    """d/dbeta of :func:`chi_scaled`, by complex step (exact to rounding)."""
    b = np.asarray(beta, dtype=float)
    return np.imag(chi_scaled(b + 1j * _H)) / _H


def _complex_exponents(beta: float) -> np.ndarray:
    """The three non-zero roots m of m**3 = -i beta**3 (w = e^{m s})."""
    roots = np.exp(1j * np.array([-math.pi / 6, math.pi / 2, 7 * math.pi / 6]))
    return beta * roots


def _clamped_matrix(beta: float) -> np.ndarray:
    """4x4 boundary matrix of w'''' + i beta^3 w' = 0 with w = w' = 0 at s = 0, 1.

    Basis 1, e^{m_j (s - s_j)} with s_j = 1 for Re m_j > 0 and 0 otherwise, so
    every entry is bounded by 1 and nothing overflows for large beta.
    """
    m = _complex_exponents(beta)
    shift = np.where(m.real > 0, 1.0, 0.0)
    rows = []
    for s in (0.0, 1.0):
        e = np.exp(m * (s - shift))
        rows.append(np.concatenate([[1.0], e]))
        rows.append(np.concatenate([[0.0], m * e]))
    return np.array(rows, dtype=complex)


def determinant(beta: float) -> complex:
    """Determinant of the (scaled) complex clamped problem; simple zeros at the
    zeros of chi. Dimensionless."""
    return complex(np.linalg.det(_clamped_matrix(beta)))


@dataclass(frozen=True)
class CharacteristicRoot:
    """A double zero beta_k of chi (eq. (91)), dimensionless.

    ``residual`` is |chi_scaled(beta)| (zero), ``curvature`` is
    chi_scaled''(beta) > 0 (a touching zero, no sign change), and
    ``kernel_dimension`` is the real dimension of the null space of the
    complex clamped problem (2: a doubly degenerate pitchfork). ``error`` is
    the a-posteriori relative error of beta (the size of one more Newton step
    on chi_scaled', floored at machine epsilon).
    """

    k: int
    beta: float
    residual: float
    curvature: float
    kernel_dimension: int
    error: float


def _curvature(beta: float) -> float:
    """chi_scaled''(beta) by a central difference of :func:`chi_scaled_derivative` (relative error ~1e-8)."""
    h = 1e-4 * beta
    return float((chi_scaled_derivative(beta + h) - chi_scaled_derivative(beta - h)) / (2 * h))


def _double_zero(guess: float) -> float:
    """The zero of chi_scaled' within guess +- 1: Newton's method, Brent's on that bracket if a step leaves it."""
    lo, hi = guess - 1.0, guess + 1.0
    beta = guess
    for _ in range(20):
        step = float(chi_scaled_derivative(beta)) / _curvature(beta)
        beta -= step
        if not lo < beta < hi:
            break
        if abs(step) <= 4 * np.finfo(float).eps * beta:
            return beta
    return brentq(chi_scaled_derivative, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


@lru_cache(maxsize=16)
def characteristic_roots(n: int = 5) -> tuple[CharacteristicRoot, ...]:
    """The first n double zeros of chi(beta), located to ~1e-15 relative.

    A double zero is a simple zero of chi_scaled', found by Newton's method
    from its asymptotic position pi/3 + 2 pi k (three or four steps; the
    zeros are 2 pi apart), or by Brent's method on pi/3 + 2 pi k +- 1 should a
    Newton step leave that bracket.
    """
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    roots = []
    for k in range(1, n + 1):
        beta = _double_zero(math.pi / 3 + 2 * math.pi * k)
        curvature = _curvature(beta)
        singular = np.linalg.svd(_clamped_matrix(beta), compute_uv=False)
        kernel = 2 * int(np.sum(singular < 1e-8 * singular[0]))
        roots.append(
            CharacteristicRoot(
                k=k,
                beta=float(beta),
                residual=float(abs(chi_scaled(beta))),
                curvature=curvature,
                kernel_dimension=kernel,
                error=max(abs(float(chi_scaled_derivative(beta)) / curvature) / beta, np.finfo(float).eps),
            )
        )
    return tuple(roots)


def critical_loads(R: float, f: float, n: int = 5) -> np.ndarray:
    """Static magnetic buckling loads B_k = beta_k**3 sqrt(R) / f, k = 1..n.

    Dimensionless (eq. (36)); omega = T = 0. Each is a doubly
    degenerate pitchfork of the straight rod (Sec. VI A).
    """
    betas = np.array([r.beta for r in characteristic_roots(n)])
    return betas**3 * math.sqrt(R) / f


def beta_of_load(B: float, R: float, f: float) -> float:
    """beta = (f B)**(1/3) / R**(1/6) for a load B >= 0 (dimensionless)."""
    return (f * abs(B)) ** (1.0 / 3.0) / R ** (1.0 / 6.0)


def buckling_mode(k: int, R: float, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Shape (x(s), y(s)) of the k-th static buckling mode, dimensionless.

    One member of the two-dimensional kernel (the other is the same coil
    turned by a quarter period of w = x + i y / sqrt(R)). Normalised so that
    max sqrt(x^2 + y^2) = 1.
    """
    beta = characteristic_roots(k)[-1].beta
    m = _complex_exponents(beta)
    _, _, vh = np.linalg.svd(_clamped_matrix(beta))
    c = vh[-1].conj()
    shift = np.where(m.real > 0, 1.0, 0.0)
    s = np.asarray(s, dtype=float)
    w = c[0] + np.exp(np.outer(s, m) - m * shift) @ c[1:]
    # pick the phase that makes x(s) largest (a well-defined, symmetric picture)
    w = w * np.exp(-1j * np.angle(w[np.argmax(np.abs(w))]))
    x, y = w.real, math.sqrt(R) * w.imag
    scale = np.max(np.hypot(x, y))
    return x / scale, y / scale


# --- unperturbed spectrum (T = gamma = omega = B = 0), Sec. VI B -----------------


def _clamped_beam_function(mu, P: float, stiffness: float):
    """Frequency equation of a clamped-clamped Rayleigh beam, Sec. VI B, f = 1 (mu scalar or array).

    (a^2 - b^2) sin a sinh b - 2 a b (1 - cos a cosh b) = 0, divided by cosh b
    so it stays bounded; ``stiffness`` is R for the x (weak) equation and 1 for y.
    """
    root = np.sqrt(mu**4 * P**2 + 4 * mu**2 / stiffness)
    a = np.sqrt(0.5 * mu**2 * P + 0.5 * root)
    b = np.sqrt(np.maximum(0.5 * root - 0.5 * mu**2 * P, 0.0))
    return (a * a - b * b) * np.sin(a) * np.tanh(b) - 2 * a * b * (1.0 / np.cosh(b) - np.cos(a))


def bending_frequencies(P: float, R: float, f: float, n: int = 5, axis: str = "weak") -> np.ndarray:
    """First n bending frequencies mu (lambda = +- i mu) of the straight rod.

    Dimensionless, f-scaling; Sec. VI B transcendental equations with rotary
    inertia P. ``axis="weak"`` is the x equation (stiffness R, first
    frequency sqrt(R) as P -> 0), ``"stiff"`` the y equation (stiffness 1).
    """
    stiffness = {"weak": R, "stiff": 1.0}[axis]
    g = lambda mu: _clamped_beam_function(mu, P, stiffness)  # noqa: E731
    # Euler-Bernoulli spacing: mu_n ~ sqrt(stiffness) ((n + 1/2) pi)^2, and rotary
    # inertia only lowers the frequencies; scan finely in the f = 1 frequency
    # and refine the first n sign changes to the last bits.
    mu_max = math.sqrt(stiffness) * ((n + 1.5) * math.pi) ** 2
    grid = np.linspace(1e-6, mu_max, 400 * (n + 2))
    values = g(grid)
    i = np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0][:n]
    if i.size < n:
        raise RuntimeError(f"found only {i.size} of {n} bending frequencies")
    return bracketed_roots(g, grid[i], grid[i + 1]) / math.sqrt(f)


def torsion_frequencies(P: float, Gamma: float, f: float, n: int = 5) -> np.ndarray:
    """Torsional frequencies mu_n = n pi sqrt(Gamma / (2 P f)), n = 1..n.

    Dimensionless, f-scaling (Sec. VI B, converted as in docs/errata.md, #6).
    Infinite for P = 0 (no rotary inertia).
    """
    if P == 0:
        return np.full(n, np.inf)
    return np.arange(1, n + 1) * math.pi * math.sqrt(Gamma / (2 * P * f))
