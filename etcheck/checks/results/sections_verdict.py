"""The sections of a check's results that page 1 of the report reads: whether the scene is within the
model's validity, the assumptions that decide the verdict, the design limits and the flight record.

Records typed field by field, as in :mod:`etcheck.checks.results.sections` (which re-exports them and
holds the rest); units in the key names, docs/results.schema.json the same layout as a JSON Schema.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal

from etcheck.jsonable import key


@dataclass(frozen=True, slots=True, kw_only=True)
class ValidityCheck:
    """One assumption of the model checked against its limit (``within`` None: not checked, ``detail`` says why)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "one assumption of the model checked against its limit (within null: not checked)"
    }

    name: str
    quantity: str
    value: float | None
    limit: float
    within: bool | None
    detail: str
    summary: str = key(
        "the reason in a few words, for the verdict where it is exceeded"
    )  # the reason in a few words, for the verdict where it is exceeded


@dataclass(frozen=True, slots=True, kw_only=True)
class LateralLoad:
    """The Lorentz load across the tether and the bow it implies (:func:`etcheck.checks.verdict.validity.lateral_load`)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "the Lorentz load across the tether and the bow it implies (SI)"}

    cross_field_T: float
    cross_field_source: str
    cross_field_assumed: bool
    current_A: float
    load_N_per_m: float
    total_N: float
    tension_N: float
    load_over_tension: float | None = key("I B⊥ L / T; null without tension")  # I B⊥ L / T (None without tension)
    stiffness_N_m2: float = key(
        "the bending stiffness it bends with (EI2)"
    )  # the bending stiffness it bends with (EI2, the weak axis)
    bow_m: float
    bow_over_length: float
    limit: float
    tension_for_limit_N: float | None = key(
        "the smallest tension that keeps the bow at the limit; null within it"
    )  # the smallest tension with the bow at the limit (None: within it)
    ends: str = key("how its ends hold it against the bow")  # how its ends hold it against the bow
    cross_field_for_limit_T: float | None = key(
        "the largest field across the tether that keeps the bow at the limit; null within it"
    )  # the largest field across the tether with the bow at the limit


@dataclass(frozen=True, slots=True, kw_only=True)
class ModelValidity:
    """``model_validity``: is the scene within the straight-tether model (:mod:`etcheck.checks.verdict.validity`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "whether the scene is within the straight-tether model: straight under the lateral Lorentz load, slender, inextensible (etcheck.checks.verdict.validity)"
    }

    within: bool
    reasons: tuple[str, ...]
    checks: tuple[ValidityCheck, ...]
    lateral: LateralLoad


@dataclass(frozen=True, slots=True, kw_only=True)
class AssumptionRecord:
    """One assumption that decides the verdict (:mod:`etcheck.checks.verdict.assumptions`); ``flag``: data, assumed,
    default or model; ``elasticity``: d ln margin / d ln input of the governing margin."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "one assumption that decides the verdict; flag: data, assumed, default or model"
    }

    key: str
    assumption: str
    value: str
    source: str
    flag: Literal["data", "assumed", "default", "model"]
    elasticity: float | None = key("d ln margin / d ln input of the smallest straight margin")
    elasticity_method: str
    alternative: str | None
    margin_alternative: float | None
    note: str


@dataclass(frozen=True, slots=True, kw_only=True)
class AssumptionsSection:
    """``assumptions``: the records and the margin they move (the smallest margin of the straight tether)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the assumptions that decide the verdict and how far the smallest margin moves with each (etcheck.checks.verdict.assumptions); null in a draft or where the check is incomplete"
    }

    margin: str | None
    margin_value: float | None
    required: float
    rows: tuple[AssumptionRecord, ...]
    time_s: float


@dataclass(frozen=True, slots=True, kw_only=True)
class DesignLimit:
    """How far one input may go with the straight tether's margins at the required margin
    (:mod:`etcheck.checks.verdict.design_limits`); ``status``: located, zero (no tension needed), none (not within a
    factor 100), not located, or not sought (an undamped spinning tether, a compressive end force)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "how far one input may go with the straight tether's margins at the required margin"
    }

    input: Literal["length", "current", "end_tension", "spin_rate"]
    label: str
    unit: str
    mission_value: float
    limit: float | None
    status: Literal["located", "zero", "none", "not located", "not sought"]
    margin_at_limit: float | None
    governing: str | None
    relative_error: float | None
    evaluations: int
    note: str
    end_mass_factor: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class DesignLimitsSection:
    """``design_limits``: the longest tether, largest current, smallest tension and largest spin rate."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the longest tether, largest current, smallest tension and largest spin rate that meet the required margin (etcheck.checks.verdict.design_limits); null in a draft or where the check is incomplete"
    }

    required: float
    tolerance: float
    limits: tuple[DesignLimit, ...]
    time_s: float
    basis: str = key(
        "the model the limits come from where it is not the check's own (a tether with its tension along it: the smallest tension held constant); empty otherwise"
    )  # the model of the limits where it is not the check's own (a bound); "" otherwise


@dataclass(frozen=True, slots=True, kw_only=True)
class FlightSection:
    """``flight``: the flight outcome against the prediction (:mod:`etcheck.checks.verdict.flight`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the flight outcome against the prediction (etcheck.checks.verdict.flight); null for a mission without a flight record"
    }

    outcome: Literal["coiled", "straight"]
    reported: str
    prediction: Literal["pass", "fail", "incomplete", "outside"]
    agreement: str
    comparison: str
    not_modelled: tuple[str, ...]
