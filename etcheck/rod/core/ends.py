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

Each kind is an :class:`EndCondition` (one class, one instance in :data:`REGISTRY` under its name) that owns its
rows: those of the collocation operator (:func:`etcheck.rod.core.linear.end_rows`) and those of the exact
determinant's scaled state (:mod:`etcheck.rod.straight.exact.determinant`). :class:`Ends` is the pair, a tuple of the
two names (as mission files and results write them) that answers what depends on both ends: the first beam
mode and Euler load of :data:`BEAMS`, looked up by the pair of the ends' bending behaviours (``CLAMPED``,
``HINGED``), never by a count of clamped ends, so that a kind that bends in a new way is a new entry.

Pure; the constants of the first bending modes are the classical beam roots.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

if TYPE_CHECKING:  # numpy loads with the first rows asked for: `etcheck --help` reads the kinds without it
    import numpy as np

__all__ = [
    "BUCKLED_WELDED_ONLY",
    "CLAMPED",
    "HINGED",
    "WELDED",
    "PINNED",
    "SWIVEL",
    "KINDS",
    "REGISTRY",
    "BEAMS",
    "ALL_WELDED",
    "ALL_PINNED",
    "Beam",
    "EndCondition",
    "Welded",
    "Pinned",
    "Swivel",
    "Ends",
    "register",
    "describe",
    "is_welded",
]

WELDED, PINNED, SWIVEL = "welded", "pinned", "swivel"
#: Why the buckled rungs (2-3) answer only for welded ends. Both ends pinned would keep the mirror symmetries S1, S2
#: of the welded problem (s -> 1 - s swaps two like ends); one of each keeps neither (docs/model.md).
BUCKLED_WELDED_ONLY = ("computed for welded ends only: the buckled tether's whirling equilibria hold the frame at "
                       "both ends (eqs. (58)-(69)), and the nonlinear condition of a pinned end (no bending moment, "
                       "M . d1 = M . d2 = 0 at an end that turns) is not part of rung 2")
#: Bending behaviours of an end, the keys of the pair tables: the slope held (w = w' = 0) or no bending moment
#: (w = w'' = 0).
CLAMPED, HINGED = "clamped", "hinged"


@dataclass(frozen=True)
class EndCondition:
    """One way of attaching an end (dimensionless); a subclass per kind, its one instance in :data:`REGISTRY`.

    Every kind holds the end's position on the axis. Class attributes: ``name`` (in mission files and results),
    ``words`` (in sentences: "on a swivel"), ``meaning`` (what it passes, "" where the word says it),
    ``bending`` (:data:`CLAMPED` or :data:`HINGED`, the key of the pair tables), ``bending_order`` (the derivative
    of the displacement held to zero besides the displacement itself: 1 the slope, 2 the curvature, i.e. no
    bending moment) and ``holds_twist`` (False: it passes no torque). A subclass of :class:`Welded` or
    :class:`Pinned` bends as they do and inherits their determinant rows.
    """

    name: ClassVar[str]
    words: ClassVar[str]
    meaning: ClassVar[str]
    bending: ClassVar[str]
    bending_order: ClassVar[int]
    holds_twist: ClassVar[bool]

    @property
    def holds_slope(self) -> bool:
        """Whether the end holds the bending slope (u' = v' = 0)."""
        return self.bending_order == 1

    @property
    def free_moments(self) -> tuple[int, ...]:
        """The body axes j (0, 1, 2 for d1, d2, d3) about which the end passes no moment (M . d_j = 0)."""
        return (() if self.holds_slope else (0, 1)) + (() if self.holds_twist else (2,))

    def collocation_rows(self, rotation: np.ndarray, d: np.ndarray, m0: np.ndarray | None) -> np.ndarray:
        """The end's three linearised conditions at its node, as coefficients (3, 6) of (a, m) (e-frame).

        ``rotation`` (3, 3): the rows on a that hold the end's frame, (a x d3) . e1 = (a x d3) . e2 = 0 (the
        slope) and (a x d1) . e2 = 0 (the twist), eqs. (76)-(81); ``d`` (3, 3): the base frame there, column
        j = d_j; ``m0`` (3,): the base contact moment there (needed only where :attr:`free_moments`). Row j of
        each free moment is replaced by no perturbed moment about d_j, (m + M0 x a) . d_j = m . d_j +
        a . (d_j x M0) = 0."""
        import numpy as np

        rows = np.zeros((3, 6))
        rows[:, :3] = rotation
        for j in self.free_moments:
            rows[j, 3:] = d[:, j]
            rows[j, :3] = np.cross(d[:, j], m0)
        return rows

    def real_rows(self) -> np.ndarray:
        """Rows of the real scaled state (u, u'/ku, u''/ku^2, u'''/ku^3, v, ..) held at this end."""
        import numpy as np

        return np.array([0, self.bending_order, 4, 4 + self.bending_order])

    def complex_rows(self) -> np.ndarray:
        """Rows of the complex scaled state (w, w'/kap, ..) held at this end."""
        import numpy as np

        return np.array([0, self.bending_order])

    def real_values(self, u: np.ndarray, v: np.ndarray, k: np.ndarray, ku: np.ndarray, kv: np.ndarray) -> np.ndarray:
        """The held values (n, 4, m) of the basis solutions (u, v) exp(k s) (u, v, k: (n, m)) at s = 0 in the
        real scaled state (:meth:`real_rows`; ku, kv (n,) the scales)."""
        raise ValueError(f"{type(self).__name__} gives no rows for the exact determinant (the collocation routes take it)")

    def complex_values(self, ms: np.ndarray) -> np.ndarray:
        """The held values (n, 2, m) of the basis solutions exp(m s) at s = 0 in the complex scaled state,
        ``ms`` = m / kap (n, m) (:meth:`complex_rows`)."""
        raise ValueError(f"{type(self).__name__} gives no rows for the exact determinant (the collocation routes take it)")


