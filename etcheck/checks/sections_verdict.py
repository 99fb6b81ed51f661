"""The sections of a check's results that page 1 of the report reads: whether the scene is within the
model's validity, the assumptions that decide the verdict, the design limits and the flight record.

Plain JSON-able dicts typed key by key, as in :mod:`etcheck.checks.sections` (which re-exports them and
holds the rest); units in the key names, docs/results.schema.json the same layout as a JSON Schema.
"""

# no ``from __future__ import annotations``: TypedDict reads NotRequired from evaluated annotations only
from typing import TypedDict


class ValidityCheck(TypedDict):
    """One assumption of the model checked against its limit (``within`` None: not checked, ``detail`` says why)."""

    name: str
    quantity: str
    value: float | None
    limit: float
    within: bool | None
    detail: str
    summary: str  # the reason in a few words, for the verdict where it is exceeded


class LateralLoad(TypedDict):
    """The Lorentz load across the tether and the bow it implies (:func:`etcheck.checks.validity.lateral_load`)."""

    cross_field_T: float
    cross_field_source: str
    cross_field_assumed: bool
    current_A: float
    load_N_per_m: float
    total_N: float
    tension_N: float
    load_over_tension: float | None  # I B⊥ L / T (None without tension)
    stiffness_N_m2: float  # the bending stiffness it bends with (EI2, the weak axis)
    ends: str  # how its ends hold it against the bow
    bow_m: float
    bow_over_length: float
    limit: float
    tension_for_limit_N: float | None  # the smallest tension with the bow at the limit (None: within it)
    cross_field_for_limit_T: float | None  # the largest field across the tether with the bow at the limit


class ModelValidity(TypedDict):
    """``model_validity``: is the scene within the straight-tether model (:mod:`etcheck.checks.validity`)."""

    within: bool
    reasons: list[str]
    checks: list[ValidityCheck]
    lateral: LateralLoad


class AssumptionRecord(TypedDict):
    """One assumption that decides the verdict (:mod:`etcheck.checks.assumptions`); ``flag``: data, assumed,
    default or model; ``elasticity``: d ln margin / d ln input of the governing margin."""

    key: str
    assumption: str
    value: str
    source: str
    flag: str
    elasticity: float | None
    elasticity_method: str
    alternative: str | None
    margin_alternative: float | None
    note: str


class AssumptionsSection(TypedDict):
    """``assumptions``: the records and the margin they move (the smallest margin of the straight tether)."""

    margin: str | None
    margin_value: float | None
    required: float
    rows: list[AssumptionRecord]
    time_s: float


class DesignLimit(TypedDict):
    """How far one input may go with the straight tether's margins at the required margin
    (:mod:`etcheck.checks.design_limits`); ``status``: located, zero (no tension needed), none (not within a
    factor 100), not located, or not sought (an undamped spinning tether, a compressive end force)."""

    input: str
    label: str
    unit: str
    mission_value: float
    limit: float | None
    status: str
    margin_at_limit: float | None
    governing: str | None
    relative_error: float | None
    evaluations: int
    note: str
    end_mass_factor: float | None


class DesignLimitsSection(TypedDict):
    """``design_limits``: the longest tether, largest current, smallest tension and largest spin rate."""

    required: float
    tolerance: float
    limits: list[DesignLimit]
    time_s: float
    basis: str  # the model of the limits where it is not the check's own (a bound); "" otherwise


class FlightSection(TypedDict):
    """``flight``: the flight outcome against the prediction (:mod:`etcheck.checks.flight`)."""

    outcome: str
    reported: str
    prediction: str
    agreement: str
    comparison: str
    not_modelled: list[str]
