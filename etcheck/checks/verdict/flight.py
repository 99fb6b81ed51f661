"""A mission that flew: its flight outcome against the check's prediction, and what the model leaves out.

``[mission] flight = { outcome = "coiled", reported = "..." }`` records what the tether did in flight
("coiled": it left the straight state, buckled or tangled; "straight": it stayed straight) and who reported
it. The check compares that with its own verdict and lists what the model does not include that could
explain a difference, with this mission's numbers where the check has them.
"""

from __future__ import annotations

from etcheck.checks.margins.margin import Margin
from etcheck.checks.results.sections_verdict import FlightSection, ModelValidity
from etcheck.input.mission import Mission
from etcheck.rod.core.ends import describe

COILED, STRAIGHT = "coiled", "straight"


def flight(mission: Mission, verdict: str, margins: list[Margin], validity: ModelValidity) -> FlightSection | None:
    """The flight section (None for a mission without a flight record)."""
    if not mission.provenance.flight:
        return None
    outcome, reported = mission.provenance.flight["outcome"], mission.provenance.flight.get("reported", "")
    straight = [g for g in margins if g.value is not None and not g.name.startswith("buckled")]
    smallest = min(straight, key=lambda g: g.value) if straight else None
    within = ("the straight tether's smallest margin is "
              f"{smallest.value:.3g} ({smallest.name})" if smallest else "no margin of the straight tether")
    return FlightSection(outcome=outcome, reported=reported, prediction=verdict,
                         agreement=_agreement(outcome, verdict),
                         comparison=_comparison(outcome, verdict, within, validity),
                         not_modelled=_not_modelled(mission, validity, smallest))


def _ends(mission: Mission, smallest: Margin | None) -> str:
    """The attachment as checked, and the smallest margin under the other attachments where they were computed."""
    others = "; ".join(f"with both ends {a.ends[0]} {a.value:.3g}" for a in (smallest.alternatives if smallest
                                                                                       else ())
                       if a.value is not None and a.ends[0] == a.ends[1])
    return (f"the end attachment: the check holds the tether {describe(mission.tether.end_conditions)}, on its axis"
            + (f" (the smallest margin {others})" if others else "") + "; a real end turns, slides or slackens")


def _agreement(outcome: str, verdict: str) -> str:
    if verdict == "outside":
        return "not decided by the model"
    if verdict == "incomplete":
        return "not decided (the check is incomplete)"
    stays = verdict == "pass"
    return "agrees" if stays == (outcome == STRAIGHT) else "disagrees"


def _comparison(outcome: str, verdict: str, within: str, validity: ModelValidity) -> str:
    flown = "coiled in flight" if outcome == COILED else "stayed straight in flight"
    if verdict == "outside":
        return (f"The tether {flown}. The check finds the scene outside the straight-tether model's validity ("
                f"{'; '.join(validity.reasons)}): the model does not describe the tether as flown, so it can "
                f"neither confirm nor contradict the flight. Within the model, {within}.")
    if verdict == "pass":
        said = "predicts a straight tether that keeps the required margin"
    elif verdict == "fail":
        said = "predicts that the straight tether does not keep the required margin"
    else:
        said = "could not answer every margin"
    return f"The tether {flown}; the check {said} ({within}): {_agreement(outcome, verdict)}."


def _not_modelled(mission: Mission, validity: ModelValidity, smallest: Margin | None) -> tuple[str, ...]:
    lat = validity.lateral
    gg = mission.operation.gravity_gradient
    items = [
        f"the bow under the lateral Lorentz load: computed here, {100 * lat.bow_over_length:.3g} % of the length with "
        f"{lat.cross_field_T * 1e6:.3g} µT across the tether ({lat.cross_field_source}); the stability "
        "analysis itself assumes a straight tether",
        "the current along the tether: " + (
            "one current along the whole tether, as for an insulated tether (a bare tether's current varies "
            "along it and the load is then circulatory: give operation.current_profile)"
            if mission.operation.current_profile is None else
            "the profile given (operation.current_profile) is the model's; the real one varies with the plasma "
            "along the orbit"),
        _ends(mission, smallest),
        "libration, the orbit's eccentricity and the deployment dynamics: the model's tether is deployed and at "
        "rest on the local vertical (a swing lowers the tension by about cos² of its angle; slack or rebound at "
        "the end of deployment is not modelled)",
        "thermal effects and the tether's memory of its reel: the model's tether is intrinsically straight and "
        "at one temperature",
    ]
    if gg is not None:
        assumed = " (marked as assumed)" if mission.provenance.is_assumed("tether.end_masses") else ""
        items.append(f"the tension along the tether: the gravity-gradient profile ({gg.minimum:.3g} N at its "
                     f"{gg.minimum_at} to {gg.maximum:.3g} N at the centre) from end masses {gg.upper_mass:.4g} kg "
                     f"and {gg.lower_mass:.4g} kg{assumed}, on a tether at rest on the local vertical")
    return tuple(items)
