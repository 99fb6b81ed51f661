"""Scene -> which model rung answers it, and why (the model ladder of the README)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from etcheck.rod.core.ends import describe, is_welded
from etcheck.rod.core.parameters import RodParameters

#: end boundary layers thinner than this fraction of the length are left to the exact determinant:
#: Chebyshev collocation on the whole length needs N of order 1/sqrt(width) and more to resolve them
LAYER_MIN = 0.02
#: below this stiffness ratio the weak axis is nearly a string: the exact determinant (collocation is ill-conditioned)
R_MIN_SPECTRAL = 1e-3

SPECTRAL, EXACT, PROFILES = "spectral", "exact determinant", "profiles"
EXACT_MODEL = "rung 1 (linear, exact characteristic determinant)"
PROFILES_MODEL = "rung 1v (linear, profiles along the tether)"

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
    route: str = ""

    @property
    def model(self) -> str:
        return route_model(self.rung, self.route)


def route_model(rung: int, route: str) -> str:
    """The model that answers on a rung and route."""
    if rung == 1 and route == EXACT:
        return EXACT_MODEL
    if rung == 1 and route == PROFILES:
        return PROFILES_MODEL
    return RUNG_NAMES[rung]


def boundary_layer(params: RodParameters) -> float:
    """Width (fraction of L, dimensionless) of the thinner end boundary layer of the straight tether.

    Under the effective tension T + P R omega^2 the weak-axis bending stiffness R/f acts only in
    layers of width sqrt(R / (f T_eff)) at the ends (welded or pinned: a pinned end's layer is weaker, of
    amplitude eps^2 u'', but as thin); inf without tension.
    """
    tension = params.T + params.P * params.R * params.omega**2
    return math.sqrt(params.R / (params.f * tension)) if tension > 0 else math.inf


def straight_route(params: RodParameters) -> str:
    """How the straight tether's critical values are computed: "spectral" (Chebyshev collocation
    of rung 1) or "exact determinant" (the constant-coefficient characteristic determinant,
    :mod:`etcheck.rod.straight.exact.roots`) where the boundary layers are thinner than LAYER_MIN or the
    weak axis is nearly a string (R < R_MIN_SPECTRAL), with or without damping
    (:mod:`etcheck.rod.straight.exact.undamped` without). Both are exact where both apply (tested to 1e-9)."""
    if boundary_layer(params) < LAYER_MIN or params.R < R_MIN_SPECTRAL:
        return EXACT
    return SPECTRAL


def _plan_profiles(model: str, profiles: str) -> Plan:
    if model == "analytic":
        return Plan(0, f"the mission has {profiles} along the tether, which rung 0 (one current, no tension) does "
                    "not model; fidelity = analytic was requested, so the check is incomplete", complete=False)
    return Plan(1, f"the mission has {profiles} along the tether: the straight tether's linear stability with "
                "variable coefficients (graded collocation resolving its end layers), stability read from the "
                "eigenvalues (divergence or flutter)", route=PROFILES)


def varies_along(sc) -> str:
    """What varies along the tether of a scene (:class:`etcheck.scaling.Scene`), in words ("" when nothing does:
    one current, one tension)."""
    parts = (["a current"] if sc.current_profile is not None else []) + (
        ["a gravity-gradient tension"] if sc.gravity_gradient is not None else [])
    return " and ".join(parts)


#: what a draft of a tether with only its tension along it answers (the plan's reason says it)
DRAFT_BOUND = ("a draft takes the gravity-gradient tension at its smallest value along the whole tether (a "
               "conservative bound: tension stabilises the straight tether under one current); a sign-off uses "
               "the profile (rung 1v)")


def modelled_along(sc, draft: bool) -> str:
    """What varies along the tether that a check models (:func:`varies_along`): a ``draft`` takes a tension
    profile under one current at its smallest value (:data:`DRAFT_BOUND`), a current along the tether never (one
    current is no bound for a circulatory load)."""
    if draft and sc.current_profile is None:
        return ""
    return varies_along(sc)


def plan(params: RodParameters, model: str = "auto", profiles: str = "") -> Plan:
    """Pick the cheapest rung that answers the straight-tether question exactly (``model``: which model the
    mission asks for, :data:`etcheck.input.mission.MODELS`).

    Rung 0 is exact for the static problem (omega = 0, T = 0; damping does not
    move static loads). Spin or end tension needs rung 1. A current or a tension
    that varies along the tether (``profiles``: what varies, in words) needs
    rung 1v (docs/model.md section 10).
    """
    if profiles:
        return _plan_profiles(model, profiles)
    static = params.omega == 0 and params.T == 0
    if static and model in ("auto", "analytic"):
        if is_welded(params.ends):
            return Plan(0, "no spin and no end tension: the static buckling loads of chi(beta) are exact")
        return Plan(0, f"no spin and no end tension: the static buckling loads of the tether {describe(params.ends)} "
                    "are exact (the zeros of its closed-form characteristic function)")
    if static:
        return Plan(1, "fidelity = linear requested (rung 0 would be exact here)", route=SPECTRAL)
    why = []
    if params.omega != 0:
        why.append("spin")
    if params.T != 0:
        why.append("end tension")
    moving = " and ".join(why)
    if model == "analytic":
        return Plan(
            0,
            f"the mission has {moving}, which rung 0 (static, tension-free) does not model; "
            "fidelity = analytic was requested, so the check is incomplete",
            complete=False,
        )
    route = straight_route(params)
    if route == SPECTRAL:
        return Plan(1, f"the mission has {moving}: rung 0 does not model it, the linear spectral model does", route=route)
    layer = boundary_layer(params)
    held = "welded ends" if is_welded(params.ends) else "ends"
    why_exact = (f"boundary layers of {layer:.2g} L at the {held}" if layer < LAYER_MIN
                 else f"a nearly string-like weak axis (R = {params.R:.2g})")
    if params.gamma <= 0:
        return Plan(1, f"the mission has {moving} and {why_exact}, too thin for collocation, and no damping: the "
                    "critical values come from the exact characteristic determinant of the undamped straight tether "
                    "(divergence and flutter points, where two vibration modes meet, located exactly)", route=route)
    return Plan(1, f"the mission has {moving} and {why_exact}, too thin for collocation: the critical values come "
                "from the exact characteristic determinant of the constant-coefficient straight tether "
                "(with damping, stability is lost only where it vanishes: Kelvin-Tait-Chetaev)", route=route)
