"""docs/results.schema.json (issue 12): the documented layout of a check's results.json.

Fresh results (draft and sign-off of the SET mission, the static SET mission, the
tensioned and orbit missions, an [uncertainty] study) validate as written (strict
JSON, no NaN); the schema rejects a bad verdict, a mistyped number and a stale
schema version, and its enums are the code's.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
from pathlib import Path

import jsonschema
import pytest

from etcheck.checks import fidelity as fidelity_module
from etcheck.checks import margins as margins_module
from etcheck.checks import plan as plan_module
from etcheck.checks.pipeline import check
from etcheck.checks.results import SCHEMA_VERSION
from etcheck.input.mission import load_mission
from etcheck.report import render

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "docs" / "results.schema.json").read_text(encoding="utf-8"))
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA, format_checker=jsonschema.Draft202012Validator.FORMAT_CHECKER)
MISSIONS = ROOT / "missions"


def as_written(results: dict) -> dict:
    """The results.json the check writes (strict JSON: the writer refuses NaN and Infinity)."""

    def no_constant(name):
        raise AssertionError(f"results.json holds {name}, which is not JSON")

    return json.loads(render(results, ("json",))["json"], parse_constant=no_constant)


def assert_valid(results: dict) -> None:
    errors = sorted(VALIDATOR.iter_errors(as_written(results)), key=lambda e: list(e.absolute_path))
    assert not errors, "\n".join(f"{list(e.absolute_path)}: {e.message[:300]}" for e in errors)


def draft(path: Path) -> dict:
    return check(dataclasses.replace(load_mission(path), fidelity="draft")).results


@pytest.fixture(scope="module")
def set_sign_off() -> dict:
    """One sign-off check of set.toml (several seconds): map, Campbell diagram, accuracy table."""
    return check(dataclasses.replace(load_mission(MISSIONS / "set.toml"), fidelity="auto")).results


def test_the_schema_is_a_valid_draft_2020_12_schema():
    assert SCHEMA["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    assert SCHEMA["properties"]["schema_version"]["const"] == SCHEMA_VERSION


def test_set_sign_off_validates(set_sign_off):
    assert set_sign_off["fidelity"]["name"] == "sign-off"
    assert set_sign_off["linear"]["stability_map"] is not None and set_sign_off["accuracy"]
    assert_valid(set_sign_off)


def test_set_draft_validates():
    results = draft(MISSIONS / "set.toml")
    assert results["fidelity"]["name"] == "draft" and results["accuracy"] is None
    assert_valid(results)


def test_static_mission_validates_in_both_fidelities():
    path = MISSIONS / "set-static.toml"
    signed = check(path).results
    assert signed["plan"]["rung"] == 0 and signed["linear"] is None
    assert_valid(signed)
    assert_valid(draft(path))


def tensioned_missions() -> list[Path]:
    return [p for p in sorted(MISSIONS.glob("*.toml")) if load_mission(p).end_tension.value > 0]


def test_tensioned_missions_validate():
    paths = tensioned_missions()
    if not paths:
        pytest.skip("no mission in missions/ has an end tension")
    for path in paths:
        results = draft(path)
        assert results["scene"]["tension_N"] > 0
        assert_valid(results)


def test_orbit_mission_validates():
    results = draft(MISSIONS / "proseds-orbit.toml")
    assert results["orbit"] is not None
    assert_valid(results)


def test_uncertainty_section_validates():
    from etcheck.studies.uncertainty import attach

    mission = dataclasses.replace(load_mission(MISSIONS / "set-tolerances.toml"), fidelity="draft")
    results = attach(check(mission).results, mission, probabilities=False)  # sensitivities only: fast
    assert "uncertainty" in results
    assert_valid(results)


@pytest.mark.parametrize(
    "spoil",
    [
        pytest.param(lambda r: r.update(verdict="ok"), id="bad verdict"),
        pytest.param(lambda r: r["margins"][0].update(verdict="maybe"), id="bad margin verdict"),
        pytest.param(lambda r: r["margins"][0].update(value="NaN"), id="NaN as a string"),
        pytest.param(lambda r: r["margins"][0].update(value=-1.0), id="negative margin"),
        pytest.param(lambda r: r["plan"].update(rung="1"), id="rung as a string"),
        pytest.param(lambda r: r["fidelity"].update(name="quick"), id="bad fidelity"),
        pytest.param(lambda r: r["linear"]["critical_load"].update(kind="buckling"), id="bad critical kind"),
        pytest.param(lambda r: r.update(schema_version=1), id="stale schema version"),
        pytest.param(lambda r: r.pop("margins"), id="missing margins"),
        pytest.param(lambda r: r.update(extra=1), id="unknown top-level key"),
        pytest.param(lambda r: r.update(verdict="pass", margins=[dict(r["margins"][0], verdict="fail")]),
                     id="pass over a failed margin"),
    ],
)
def test_the_schema_rejects_spoilt_results(spoil):
    results = as_written(draft(MISSIONS / "set.toml"))
    assert VALIDATOR.is_valid(results)
    spoilt = copy.deepcopy(results)
    spoil(spoilt)
    assert not VALIDATOR.is_valid(spoilt)


def test_nan_never_reaches_results_json():
    """JSON has no NaN: the writer refuses one (the schema documents numbers as finite or null)."""
    results = draft(MISSIONS / "set.toml")
    results["margins"][0]["value"] = math.nan
    with pytest.raises(ValueError):
        render(results, ("json",))


def test_enums_are_the_codes():
    margin = SCHEMA["properties"]["margins"]["items"]["properties"]
    verdicts = {margins_module.PASS, margins_module.FAIL, margins_module.INCOMPLETE}
    assert set(SCHEMA["properties"]["verdict"]["enum"]) == verdicts == set(margin["verdict"]["enum"])
    assert set(margin["model"]["enum"]) == set(plan_module.RUNG_NAMES.values()) | {plan_module.EXACT_MODEL}
    assert set(margin["rung"]["enum"]) == set(plan_module.RUNG_NAMES)
    routes = {"", plan_module.SPECTRAL, plan_module.EXACT}
    assert set(margin["route"]["enum"]) == routes == set(SCHEMA["properties"]["plan"]["properties"]["route"]["enum"])
    assert fidelity_module.fidelity_of("draft", 0.0).left_out == fidelity_module.LEFT_OUT
    assert set(SCHEMA["properties"]["fidelity"]["properties"]["name"]["enum"]) == {
        fidelity_module.fidelity_of("draft", 1e-8).name, fidelity_module.fidelity_of("auto", 1e-8).name}
