"""Scene -> which model rung answers it, and why (the model ladder of the README)."""

from __future__ import annotations

from dataclasses import dataclass

from etcheck.rod.parameters import RodParameters

RUNG_NAMES = {0: "rung 0 (analytic)", 1: "rung 1 (linear spectral)",
              3: "rungs 2-3 (post-buckling equilibria and their stability)"}


@dataclass(frozen=True)
class Plan:
    """The rung chosen for the straight-tether stability question and why.

    ``complete`` is False when the requested fidelity cannot answer the scene
    (the check is then incomplete and never passes).
    """

    rung: int
    reason: str
    complete: bool = True

    @property
    def model(self) -> str:
        return RUNG_NAMES[self.rung]


def plan(params: RodParameters, fidelity: str = "auto") -> Plan:
    """Pick the cheapest rung that answers the straight-tether question exactly.

    Rung 0 is exact for the static problem (omega = 0, T = 0; damping does not
    move static loads). Spin or end tension needs rung 1.
    """
    static = params.omega == 0 and params.T == 0
    if static and fidelity in ("auto", "draft", "analytic"):
        return Plan(0, "no spin and no end tension: the static buckling loads of chi(beta) are exact")
    if static:
        return Plan(1, "fidelity = linear requested (rung 0 would be exact here)")
    why = []
    if params.omega != 0:
        why.append("spin")
    if params.T != 0:
        why.append("end tension")
    moving = " and ".join(why)
    if fidelity == "analytic":
        return Plan(
            0,
            f"the mission has {moving}, which rung 0 (static, tension-free) does not model; "
            "fidelity = analytic was requested, so the check is incomplete",
            complete=False,
        )
    return Plan(1, f"the mission has {moving}: rung 0 does not model it, the linear spectral model does")