#: The kinds by name (what mission files and results write), in the order they are offered.
REGISTRY: dict[str, EndCondition] = {}


def register(kind: type[EndCondition]) -> type[EndCondition]:
    """Class decorator: put the kind's instance in :data:`REGISTRY` under its ``name``."""
    if kind.name in REGISTRY:
        raise ValueError(f"an end condition named {kind.name!r} is registered already")
    REGISTRY[kind.name] = kind()
    return kind


@register
@dataclass(frozen=True)
class Welded(EndCondition):
    """Welded (clamped): the end's frame held; u = u' = v = v' = 0 on the straight rod."""

    name: ClassVar[str] = WELDED
    words: ClassVar[str] = "welded"
    meaning: ClassVar[str] = ""
    bending: ClassVar[str] = CLAMPED
    bending_order: ClassVar[int] = 1
    holds_twist: ClassVar[bool] = True

    def real_values(self, u, v, k, ku, kv):
        import numpy as np

        return np.stack([u, u * k / ku[:, None], v, v * k / kv[:, None]], axis=1)

    def complex_values(self, ms):
        import numpy as np

        return np.stack([np.ones_like(ms), ms], axis=1)


@register
@dataclass(frozen=True)
class Pinned(EndCondition):
    """Pinned (a gimbal): no bending moment, twist held; u = u'' = v = v'' = 0 on the straight rod."""

    name: ClassVar[str] = PINNED
    words: ClassVar[str] = "pinned"
    meaning: ClassVar[str] = "no bending moment, twist held"
    bending: ClassVar[str] = HINGED
    bending_order: ClassVar[int] = 2
    holds_twist: ClassVar[bool] = True

    def real_values(self, u, v, k, ku, kv):
        import numpy as np

        return np.stack([u, u * (k / ku[:, None]) ** 2, v, v * (k / kv[:, None]) ** 2], axis=1)

    def complex_values(self, ms):
        import numpy as np

        return np.stack([np.ones_like(ms), ms**2], axis=1)


@register
@dataclass(frozen=True)
class Swivel(Pinned):
    """On a swivel (a ball joint): no moment at all; bends as a pin, free to twist."""

    name: ClassVar[str] = SWIVEL
    words: ClassVar[str] = "on a swivel"
    meaning: ClassVar[str] = "no moment, free to twist"
    holds_twist: ClassVar[bool] = False


#: The attachments an end may have (the names of :data:`REGISTRY`'s kinds).
KINDS = tuple(REGISTRY)


@dataclass(frozen=True)
class Beam:
    """The first bending mode phi of a beam w'''' = beta^4 w (w = 0 at both ends) with a pair of bending
    behaviours (dimensionless, f = 1): ``root`` its beta, ``euler_load`` the first compressive load
    T L^2 / EI of the column, ``slope_quotient`` int phi'^2 / int phi^2 (to 4 digits: a scan's scale)."""

    root: float
    euler_load: float
    slope_quotient: float


#: The first beam mode by the (sorted) pair of the ends' bending behaviours: clamped-clamped cos(beta)
#: cosh(beta) = 1 and Euler load 4 pi^2; clamped-hinged tan(beta) = tanh(beta) and 2.0457 pi^2 (tan(k) = k,
#: k = 4.493409457909064); hinged-hinged pi and pi^2.
BEAMS: dict[tuple[str, str], Beam] = {
    (CLAMPED, CLAMPED): Beam(4.730040744862704, 4.0 * math.pi**2, 12.30),
    (CLAMPED, HINGED): Beam(3.926602312047919, 4.493409457909064**2, 11.51),
    (HINGED, HINGED): Beam(math.pi, math.pi**2, math.pi**2),
}


