"""docs/results.schema.json (issue 12): the documented layout of a check's results.json.

The schema is made from the records of the results (etcheck/checks/sections*.py, etcheck/input/echo.py) by
etcheck.checks.results.schema: the committed file is that one (regenerate it with
``python -m etcheck.checks.results.schema`` after changing a record). Fresh results (draft and sign-off of the
SET mission, the static SET mission, the tensioned and orbit missions, an [uncertainty] study) validate as
written (strict JSON, no NaN); the schema rejects a bad verdict, a mistyped number and a stale schema version,
and its enums are the code's.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from pathlib import Path

import jsonschema
import pytest

from etcheck.checks import fidelity as fidelity_module
from etcheck.checks import plan as plan_module
from etcheck.checks.margins import margin as margins_module
from etcheck.checks.pipeline import check
from etcheck.checks.results.header import SCHEMA_VERSION
from etcheck.checks.results.schema import SCHEMA_PATH, results_schema, schema_text
from etcheck.checks.results.sections import CheckResults
from etcheck.input.mission import load_mission, mission_from_dict
from etcheck.jsonable import from_json, to_json
from etcheck.report import render

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "docs" / "results.schema.json").read_text(encoding="utf-8"))
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA, format_checker=jsonschema.Draft202012Validator.FORMAT_CHECKER)
MISSIONS = ROOT / "missions"


def test_the_committed_schema_is_the_one_the_records_make():
    """A record changed without regenerating the schema (or the schema edited by hand) fails here."""
    assert SCHEMA_PATH == ROOT / "docs" / "results.schema.json"
    assert SCHEMA_PATH.read_text(encoding="utf-8") == schema_text(), (
        "docs/results.schema.json is not the schema of the records: run python -m etcheck.checks.results.schema")


def test_every_object_of_the_schema_lists_its_keys():
    """Each record of the results is an object that allows no other keys and requires only its own."""

    def objects(node: dict):
        if "properties" in node:
            yield node
        for sub in list(node.get("properties", {}).values()) + node.get("oneOf", []) + node.get("anyOf", []):
            yield from objects(sub)
        for key in ("items", "additionalProperties"):
            if isinstance(node.get(key), dict):
                yield from objects(node[key])

    found = list(objects(results_schema()))
    assert len(found) >= 90  # the 89 locations of the records and the shapes of a branch
    assert all(node["additionalProperties"] is False and set(node["required"]) <= set(node["properties"])
               for node in found)


def test_results_are_their_records_round_trip(set_sign_off):
    """The JSON of a check read back into its records and written again is the same JSON, key order included."""
    again = to_json(from_json(CheckResults, set_sign_off))
    assert json.dumps(again) == json.dumps(set_sign_off)


def test_a_key_a_record_lacks_is_refused():
    with pytest.raises(KeyError, match="extra"):
        from_json(CheckResults, {"extra": 1})


def as_written(results: dict) -> dict:
    """The results.json the check writes (strict JSON: the writer refuses NaN and Infinity)."""

    def no_constant(name):
        raise AssertionError(f"results.json holds {name}, which is not JSON")

    return json.loads(render(results, ("json",))["json"], parse_constant=no_constant)


def assert_valid(results: dict) -> None:
    errors = sorted(VALIDATOR.iter_errors(as_written(results)), key=lambda e: list(e.absolute_path))
    assert not errors, "\n".join(f"{list(e.absolute_path)}: {e.message[:300]}" for e in errors)


def draft(path: Path) -> dict:
    return check(load_mission(path).with_fidelity("draft")).results


@pytest.fixture(scope="module")
def set_sign_off() -> dict:
    """One sign-off check of set.toml (several seconds): map, Campbell diagram, accuracy table."""
    return check(load_mission(MISSIONS / "set.toml").with_fidelity("auto")).results


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
    return [p for p in sorted(MISSIONS.glob("*.toml")) if load_mission(p).operation.end_tension.value > 0]


def test_tensioned_missions_validate():
    paths = tensioned_missions()
    if not paths:
        pytest.skip("no mission in missions/ has an end tension")
    for path in paths:
        results = draft(path)
        assert results["scene"]["tension_N"] > 0
        assert_valid(results)


def test_profiles_mission_validates():
    """A bare tether with a current and a gravity-gradient tension along it (rung 1v), both fidelities."""
    path = MISSIONS / "tape-tether.toml"
    mission = load_mission(path).with_fidelity("draft")
    results = check(mission).results
    assert results["profiles"] is not None and results["profiles"]["damping"]["map"]
    assert_valid(results)


def test_orbit_mission_validates():
    results = draft(MISSIONS / "proseds-orbit.toml")
    assert results["orbit"] is not None
    assert_valid(results)


def test_uncertainty_section_validates():
    """Draft checks with [uncertainty] tables: the spinning SET (pencils; its spin margin at a root, the load
    margin in closed form) and the static SET at a small margin (closed form, with its FORM/SORM cross-check)
    and at a large one (a bound)."""
    ei_field = {"bending_stiffness": {"distribution": "normal", "sigma": "15 %"},
                "axial_field": {"distribution": "lognormal", "sigma": "30 %"}}
    for name, current, table in (("set.toml", None, {"current": "±10 %", "length": "±1 %"}),
                                 ("set-static.toml", "20 A", ei_field), ("set-static.toml", "4 A", ei_field)):
        data = tomllib.loads((MISSIONS / name).read_text())
        data["check"]["fidelity"] = "draft"
        data["uncertainty"] = table
        if current:
            data["operation"]["current"] = current
        results = check(mission_from_dict(data)).results
        assert results["uncertainty"]["probabilities"]
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
        pytest.param(lambda r: r["straight_rod"]["limits"].update(extra=1), id="unknown nested key"),
        pytest.param(lambda r: r["straight_rod"]["critical_loads"][0].pop("beta"), id="missing nested key"),
        pytest.param(lambda r: r["linear"]["critical_spin"].update(rpm="fast"), id="mistyped nested value"),
        pytest.param(lambda r: r["scene"].update(length_m=None), id="null for a number"),
        pytest.param(lambda r: r.update(verdict="pass", margins=[dict(r["margins"][0], verdict="fail")]),
                     id="pass over a failed margin"),
        pytest.param(lambda r: r["model_validity"].update(within=False), id="pass outside the model's validity"),
        pytest.param(lambda r: r.update(verdict="outside"), id="outside within the model's validity"),
        pytest.param(lambda r: r["model_validity"]["checks"][0].update(within="yes"), id="mistyped validity"),
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
    assert set(margin["verdict"]["enum"]) == verdicts
    assert set(SCHEMA["properties"]["verdict"]["enum"]) == verdicts | {margins_module.OUTSIDE} == set(
        margins_module.Verdict)
    assert set(margin["model"]["enum"]) == set(plan_module.RUNG_NAMES.values()) | {plan_module.EXACT_MODEL,
                                                                                   plan_module.PROFILES_MODEL}
    assert set(margin["rung"]["enum"]) == set(plan_module.RUNG_NAMES)
    routes = {"", plan_module.SPECTRAL, plan_module.EXACT, plan_module.PROFILES}
    assert set(margin["route"]["enum"]) == routes == set(SCHEMA["properties"]["plan"]["properties"]["route"]["enum"])
    assert fidelity_module.fidelity_of(True, 0.0).left_out == fidelity_module.LEFT_OUT
    assert set(SCHEMA["properties"]["fidelity"]["properties"]["name"]["enum"]) == {
        fidelity_module.fidelity_of(True, 1e-8).name, fidelity_module.fidelity_of(False, 1e-8).name}
