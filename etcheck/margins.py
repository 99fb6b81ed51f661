"""Results -> margins and verdicts, back in physical units."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

PASS, FAIL, INCOMPLETE = "pass", "fail", "incomplete"


@dataclass(frozen=True)
class Margin:
    """One design margin: critical / operating, judged against the required margin.

    ``critical`` and ``operating`` are in ``unit`` (SI); ``value`` is their
    ratio (None when the operating value is zero: an unlimited margin);
    ``error`` the estimated relative numerical error of ``value``.
    """

    name: str
    unit: str
    critical: float | None
    operating: float
    required: float
    verdict: str
    model: str
    error: float | None
    why: str
    value: float | None = None

    def as_dict(self) -> dict:
        return asdict(self)


def ratio_margin(
    name: str,
    unit: str,
    critical: float,
    operating: float,
    required: float,
    model: str,
    error: float,
    why: str,
) -> Margin:
    """Margin = critical / operating (both >= 0, same unit); pass if >= required.

    A margin that passes only within its numerical error is judged on the
    pessimistic side (value * (1 - error)).
    """
    if operating == 0:
        return Margin(name, unit, critical, operating, required, PASS, model, error, why, None)
    value = critical / operating
    verdict = PASS if value * (1.0 - error) >= required else FAIL
    return Margin(name, unit, critical, operating, required, verdict, model, error, why, value)


def incomplete_margin(name: str, unit: str, operating: float, required: float, model: str, why: str) -> Margin:
    """A margin the chosen model cannot answer: never a pass."""
    return Margin(name, unit, None, operating, required, INCOMPLETE, model, None, why, None)


def overall_verdict(margins: list[Margin]) -> str:
    verdicts = {m.verdict for m in margins}
    if FAIL in verdicts:
        return FAIL
    if INCOMPLETE in verdicts or not margins:
        return INCOMPLETE
    return PASS


def finite_or_none(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else x
