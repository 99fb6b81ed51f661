"""Results -> margins and verdicts, back in physical units."""

from __future__ import annotations

from dataclasses import asdict, dataclass

from .plan import RUNG_NAMES

PASS, FAIL, INCOMPLETE = "pass", "fail", "incomplete"


@dataclass(frozen=True)
class Margin:
    """One design margin: critical / operating, judged against the required margin.

    ``critical`` and ``operating`` are in ``unit`` (SI); ``value`` is their
    ratio (None when the operating value is zero: an unlimited margin, or when
    the check is incomplete); ``error`` is the estimated relative numerical
    error of ``value``; ``rung`` the model that answered.
    """

    name: str
    unit: str
    critical: float | None
    operating: float
    value: float | None
    required: float
    verdict: str
    rung: int
    error: float | None
    why: str

    @property
    def model(self) -> str:
        return RUNG_NAMES[self.rung]

    def as_dict(self) -> dict:
        return asdict(self) | {"model": self.model}


def ratio_margin(
    name: str, unit: str, critical: float, operating: float, required: float, rung: int, error: float, why: str
) -> Margin:
    """Margin = critical / operating (both >= 0, same unit); pass if >= required.

    A margin is judged on its pessimistic side, value * (1 - error), so a
    numerical error can never turn a fail into a pass.
    """
    if operating == 0:
        return Margin(name, unit, critical, operating, None, required, PASS, rung, error, why)
    value = critical / operating
    verdict = PASS if value * (1.0 - error) >= required else FAIL
    return Margin(name, unit, critical, operating, value, required, verdict, rung, error, why)


def incomplete_margin(name: str, unit: str, operating: float, required: float, rung: int, why: str) -> Margin:
    """A margin the chosen model cannot answer: never a pass."""
    return Margin(name, unit, None, operating, None, required, INCOMPLETE, rung, None, why)


def overall_verdict(margins: list[Margin]) -> str:
    verdicts = {m.verdict for m in margins}
    if FAIL in verdicts:
        return FAIL
    if INCOMPLETE in verdicts or not margins:
        return INCOMPLETE
    return PASS
