"""docs/results.schema.json (issue 12): the documented layout of a check's results.json.

The schema and the TypedDicts of etcheck/checks/sections*.py describe the same
records (with the echo of the inputs in etcheck/input/echo.py): same keys, same
required keys, compatible value types, and every object of the schema has its type. Fresh results (draft and sign-off of the SET mission, the static SET mission, the
tensioned and orbit missions, an [uncertainty] study) validate as written (strict
JSON, no NaN); the schema rejects a bad verdict, a mistyped number and a stale
schema version, and its enums are the code's.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
import types
import typing
from pathlib import Path

import jsonschema
import pytest

from etcheck.checks import fidelity as fidelity_module
from etcheck.checks import margins as margins_module
from etcheck.checks import plan as plan_module
from etcheck.checks import sections as S
from etcheck.checks import sections_buckled as B
from etcheck.checks import sections_verdict as V
from etcheck.checks.pipeline import check
from etcheck.checks.results import SCHEMA_VERSION
from etcheck.input import echo as E
from etcheck.input.mission import load_mission, mission_from_dict
from etcheck.report import render

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "docs" / "results.schema.json").read_text(encoding="utf-8"))
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA, format_checker=jsonschema.Draft202012Validator.FORMAT_CHECKER)
MISSIONS = ROOT / "missions"


#: schema location (dotted keys, [] for the items of an array) -> the TypedDict of the object there
SECTIONS = {
    "": S.CheckResults,
    "mission": E.MissionEcho,
    "mission.tether": E.TetherEcho,
    "mission.operation": E.OperationEcho,
    "mission.operation.gravity_gradient": E.TensionProfile,
    "mission.operation.current_profile": E.CurrentProfileEcho,
    "mission.operation.current_profile.collection": E.CollectionEcho,
    "mission.check": E.CheckEcho,
    "mission.orbit": E.OrbitEcho,
    "mission.flight": E.FlightEcho,
    "scene": S.SceneSection,
    "scene.tension_profile": E.TensionProfile,
    "scaled": S.ScaledSection,
    "scales": S.ScalesSection,
    "plan": S.PlanSection,
    "fidelity": S.FidelitySection,
    "straight_rod": S.StraightRodSection,
    "straight_rod.critical_loads[]": S.StaticCriticalLoad,
    "straight_rod.first_mode": S.ModeShape,
    "straight_rod.chi_curve": S.ChiCurve,
    "straight_rod.natural_frequencies": S.NaturalFrequencies,
    "straight_rod.natural_frequencies.bending_weak[]": S.NaturalFrequency,
    "straight_rod.natural_frequencies.bending_stiff[]": S.NaturalFrequency,
    "straight_rod.natural_frequencies.torsion[]": S.NaturalFrequency,
    "straight_rod.limits": S.StaticLimits,
    "linear": S.LinearSection,
    "linear.operating_spectrum": S.OperatingSpectrum,
    "linear.operating_spectrum.modes[]": S.Mode,
    "linear.critical_load": S.CriticalLoad,
    "linear.critical_spin": S.CriticalSpin,
    "linear.spin_windows[]": S.SpinWindow,
    "linear.operating": S.OperatingPoint,
    "linear.campbell": S.Campbell,
    "linear.stability_map": S.StabilityMap,
    "linear.stability_map.stable_rows[]": S.StableRow,
    "linear.stability_map.static_points": S.StaticPoints,
    "profiles": S.ProfilesSection,
    "profiles.current": S.ProfileCurrent,
    "profiles.tension": S.ProfileTension,
    "profiles.damping": S.DampingSection,
    "profiles.damping.map[]": S.DampingPoint,
    "profiles.undamped": S.CriticalLoad,
    "profiles.uniform_tension_bound": S.CriticalLoad,
    "profiles.mode": S.ProfileMode,
    "accuracy[]": S.AccuracyRow,
    "postbuckling": B.PostbucklingSection,
    "postbuckling.diagram": B.BifurcationDiagram,
    "postbuckling.diagram.params": B.DiagramParameters,
    "postbuckling.diagram.branches[]": B.BranchRecord,
    "postbuckling.diagram.branches[].special[]": B.SpecialPoint,
    "postbuckling.diagram.lifted_off[]": B.LiftedOff,
    "postbuckling.operating": B.BuckledOperatingPoint,
    "postbuckling.operating.damping_sensitivity[]": B.DampingSensitivity,
    "postbuckling.operating.shape": B.Shape,
    "postbuckling.operating.least_damped": B.LeastDamped,
    "postbuckling.region": B.CoilRegion,
    "postbuckling.region.rows[]": B.RegionRow,
    "postbuckling.region.pitchfork_curve": B.RegionCurve,
    "postbuckling.region.secondary_curve": B.SecondaryCurve,
    "margins[]": S.MarginRecord,
    "margins[].alternatives[]": S.AlternativeMargin,
    "attachment": S.AttachmentSection,
    "attachment.alternatives[]": S.AttachmentAlternative,
    "resources": S.ResourcesSection,
    "resources.skipped[]": S.SkippedPart,
    "model_validity": V.ModelValidity,
    "model_validity.checks[]": V.ValidityCheck,
    "model_validity.lateral": V.LateralLoad,
    "assumptions": V.AssumptionsSection,
    "assumptions.rows[]": V.AssumptionRecord,
    "design_limits": V.DesignLimitsSection,
    "design_limits.limits[]": V.DesignLimit,
    "flight": V.FlightSection,
    "orbit": S.OrbitSection,
    "orbit.sampling": S.OrbitSampling,
    "orbit.worst": S.OrbitWorst,
    "orbit.percentiles": S.OrbitPercentiles,
    "orbit.histogram": S.OrbitHistogram,
    "orbit.margin": S.OrbitMargin,
    "orbit.first_orbit": S.OrbitSeries,
    "orbit.series": S.OrbitSeries,
    "uncertainty": S.UncertaintySection,
    "uncertainty.inputs": E.UncertaintyInputs,
    "uncertainty.inputs.inputs[]": E.DistributionRecord,
    "uncertainty.margins[]": S.MarginSensitivityRecord,
    "uncertainty.margins[].elasticities[]": S.ElasticityRecord,
    "uncertainty.margins[].swings[]": S.SwingRecord,
    "uncertainty.probabilities[]": S.ProbabilityRecord,
    "uncertainty.probabilities[].cross_check": S.CrossCheckRecord,
}


def branch(node: dict, key: str) -> dict:
    """The branch of a nullable node (``oneOf``/``anyOf`` with null) that holds ``key``."""
    return next((b for b in node.get("oneOf", []) + node.get("anyOf", []) if key in b), node)


def locate(path: str) -> dict:
    node = SCHEMA
    for part in filter(None, path.split(".")):
        node = branch(node, "properties")["properties"][part.removesuffix("[]")]
        if part.endswith("[]"):
            node = branch(node, "items")["items"]
    return branch(node, "properties")


def schema_objects(node: dict, path: str = "") -> set[str]:
    """Locations of every object with properties in the schema."""
    found = {path} if "properties" in node else set()
    for key, sub in node.get("properties", {}).items():
        found |= schema_objects(sub, f"{path}.{key}" if path else key)
    for branch in node.get("oneOf", []) + node.get("anyOf", []):
        found |= schema_objects(branch, path)
    if "items" in node:
        found |= schema_objects(node["items"], path + "[]")
    return found


def annotation_types(annotation) -> set[str]:
    """JSON types a value of this annotation may take (a float may be written as an integer)."""
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        return set().union(*(annotation_types(a) for a in typing.get_args(annotation)))
    if origin is list:
        return {"array"}
    if origin is dict or typing.is_typeddict(annotation):
        return {"object"}
    return {float: {"number", "integer"}, int: {"integer"}, bool: {"boolean"}, str: {"string"},
            type(None): {"null"}}[annotation]


def schema_types(node: dict) -> set[str]:
    """JSON types a schema node admits (type, enum or const, and the branches of oneOf/anyOf)."""
    if "type" in node:
        return {node["type"]} if isinstance(node["type"], str) else set(node["type"])
    values = node.get("enum", [node["const"]] if "const" in node else None)
    if values is not None:
        names = {str: "string", int: "integer", float: "number", bool: "boolean", type(None): "null"}
        return {names[type(v)] for v in values}
    return set().union(*(schema_types(b) for b in node.get("oneOf", []) + node.get("anyOf", [])))


def test_every_object_of_the_schema_has_its_type():
    assert schema_objects(SCHEMA) == set(SECTIONS)


@pytest.mark.parametrize("path", list(SECTIONS), ids=lambda p: p or "results")
def test_type_and_schema_list_the_same_keys(path):
    node, typed = locate(path), SECTIONS[path]
    hints = typing.get_type_hints(typed)
    assert set(node["properties"]) == set(hints)
    assert set(node["required"]) == set(typed.__required_keys__)
    assert node["additionalProperties"] is False
    for key, annotation in hints.items():
        assert schema_types(node["properties"][key]) <= annotation_types(annotation), key


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
    return [p for p in sorted(MISSIONS.glob("*.toml")) if load_mission(p).end_tension.value > 0]


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
