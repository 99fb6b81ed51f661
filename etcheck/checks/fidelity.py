"""Sign-off or draft: what a check computes, at which tolerance, and what a draft leaves out.

A sign-off check (the default) computes everything the report shows. A draft
answers the margins and the verdict only, at a looser tolerance: no stability
map, no Campbell diagram, no accuracy table, no post-buckling analysis (the
straight tether's margins decide the verdict either way: a tether past its
first critical load fails them); a damped tether's critical values start their
two-resolution ladder one rung lower (N = 12 checked at 20: half the cost,
errors of ~1e-7 for SET instead of ~1e-11).
"""

from __future__ import annotations

from dataclasses import dataclass

from etcheck.checks.results.sections import FidelitySection

#: relative two-resolution agreement of a draft's critical values and eigenvalues
DRAFT_TOLERANCE = 1e-6
#: the CLI's seconds of a sign-off's computation after which the report's extras not yet computed (operating
#: spectrum, Campbell diagram, stability map, accuracy table) are skipped, saying so: with the imports, the report
#: process and the reports a sign-off stays within about 10 s on two cores; the margins are always answered
TIME_BUDGET = 5.0

LEFT_OUT = ("stability map", "Campbell diagram", "eigenvalues at the operating point (damped tethers)",
            "stable spin windows and, without spin, the critical spin (undamped tethers)",
            "accuracy table", "post-buckling analysis (rungs 2-3)",
            "how far the margin moves with each assumption", "design limits",
            "the margins under the other attachments of the ends")


@dataclass(frozen=True)
class Fidelity:
    """Which fidelity ran: ``name`` "sign-off" or "draft", its tolerance and what it left out."""

    name: str
    tolerance: float
    left_out: tuple[str, ...] = ()

    @property
    def draft(self) -> bool:
        return self.name == "draft"

    def section(self) -> FidelitySection:
        """The ``fidelity`` section of the results."""
        return FidelitySection(name=self.name, tolerance=self.tolerance, left_out=self.left_out)


def fidelity_of(draft: bool, tolerance: float) -> Fidelity:
    """The precision a mission's ``[check]`` asks for: a ``draft`` or a sign-off (``tolerance``: its
    ``[check] tolerance``)."""
    if draft:
        return Fidelity("draft", max(tolerance, DRAFT_TOLERANCE), LEFT_OUT)
    return Fidelity("sign-off", tolerance)
