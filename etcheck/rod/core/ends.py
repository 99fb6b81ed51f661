"""How the tether is attached at its two ends: welded, pinned or on a swivel (dimensionless).

The paper welds both ends (clamped: eqs. (23)-(34), linearised (76)-(81)). A
tether that hangs from a gimbal, a hinge pair or a deployer's exit guide passes
force but no bending moment there. Three attachments, each holding the end's
position on the axis (x = y = 0; the sliding end s = 0 keeps F . e3 = T):

* ``"welded"``: the end's frame is held, d_i = e_i (bending and twist held);
  straight rod u = u' = v = v' = 0.
* ``"pinned"``: no bending moment, twist held (a gimbal or a cardan joint: it
  passes the torque about the tether's axis that keeps the tether spinning with
  the end body); straight rod u = u'' = v = v'' = 0, M . d1 = M . d2 = 0,
  twist (a x d1) . e2 = 0.
* ``"swivel"``: no moment at all (a ball joint or a swivel: it passes no torque,
  M = 0); bending as pinned, torsion free (M . d3 = 0) at that end. At least
  one end must hold the twist, or the tether turns freely about its axis (a
  neutral rigid rotation that the whirling model, spun by its end bodies, cannot
  carry).

Torsion decouples from bending about the straight rod, so for rungs 0 and 1
``"pinned"`` and ``"swivel"`` differ only in the torsional vibrations. The
pair is (end at s = 0, end at s = 1): the lower end first, then the upper.

Pure; the constants of the first bending modes are the classical beam roots.
"""

from __future__ import annotations

import math

__all__ = [
    "BUCKLED_WELDED_ONLY",
    "WELDED",
    "PINNED",
    "SWIVEL",
    "KINDS",
    "ALL_WELDED",
    "ALL_PINNED",
    "Ends",
    "bending_order",
    "check_ends",
    "clamped_count",
    "describe",
    "euler_load",
    "first_bending_root",
    "is_welded",
    "twist_held",
]

WELDED, PINNED, SWIVEL = "welded", "pinned", "swivel"
#: Why the buckled rungs (2-3) answer only for welded ends. Both ends pinned would keep the mirror symmetries S1, S2
#: of the welded problem (s -> 1 - s swaps two like ends); one of each keeps neither (docs/model.md).
BUCKLED_WELDED_ONLY = ("computed for welded ends only: the buckled tether's whirling equilibria hold the frame at "
                       "both ends (eqs. (58)-(69)), and the nonlinear condition of a pinned end (no bending moment, "
                       "M . d1 = M . d2 = 0 at an end that turns) is not part of rung 2")
#: The attachments an end may have.
KINDS = (WELDED, PINNED, SWIVEL)
Ends = tuple[str, str]
ALL_WELDED: Ends = (WELDED, WELDED)
ALL_PINNED: Ends = (PINNED, PINNED)

#: First root beta of the bending modes w'''' = beta^4 w (w = 0 at both ends) by the number of clamped ends:
#: pinned-pinned pi, clamped-pinned tan(beta) = tanh(beta), clamped-clamped cos(beta) cosh(beta) = 1.
_BENDING_ROOT = {0: math.pi, 1: 3.926602312047919, 2: 4.730040744862704}
#: First compressive (Euler) load T L^2 / EI of a column by the number of clamped ends: pi^2, 2.0457 pi^2
#: (tan(k) = k, k = 4.493409457909064), 4 pi^2.
_EULER = {0: math.pi**2, 1: 4.493409457909064**2, 2: 4.0 * math.pi**2}


def check_ends(ends) -> Ends:
    """``ends`` as a validated pair (a list or tuple of two of :data:`KINDS`). Raises ValueError."""
    pair = tuple(ends)
    if len(pair) != 2 or any(e not in KINDS for e in pair):
        raise ValueError(f"ends must be two of {KINDS}, got {ends!r}")
    if pair == (SWIVEL, SWIVEL):
        raise ValueError("ends: a swivel at both ends leaves the tether free to turn about its axis; "
                         "at least one end must hold the twist (welded or pinned)")
    return pair  # type: ignore[return-value]


def is_welded(ends: Ends) -> bool:
    """Both ends welded (the paper's case)."""
    return tuple(ends) == ALL_WELDED


def bending_order(end: str) -> int:
    """The derivative of the displacement held to zero at an end besides the displacement itself:
    1 (slope, welded) or 2 (curvature, i.e. no bending moment: pinned or swivel)."""
    return 1 if end == WELDED else 2


def twist_held(end: str) -> bool:
    """Whether the end holds the twist (welded, pinned) or passes no torque (swivel)."""
    return end != SWIVEL


def clamped_count(ends: Ends) -> int:
    """Number of ends where bending is held (welded)."""
    return sum(e == WELDED for e in ends)


def first_bending_root(ends: Ends) -> float:
    """beta of the first bending mode of a beam with these ends (beta^4 = least int w''^2 / int w^2)."""
    return _BENDING_ROOT[clamped_count(ends)]


def euler_load(ends: Ends) -> float:
    """First compressive load T L^2 / EI of a column with these ends (dimensionless, f = 1)."""
    return _EULER[clamped_count(ends)]


_WORDS = {WELDED: "welded", PINNED: "pinned", SWIVEL: "on a swivel"}
_MEANING = {PINNED: "no bending moment, twist held", SWIVEL: "no moment, free to twist"}


def describe(ends: Ends) -> str:
    """The attachment in words: "welded at both ends", "pinned at both ends (no bending moment, twist held)",
    "lower end welded, upper end pinned (no bending moment, twist held)"."""
    lower, upper = ends
    meaning = "; ".join(f"{_WORDS[e]}: {_MEANING[e]}" if lower != upper and len(set(ends) - {WELDED}) > 1
                        else _MEANING[e] for e in dict.fromkeys(ends) if e in _MEANING)
    said = f"{_WORDS[lower]} at both ends" if lower == upper else f"lower end {_WORDS[lower]}, upper end {_WORDS[upper]}"
    return f"{said} ({meaning})" if meaning else said