class Ends(tuple[str, str]):
    """The attachment of both ends: the pair (lower end at s = 0, upper end at s = 1) of kind names.

    A tuple of the names, so it prints, compares, hashes, pickles and serialises (JSON, ``dataclasses.asdict``)
    as the names do; :attr:`lower`, :attr:`upper` are the kinds (:class:`EndCondition`), and the pair answers
    what depends on both ends. ``Ends(["welded", "pinned"])`` validates; :meth:`of` leaves an Ends as it is.
    Raises ValueError for unknown names, not two of them, or no end that holds the twist.
    """

    __slots__ = ()

    def __new__(cls, names) -> Ends:
        pair = tuple(names)
        if len(pair) != 2 or any(not isinstance(e, str) or e not in REGISTRY for e in pair):
            raise ValueError(f"ends must be two of {tuple(REGISTRY)}, got {names!r}")
        if not any(REGISTRY[e].holds_twist for e in pair):
            said = f"a {pair[0]} at both ends" if pair[0] == pair[1] else f"a {pair[0]} and a {pair[1]}"
            holding = " or ".join(name for name, kind in REGISTRY.items() if kind.holds_twist)
            raise ValueError(f"ends: {said} leaves the tether free to turn about its axis; at least one end must "
                             f"hold the twist ({holding})")
        return super().__new__(cls, pair)

    @classmethod
    def of(cls, ends) -> Ends:
        """``ends`` (a pair of names, e.g. from a mission file or JSON) as an Ends; an Ends as it is."""
        return ends if isinstance(ends, Ends) else cls(ends)

    @property
    def lower(self) -> EndCondition:
        return REGISTRY[self[0]]

    @property
    def upper(self) -> EndCondition:
        return REGISTRY[self[1]]

    @property
    def conditions(self) -> tuple[EndCondition, EndCondition]:
        """(lower, upper) as kinds."""
        return self.lower, self.upper

    @property
    def bending(self) -> tuple[str, str]:
        """The key of the pair tables: the ends' bending behaviours, sorted (the straight rod's answers that
        depend on bending alone are the same with the ends swapped)."""
        return tuple(sorted(e.bending for e in self.conditions))  # type: ignore[return-value]

    def entry(self, table: dict, what: str):
        """``table[self.bending]``; a ValueError that says which entry is missing."""
        try:
            return table[self.bending]
        except KeyError:
            raise ValueError(f"no {what} for the ends {self[0]}, {self[1]}: the table has no entry for the "
                             f"bending pair {self.bending}") from None

    @property
    def is_welded(self) -> bool:
        """Both ends welded (the paper's case)."""
        return tuple(self) == (WELDED, WELDED)

    @property
    def holds_twist(self) -> bool:
        """Whether both ends hold the twist."""
        return all(e.holds_twist for e in self.conditions)

    @property
    def beam(self) -> Beam:
        return self.entry(BEAMS, "beam mode")

    @property
    def first_bending_root(self) -> float:
        """beta of the first bending mode of a beam with these ends (beta^4 = least int w''^2 / int w^2)."""
        return self.beam.root

    @property
    def euler_load(self) -> float:
        """First compressive load T L^2 / EI of a column with these ends (dimensionless, f = 1)."""
        return self.beam.euler_load

    def describe(self) -> str:
        """The attachment in words: "welded at both ends", "pinned at both ends (no bending moment, twist
        held)", "lower end welded, upper end pinned (no bending moment, twist held)"."""
        lower, upper = self.conditions
        kinds = [e for e in dict.fromkeys(self.conditions) if e.meaning]
        both = lower != upper and len(kinds) > 1
        meaning = "; ".join(f"{e.words}: {e.meaning}" if both else e.meaning for e in kinds)
        said = f"{lower.words} at both ends" if lower == upper else f"lower end {lower.words}, upper end {upper.words}"
        return f"{said} ({meaning})" if meaning else said


ALL_WELDED = Ends((WELDED, WELDED))
ALL_PINNED = Ends((PINNED, PINNED))


def describe(ends) -> str:
    """:meth:`Ends.describe` of a pair of names (a mission's ``end_conditions``)."""
    return Ends.of(ends).describe()


def is_welded(ends) -> bool:
    """:attr:`Ends.is_welded` of a pair of names: both ends welded (the paper's case)."""
    return Ends.of(ends).is_welded
