"""Rung 0: closed-form results for the straight rod (Secs. VI A, VI B of arXiv:0810.3668), welded or pinned.

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

**Pinned ends** (no bending moment: w = w'' = 0; :mod:`etcheck.rod.core.ends`).
The boundary conditions stay complex-linear, so the kernel is again w and
i w. With a = sqrt(3) beta / 2 the determinant of the boundary map, for the
basis 1, exp(m_j s) (m_j^3 = -i beta^3), is i times a real multiple of

    welded-welded:  cos beta - e^a cos(beta/2 + pi/3) - e^-a cos(beta/2 - pi/3)
    pinned-pinned:  cos beta - e^a sin(beta/2 + pi/6) - e^-a cos(beta/2 + pi/3)
    welded-pinned:  2 sin(beta/2) (cosh a - cos(beta/2))

(the first is chi of eq. (91): chi e^(-sqrt(3) beta) = 2 (e^-a times it)^2).
The mixed attachment buckles exactly at beta = 2 pi k (cosh a > 1 >= cos),
either way round; the pinned one at beta ~ 2 pi k - pi/3 (beta_1 =
5.225154248768965): with R = 21/38 its first load is 0.362 of the welded
one, the mixed one's (2 pi / beta_1)^3 = 0.629.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache, partial

import numpy as np

from etcheck.numerics.optimize import bracketed_roots, brentq
from etcheck.rod.core.ends import ALL_WELDED, CLAMPED, HINGED, Ends

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


def _clamped_matrix(beta: float, ends: Ends = ALL_WELDED) -> np.ndarray:
    """4x4 boundary matrix of w'''' + i beta^3 w' = 0 with w = w' = 0 (welded) or w = w'' = 0 (pinned, swivel)
    at s = 0 and s = 1.

    Basis 1, e^{m_j (s - s_j)} with s_j = 1 for Re m_j > 0 and 0 otherwise, so
    every entry is bounded by 1 and nothing overflows for large beta.
    """
    m = _complex_exponents(beta)
    shift = np.where(m.real > 0, 1.0, 0.0)
    rows = []
    for s, end in zip((0.0, 1.0), Ends.of(ends).conditions):
        e = np.exp(m * (s - shift))
        rows.append(np.concatenate([[1.0], e]))
        rows.append(np.concatenate([[0.0], m ** end.bending_order * e]))
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


def critical_loads(R: float, f: float, n: int = 5, ends: Ends = ALL_WELDED) -> np.ndarray:
    """Static magnetic buckling loads B_k = beta_k**3 sqrt(R) / f, k = 1..n.

    Dimensionless (eq. (36)); omega = T = 0. Each is a doubly
    degenerate pitchfork of the straight rod (Sec. VI A). ``ends``: the
    attachment (:func:`static_roots`; welded: the zeros of chi, eq. (91)).
    """
    betas = np.array([r.beta for r in static_roots(ends, n)])
    return betas**3 * math.sqrt(R) / f


# --- any attachment: the three closed-form characteristic functions -------------------


def _g_clamped(b, e1, e2):
    return e1 * np.cos(b) - np.cos(0.5 * b + math.pi / 3) - e2 * np.cos(0.5 * b - math.pi / 3)


def _g_mixed(b, e1, e2):
    return np.sin(0.5 * b) * (1.0 - 2.0 * e1 * np.cos(0.5 * b) + e2)


def _g_hinged(b, e1, e2):
    return e1 * np.cos(b) - np.sin(0.5 * b + math.pi / 6) - e2 * np.cos(0.5 * b + math.pi / 3)


@dataclass(frozen=True)
class _StaticForm:
    """Rung 0 for a pair of bending behaviours: ``reduced`` g e^-a from (beta, e^-a, e^-2a); the k-th zero near
    2 pi k + ``offset`` (``exact``: there exactly); ``chi``: the paper's chi (eq. (91)) is the scaled function and
    its double zeros are located on it (:func:`characteristic_roots`)."""

    reduced: Callable
    offset: float
    exact: bool = False
    chi: bool = False


#: Rung 0's closed forms by the (sorted) pair of the ends' bending behaviours (:attr:`Ends.bending`).
_STATIC = {
    (CLAMPED, CLAMPED): _StaticForm(_g_clamped, math.pi / 3, chi=True),
    (CLAMPED, HINGED): _StaticForm(_g_mixed, 0.0, exact=True),
    (HINGED, HINGED): _StaticForm(_g_hinged, -math.pi / 3),
}


def _form(ends) -> _StaticForm:
    return Ends.of(ends).entry(_STATIC, "closed-form static buckling (rung 0)")


def reduced_characteristic(beta, ends: Ends = ALL_WELDED):
    """The real characteristic function g(beta) of the static straight rod with these ends, times e^(-a),
    a = sqrt(3) beta / 2 (bounded, simple zeros at the buckling betas; see the module docstring):

        welded-welded  e^-a cos beta - cos(beta/2 + pi/3) - e^-2a cos(beta/2 - pi/3)
        pinned-pinned  e^-a cos beta - sin(beta/2 + pi/6) - e^-2a cos(beta/2 + pi/3)
        mixed          sin(beta/2) (1 - 2 e^-a cos(beta/2) + e^-2a)

    A swivel bends as a pin. Dimensionless; real or complex arrays (complex for the complex-step derivative)."""
    b = np.asarray(beta)
    e1 = np.exp(-0.5 * SQRT3 * b)
    e2 = e1 * e1
    return _form(ends).reduced(b, e1, e2)


def characteristic_scaled(beta, ends: Ends = ALL_WELDED):
    """chi(beta) e^(-sqrt(3) beta) of eq. (91) for welded ends, and its analogue 2 g(beta)^2 for others
    (:func:`reduced_characteristic`): the real 8 x 8 determinant, with double zeros. Dimensionless."""
    if _form(ends).chi:
        return chi_scaled(beta)
    return 2.0 * reduced_characteristic(np.asarray(beta, dtype=float), ends) ** 2


def _reduced_derivative(beta: float, ends: Ends) -> float:
    return float(np.imag(reduced_characteristic(beta + 1j * _H, ends)) / _H)


def _asymptote(k: int, ends: Ends) -> float:
    """Asymptotic position of the k-th buckling beta: pi/3 + 2 pi k welded, 2 pi k mixed, 2 pi k - pi/3 pinned."""
    return 2 * math.pi * k + _form(ends).offset


def _simple_zero(k: int, ends: Ends) -> float:
    """The k-th zero of g: 2 pi k for mixed ends; pinned-pinned, Newton's method from its asymptote
    2 pi k - pi/3, Brent's on that +- 1 should a step leave it."""
    guess = beta = _asymptote(k, ends)
    if _form(ends).exact:
        return beta
    lo, hi = guess - 1.0, guess + 1.0
    for _ in range(20):
        step = float(reduced_characteristic(beta, ends)) / _reduced_derivative(beta, ends)
        beta -= step
        if not lo < beta < hi:
            break
        if abs(step) <= 4 * np.finfo(float).eps * beta:
            return beta
    return brentq(lambda x: float(reduced_characteristic(x, ends)), lo, hi, xtol=1e-15,
                  rtol=4 * np.finfo(float).eps, maxiter=200)


def _root_record(k: int, ends: Ends) -> CharacteristicRoot:
    beta = _simple_zero(k, ends)
    slope = _reduced_derivative(beta, ends)
    singular = np.linalg.svd(_clamped_matrix(beta, ends), compute_uv=False)
    return CharacteristicRoot(
        k=k,
        beta=float(beta),
        residual=float(characteristic_scaled(beta, ends)),
        curvature=4.0 * slope**2,  # (2 g^2)'' at a zero of g
        kernel_dimension=2 * int(np.sum(singular < 1e-8 * singular[0])),
        error=max(abs(float(reduced_characteristic(beta, ends)) / slope) / beta, np.finfo(float).eps),
    )


@lru_cache(maxsize=64)
def static_roots(ends: Ends = ALL_WELDED, n: int = 5) -> tuple[CharacteristicRoot, ...]:
    """The first n buckling betas of the static straight rod with these ends (the double zeros of
    :func:`characteristic_scaled`), located to ~1e-15 relative: welded, the zeros of chi
    (:func:`characteristic_roots`); pinned-pinned, the simple zeros of g by Newton's method; mixed,
    beta = 2 pi k exactly. ``curvature``: the scaled function's second derivative at the zero (> 0, a
    touching zero); ``error``: the size of one more Newton step, relative."""
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    if _form(ends).chi:
        return characteristic_roots(n)
    return tuple(_root_record(k, ends) for k in range(1, n + 1))


def asymptotic_count(beta: float, ends: Ends = ALL_WELDED) -> int:
    """Number of buckling betas up to ``beta`` from their asymptotic positions (past the tabulated ones)."""
    return max(int((beta - _asymptote(0, ends)) // (2 * math.pi)), 0)


def beta_of_load(B: float, R: float, f: float) -> float:
    """beta = (f B)**(1/3) / R**(1/6) for a load B >= 0 (dimensionless)."""
    return (f * abs(B)) ** (1.0 / 3.0) / R ** (1.0 / 6.0)


def buckling_mode(k: int, R: float, s: np.ndarray, ends: Ends = ALL_WELDED) -> tuple[np.ndarray, np.ndarray]:
    """Shape (x(s), y(s)) of the k-th static buckling mode, dimensionless.

    One member of the two-dimensional kernel (the other is the same coil
    turned by a quarter period of w = x + i y / sqrt(R)). Normalised so that
    max sqrt(x^2 + y^2) = 1.
    """
    beta = static_roots(ends, k)[-1].beta
    m = _complex_exponents(beta)
    _, _, vh = np.linalg.svd(_clamped_matrix(beta, ends))
    c = vh[-1].conj()
    shift = np.where(m.real > 0, 1.0, 0.0)
    s = np.asarray(s, dtype=float)
    w = c[0] + np.exp(np.outer(s, m) - m * shift) @ c[1:]
    # pick the phase that makes x(s) largest (a well-defined, symmetric picture)
    w = w * np.exp(-1j * np.angle(w[np.argmax(np.abs(w))]))
    x, y = w.real, math.sqrt(R) * w.imag
    scale = np.max(np.hypot(x, y))
    return x / scale, y / scale


# --- the spectrum without load and spin (gamma = omega = B = 0; T = 0: Sec. VI B) -----------------


def _wavenumbers(mu, P: float, stiffness: float, tension: float = 0.0):
    """(a, b) of the Rayleigh beam under tension at frequency mu (f = 1): solutions cos(a s), sin(a s),
    cosh(b s), sinh(b s), with k^2 = b^2 and -a^2 the roots of S k^4 - (tension - P S mu^2) k^2 - mu^2 = 0
    (S the stiffness: R for the x (weak) equation and 1 for y; Sec. VI B at tension 0)."""
    c = tension / stiffness - P * mu**2
    root = np.sqrt(c * c + 4 * mu**2 / stiffness)
    return np.sqrt(0.5 * (root - c)), np.sqrt(np.maximum(0.5 * (root + c), 0.0))


def _clamped_beam_function(mu, P: float, stiffness: float, tension: float = 0.0):
    """Frequency equation of a clamped-clamped Rayleigh beam under tension, f = 1 (mu scalar or array).

    (a^2 - b^2) sin a sinh b - 2 a b (1 - cos a cosh b) = 0 with (a, b) of :func:`_wavenumbers`, divided by
    cosh b so it stays bounded (1 / cosh b written without overflow: under strong tension b is large).
    """
    a, b = _wavenumbers(mu, P, stiffness, tension)
    sech = 2.0 * np.exp(-b) / (1.0 + np.exp(-2.0 * b))
    return (a * a - b * b) * np.sin(a) * np.tanh(b) - 2 * a * b * (sech - np.cos(a))


def _clamped_pinned_beam_function(mu, P: float, stiffness: float, tension: float = 0.0):
    """Frequency equation of a clamped-pinned Rayleigh beam under tension (f = 1): with X = C1 (cos a s - cosh b s) +
    C2 (sin a s - (a/b) sinh b s) (clamped at s = 0), X(1) = X''(1) = 0 give (a^2 + b^2) (sin a cosh b -
    (a/b) cos a sinh b) = 0; written b sin a - a cos a tanh b (bounded; tan a = tanh a without rotary inertia
    and tension)."""
    a, b = _wavenumbers(mu, P, stiffness, tension)
    return b * np.sin(a) - a * np.cos(a) * np.tanh(b)


def bending_frequencies(P: float, R: float, f: float, n: int = 5, axis: str = "weak",
                        ends: Ends = ALL_WELDED, T: float = 0.0) -> np.ndarray:
    """First n bending frequencies mu (lambda = +- i mu) of the straight rod under the end tension T.

    Dimensionless, f-scaling; Sec. VI B transcendental equations with rotary inertia P, and the tension T
    (f-scaled as in eq. (36)) of the undamped, unloaded, non-spinning straight rod (docs/model.md, section 6:
    the weak equation is (R/f) u'''' - (T + P R lambda^2) u'' + lambda^2 u = 0). ``axis="weak"`` is the x
    equation (stiffness R, first frequency sqrt(R) as P, T -> 0 for welded ends), ``"stiff"`` the y equation
    (stiffness 1). ``ends``: pinned at both, the modes sin(k s), k = n pi, mu^2 = (S k^4 + f T k^2) /
    (P S k^2 + 1) (f = 1); one of each, the roots of :func:`_clamped_pinned_beam_function`. Under a strong
    tension the first ones approach the taut string's n pi sqrt(T).
    """
    if T < 0:
        raise ValueError("bending_frequencies: a compressive end force (T < 0) is not modelled here")
    stiffness = {"weak": R, "stiff": 1.0}[axis]
    frequencies = Ends.of(ends).entry(_FREQUENCIES, "bending frequencies")
    return frequencies(P, stiffness, f * T, n) / math.sqrt(f)


def _hinged_frequencies(P: float, stiffness: float, fT: float, n: int) -> np.ndarray:
    """The first n frequencies (f = 1) pinned at both ends: the modes sin(k s), k = n pi."""
    k = np.arange(1, n + 1) * math.pi
    return np.sqrt((stiffness * k**4 + fT * k**2) / (P * stiffness * k**2 + 1.0))


def _scanned_frequencies(equation, P: float, stiffness: float, fT: float, n: int) -> np.ndarray:
    """The first n roots (f = 1) of a frequency ``equation`` (mu, P, stiffness, fT)."""
    g = lambda mu: equation(mu, P, stiffness, fT)  # noqa: E731
    # the f = 1 frequency of the n-th mode is below that of a beam plus that of a string without rotary inertia
    # (rotary inertia only lowers them): scan finely and refine the first n sign changes to the last bits
    k = (n + 1.5) * math.pi
    mu_max = math.sqrt(stiffness * k**4 + fT * k**2)
    grid = np.linspace(1e-6 * mu_max / k**2, mu_max, 400 * (n + 2))
    values = g(grid)
    i = np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0][:n]
    if i.size < n:
        raise RuntimeError(f"found only {i.size} of {n} bending frequencies")
    return bracketed_roots(g, grid[i], grid[i + 1])


#: The first n bending frequencies (f = 1) from (P, stiffness, f T, n), by the (sorted) pair of the ends' bending
#: behaviours.
_FREQUENCIES = {
    (CLAMPED, CLAMPED): partial(_scanned_frequencies, _clamped_beam_function),
    (CLAMPED, HINGED): partial(_scanned_frequencies, _clamped_pinned_beam_function),
    (HINGED, HINGED): _hinged_frequencies,
}


def torsion_frequencies(P: float, Gamma: float, f: float, n: int = 5, ends: Ends = ALL_WELDED) -> np.ndarray:
    """Torsional frequencies mu_n = n pi sqrt(Gamma / (2 P f)), n = 1..n, with the twist held at both ends
    (welded or pinned); (n - 1/2) pi sqrt(Gamma / (2 P f)) with one end on a swivel (no torque there).

    Dimensionless, f-scaling (Sec. VI B, converted as in docs/errata.md, #6).
    Infinite for P = 0 (no rotary inertia).
    """
    if P == 0:
        return np.full(n, np.inf)
    order = np.arange(1, n + 1) - (0.0 if Ends.of(ends).holds_twist else 0.5)
    return order * math.pi * math.sqrt(Gamma / (2 * P * f))
