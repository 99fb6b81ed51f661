"""Mission files (etcheck/mission.py): the shipped missions parse, and every bad
input is a MissionError naming the file and the field."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import astropy.units as u
import pytest
from helpers import set_like

from etcheck import Mission, MissionError, load_mission, mission_from_dict
from etcheck.scaling import scene

MISSIONS = Path(__file__).resolve().parents[2] / "missions"

# A valid mission as raw TOML literals: {table: {key: literal}}.
BASE: dict[str, dict[str, str]] = {
    "mission": {"name": '"Test tether"', "description": '"unit-test mission"'},
    "tether": {
        "length": '"100 m"',
        "bending_stiffness": '["38 N m2", "21 N m2"]',
        "poisson_ratio": "0.3",
        "mass_per_length": '"0.1 kg/m"',
        "rotary_inertia_ratio": "0.001",
    },
    "operation": {"current": '"1 A"', "axial_field": '"70 uT"'},
    "check": {"required_margin": "2"},
}


def render(data: dict[str, dict[str, str]]) -> str:
    lines = []
    for table, fields in data.items():
        lines.append(f"[{table}]")
        lines.extend(f"{key} = {value}" for key, value in fields.items())
        lines.append("")
    return "\n".join(lines)


def variant(changes: dict[tuple[str, str], str | None]) -> dict[str, dict[str, str]]:
    """BASE with (table, key) -> literal set, or removed where the literal is None."""
    data = copy.deepcopy(BASE)
    for (table, key), literal in changes.items():
        if literal is None:
            data.get(table, {}).pop(key, None)
        else:
            data.setdefault(table, {})[key] = literal
    return data


def write_mission(tmp_path: Path, changes: dict | None = None, name: str = "mission.toml") -> Path:
    path = tmp_path / name
    path.write_text(render(variant(changes or {})), encoding="utf-8")
    return path


# (id, changes, field the message must name, optional extra text it must contain)
BAD_CASES: list[tuple[str, dict, str, str | None]] = [
    # missing required fields
    ("missing-name", {("mission", "name"): None}, "mission.name", None),
    ("missing-length", {("tether", "length"): None}, "tether.length", None),
    ("missing-stiffness", {("tether", "bending_stiffness"): None}, "tether.bending_stiffness", None),
    ("missing-mass", {("tether", "mass_per_length"): None}, "tether.mass_per_length", None),
    ("missing-current", {("operation", "current"): None}, "operation.current", None),
    ("missing-field", {("operation", "axial_field"): None}, "operation.axial_field", None),
    ("missing-torsion", {("tether", "poisson_ratio"): None}, "poisson_ratio", "torsional_stiffness"),
    ("missing-P", {("tether", "rotary_inertia_ratio"): None}, "rotary_inertia_ratio", "cross_section_area"),
    (
        "section-without-E",
        {("tether", "rotary_inertia_ratio"): None, ("tether", "cross_section_area"): '"1 mm2"'},
        "tether.youngs_modulus",
        None,
    ),
    (
        "section-without-A",
        {("tether", "rotary_inertia_ratio"): None, ("tether", "youngs_modulus"): '"70 GPa"'},
        "tether.cross_section_area",
        None,
    ),
    # unknown fields and tables
    ("typo-lenght", {("tether", "length"): None, ("tether", "lenght"): '"100 m"'}, "tether.lenght", "length"),
    ("typo-curent", {("operation", "curent"): '"1 A"'}, "operation.curent", "current"),
    ("unknown-table", {("tehter", "length"): '"100 m"'}, "tehter", "tether"),
    ("unknown-table-2", {("extras", "x"): "1"}, "extras", None),
    # how the ends are held
    ("ends-unknown", {("tether", "end_conditions"): '"hinged"'}, "tether.end_conditions", "pinned"),
    ("ends-three", {("tether", "end_conditions"): '["welded", "pinned", "welded"]'}, "tether.end_conditions",
     "[lower, upper]"),
    ("ends-number", {("tether", "end_conditions"): "1"}, "tether.end_conditions", "unknown attachment"),
    ("ends-two-swivels", {("tether", "end_conditions"): '["swivel", "swivel"]'}, "tether.end_conditions",
     "twist"),
    ("ends-typo", {("tether", "end_condition"): '"pinned"'}, "tether.end_condition", "end_conditions"),
    # wrong dimension
    ("length-in-seconds", {("tether", "length"): '"100 s"'}, "tether.length", None),
    ("field-in-metres", {("operation", "axial_field"): '"70 m"'}, "operation.axial_field", None),
    ("current-in-volts", {("operation", "current"): '"1 V"'}, "operation.current", None),
    ("stiffness-in-newtons", {("tether", "bending_stiffness"): '"38 N"'}, "tether.bending_stiffness", None),
    ("mass-in-kg", {("tether", "mass_per_length"): '"0.1 kg"'}, "tether.mass_per_length", None),
    ("spin-in-metres", {("operation", "spin_rate"): '"2 m"'}, "operation.spin_rate", None),
    ("tension-in-kg", {("operation", "end_tension"): '"5 kg"'}, "operation.end_tension", None),
    ("damping-in-metres", {("tether", "damping_time"): '"1 m"'}, "tether.damping_time", None),
    (
        "gj-in-newtons",
        {("tether", "poisson_ratio"): None, ("tether", "torsional_stiffness"): '"20 N"'},
        "tether.torsional_stiffness",
        None,
    ),
    # bare numbers
    ("bare-length", {("tether", "length"): "100"}, "tether.length", "unit"),
    ("bare-length-string", {("tether", "length"): '"100"'}, "tether.length", "unit"),
    ("bare-current", {("operation", "current"): "1.0"}, "operation.current", "unit"),
    ("bare-stiffness", {("tether", "bending_stiffness"): "[38, 21]"}, "tether.bending_stiffness", "unit"),
    ("bare-field-range", {("operation", "axial_field"): '["10 uT", 70]'}, "operation.axial_field", "unit"),
    # non-positive
    ("zero-length", {("tether", "length"): '"0 m"'}, "tether.length", "positive"),
    ("negative-length", {("tether", "length"): '"-100 m"'}, "tether.length", "positive"),
    ("zero-stiffness", {("tether", "bending_stiffness"): '["0 N m2", "0 N m2"]'}, "tether.bending_stiffness", None),
    ("negative-EI2", {("tether", "bending_stiffness"): '["38 N m2", "-21 N m2"]'}, "tether.bending_stiffness", None),
    ("negative-isotropic", {("tether", "bending_stiffness"): '"-38 N m2"'}, "tether.bending_stiffness", None),
    ("zero-mass", {("tether", "mass_per_length"): '"0 kg/m"'}, "tether.mass_per_length", None),
    ("negative-mass", {("tether", "mass_per_length"): '"-0.1 kg/m"'}, "tether.mass_per_length", None),
    (
        "zero-gj",
        {("tether", "poisson_ratio"): None, ("tether", "torsional_stiffness"): '"0 N m2"'},
        "tether.torsional_stiffness",
        None,
    ),
    (
        "zero-E",
        {
            ("tether", "rotary_inertia_ratio"): None,
            ("tether", "youngs_modulus"): '"0 GPa"',
            ("tether", "cross_section_area"): '"1 mm2"',
        },
        "tether.youngs_modulus",
        None,
    ),
    (
        "negative-area",
        {
            ("tether", "rotary_inertia_ratio"): None,
            ("tether", "youngs_modulus"): '"70 GPa"',
            ("tether", "cross_section_area"): '"-1 mm2"',
        },
        "tether.cross_section_area",
        None,
    ),
    ("negative-P", {("tether", "rotary_inertia_ratio"): "-0.001"}, "tether.rotary_inertia_ratio", None),
    ("negative-damping", {("tether", "damping_time"): '"-1 s"'}, "tether.damping_time", None),
    # NaN and inf
    ("toml-nan-length", {("tether", "length"): "nan"}, "tether.length", None),
    ("toml-inf-length", {("tether", "length"): "inf"}, "tether.length", None),
    ("string-nan-length", {("tether", "length"): '"nan m"'}, "tether.length", None),
    ("string-inf-length", {("tether", "length"): '"inf m"'}, "tether.length", None),
    ("string-minus-inf-mass", {("tether", "mass_per_length"): '"-inf kg/m"'}, "tether.mass_per_length", None),
    ("overflow-length", {("tether", "length"): '"1e999 m"'}, "tether.length", None),
    ("nan-EI2", {("tether", "bending_stiffness"): '["38 N m2", "nan N m2"]'}, "tether.bending_stiffness", None),
    ("inf-EI1", {("tether", "bending_stiffness"): '["inf N m2", "21 N m2"]'}, "tether.bending_stiffness", None),
    ("nan-current", {("operation", "current"): '"nan A"'}, "operation.current", None),
    ("inf-current-range", {("operation", "current"): '["1 A", "inf A"]'}, "operation.current", None),
    ("nan-field", {("operation", "axial_field"): '"nan uT"'}, "operation.axial_field", None),
    ("toml-nan-field", {("operation", "axial_field"): "nan"}, "operation.axial_field", None),
    ("nan-spin", {("operation", "spin_rate"): '"nan rpm"'}, "operation.spin_rate", None),
    ("inf-tension", {("operation", "end_tension"): '"inf N"'}, "operation.end_tension", None),
    ("nan-damping", {("tether", "damping_time"): '"nan s"'}, "tether.damping_time", None),
    ("nan-poisson", {("tether", "poisson_ratio"): "nan"}, "tether.poisson_ratio", None),
    ("inf-P", {("tether", "rotary_inertia_ratio"): "inf"}, "tether.rotary_inertia_ratio", None),
    ("nan-P", {("tether", "rotary_inertia_ratio"): "nan"}, "tether.rotary_inertia_ratio", None),
    ("nan-margin", {("check", "required_margin"): "nan"}, "check.required_margin", None),
    ("inf-margin", {("check", "required_margin"): "inf"}, "check.required_margin", None),
    # anisotropy the wrong way round
    ("EI2-gt-EI1", {("tether", "bending_stiffness"): '["21 N m2", "38 N m2"]'}, "tether.bending_stiffness", "swap"),
    (
        "three-stiffnesses",
        {("tether", "bending_stiffness"): '["38 N m2", "21 N m2", "1 N m2"]'},
        "tether.bending_stiffness",
        None,
    ),
    # ranges
    ("current-min-gt-max", {("operation", "current"): '["2 A", "1 A"]'}, "operation.current", "min"),
    ("field-min-gt-max", {("operation", "axial_field"): '["70 uT", "10 uT"]'}, "operation.axial_field", "min"),
    ("range-three-values", {("operation", "current"): '["1 A", "2 A", "3 A"]'}, "operation.current", None),
    # check options
    ("wrong-fidelity", {("check", "fidelity"): '"best"'}, "check.fidelity", "auto"),
    ("fidelity-number", {("check", "fidelity"): "1"}, "check.fidelity", None),
    ("margin-below-one", {("check", "required_margin"): "0.5"}, "check.required_margin", None),
    ("margin-as-string", {("check", "required_margin"): '"2"'}, "check.required_margin", None),
    # Poisson's ratio outside (-1, 0.5]
    ("poisson-0.6", {("tether", "poisson_ratio"): "0.6"}, "tether.poisson_ratio", None),
    ("poisson-0.5000001", {("tether", "poisson_ratio"): "0.5000001"}, "tether.poisson_ratio", None),
    ("poisson-minus-1", {("tether", "poisson_ratio"): "-1"}, "tether.poisson_ratio", None),
    ("poisson-minus-2", {("tether", "poisson_ratio"): "-2.0"}, "tether.poisson_ratio", None),
    ("poisson-with-unit", {("tether", "poisson_ratio"): '"0.3 m"'}, "tether.poisson_ratio", None),
    # exclusive alternatives
    (
        "P-and-section",
        {("tether", "youngs_modulus"): '"70 GPa"', ("tether", "cross_section_area"): '"1 mm2"'},
        "rotary_inertia_ratio",
        "cross_section_area",
    ),
    ("nu-and-GJ", {("tether", "torsional_stiffness"): '"20 N m2"'}, "poisson_ratio", "torsional_stiffness"),
    # text fields
    ("empty-name", {("mission", "name"): '"  "'}, "mission.name", None),
    ("name-not-text", {("mission", "name"): "3"}, "mission.name", None),
]


def _assert_names(exc: MissionError, source: str, field: str, extra: str | None) -> None:
    text = str(exc)
    assert source in text, text
    assert field in text, text
    assert exc.field is not None and field in exc.field, (exc.field, text)
    assert exc.source == source
    if extra is not None:
        assert extra in text, text
    assert "Traceback" not in text
    assert len(text.splitlines()) <= 3


# --- the shipped missions -----------------------------------------------------------


@pytest.mark.parametrize("name", ["set.toml", "set-static.toml", "pmg.toml", "proseds.toml"])
def test_shipped_missions_parse(name):
    m = load_mission(MISSIONS / name)
    assert isinstance(m, Mission)
    assert m.provenance.name
    assert m.provenance.file == str(MISSIONS / name)
    assert len(m.provenance.sha256) == 64
    EI1, EI2 = m.tether.bending_stiffness
    assert EI1 >= EI2 > 0 * u.N * u.m**2
    assert m.tether.length > 0 * u.m
    assert m.tether.mass_per_length > 0 * u.kg / u.m
    assert 0 <= m.tether.rotary_inertia_ratio < 1


def test_set_mission_values():
    m = load_mission(MISSIONS / "set.toml")
    assert m.provenance.name == "SET"
    assert m.tether.length.to_value(u.m) == pytest.approx(100.0)
    assert [q.to_value(u.N * u.m**2) for q in m.tether.bending_stiffness] == pytest.approx([38.0, 21.0])
    assert m.tether.rotary_inertia_ratio == pytest.approx(0.001)
    assert m.operation.worst_current.to_value(u.A) == pytest.approx(1.0)
    assert scene(m).field.axial == pytest.approx(70e-6)
    assert scene(m).load == pytest.approx(70e-6)
    # spin: the paper's omega = 0.25 with the assumed mass per length (commented in the file)
    assert m.operation.spin_rate.to_value(u.cycle / u.min) == pytest.approx(0.1041)
    assert m.operation.end_tension.to_value(u.N) == 0
    # Gamma = 2 GJ / (EI1 + EI2) = 1 / (1 + nu) = 1/1.3
    GJ = m.tether.torsional_stiffness.to_value(u.N * u.m**2)
    assert 2 * GJ / (38.0 + 21.0) == pytest.approx(1 / 1.3, rel=1e-14)
    assert m.check.required_margin == 2
    assert m.check.fidelity == "auto"


def test_rotary_inertia_from_section():
    m = load_mission(MISSIONS / "pmg.toml")
    EI1 = m.tether.bending_stiffness[0].to_value(u.N * u.m**2)
    E = m.tether.youngs_modulus.to_value(u.Pa)
    A = m.tether.cross_section_area.to_value(u.m**2)
    L = m.tether.length.to_value(u.m)
    # P = I1 / (A L^2) with I1 = EI1 / E
    assert m.tether.rotary_inertia_ratio == pytest.approx(EI1 / E / (A * L**2), rel=1e-12)
    assert any("rotary inertia" in note for note in m.provenance.notes)


def test_ranges_worst_case():
    m = load_mission(MISSIONS / "proseds.toml")
    assert m.operation.current[0] < m.operation.current[1]
    assert m.operation.worst_current.to_value(u.A) == pytest.approx(1.5)
    assert scene(m).field.axial == pytest.approx(40e-6)
    assert any("worst case" in note for note in m.provenance.notes)


def test_isotropic_single_stiffness(tmp_path):
    m = load_mission(write_mission(tmp_path, {("tether", "bending_stiffness"): '"10 N m2"'}))
    assert m.tether.bending_stiffness[0] == m.tether.bending_stiffness[1]
    assert m.tether.bending_stiffness[0].to_value(u.N * u.m**2) == pytest.approx(10.0)


def test_negative_range_uses_magnitude(tmp_path):
    m = load_mission(write_mission(tmp_path, {("operation", "current"): '["-3 A", "1 A"]'}))
    assert m.operation.worst_current.to_value(u.A) == pytest.approx(3.0)


@pytest.mark.parametrize("nu", ["0.5", "-0.99", "0", "0.3"])
def test_poisson_ratio_edges_accepted(tmp_path, nu):
    m = load_mission(write_mission(tmp_path, {("tether", "poisson_ratio"): nu}))
    assert m.tether.poisson_ratio == pytest.approx(float(nu))
    GJ = m.tether.torsional_stiffness.to_value(u.N * u.m**2)
    assert GJ == pytest.approx((38 + 21) / (2 * (1 + float(nu))), rel=1e-14)


def test_torsional_stiffness_instead_of_poisson(tmp_path):
    m = load_mission(
        write_mission(tmp_path, {("tether", "poisson_ratio"): None, ("tether", "torsional_stiffness"): '"20 N m2"'})
    )
    assert m.tether.torsional_stiffness.to_value(u.N * u.m**2) == pytest.approx(20.0)
    assert m.tether.poisson_ratio is None


def test_optional_fields(tmp_path):
    m = load_mission(
        write_mission(
            tmp_path,
            {
                ("tether", "damping_time"): '"20 ms"',
                ("operation", "spin_rate"): '"2 rpm"',
                ("operation", "end_tension"): '"0.5 kN"',
                ("check", "fidelity"): '"analytic"',
            },
        )
    )
    assert m.tether.damping_time.to_value(u.s) == pytest.approx(0.02)
    assert m.operation.spin_rate.to_value(u.rad / u.s) == pytest.approx(2 * 2 * math.pi / 60)
    assert m.operation.end_tension.to_value(u.N) == pytest.approx(500.0)
    assert m.check.fidelity == "analytic"


def test_defaults(tmp_path):
    m = load_mission(write_mission(tmp_path, {("check", "required_margin"): None}))
    assert m.check.required_margin == 2
    assert m.check.fidelity == "auto"
    assert m.operation.spin_rate.to_value(u.rad / u.s) == 0
    assert m.operation.end_tension.to_value(u.N) == 0


# --- bad input --------------------------------------------------------------------------


@pytest.mark.parametrize("case_id, changes, field, extra", BAD_CASES, ids=[c[0] for c in BAD_CASES])
def test_bad_input_names_file_and_field(tmp_path, case_id, changes, field, extra):
    path = write_mission(tmp_path, changes)
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    _assert_names(exc.value, str(path), field, extra)


def test_table_given_as_value(tmp_path):
    path = tmp_path / "m.toml"
    data = variant({})
    del data["tether"]
    path.write_text('tether = "100 m"\n' + render(data))
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert str(path) in str(exc.value) and "tether" in str(exc.value)


def test_missing_whole_table(tmp_path):
    data = variant({})
    del data["operation"]
    path = tmp_path / "m.toml"
    path.write_text(render(data))
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert "operation." in str(exc.value) and str(path) in str(exc.value)


def test_typo_suggests_length(tmp_path):
    path = write_mission(tmp_path, {("tether", "length"): None, ("tether", "lenght"): '"100 m"'})
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    text = str(exc.value)
    assert "lenght" in text
    assert "'length'" in text or '"length"' in text or "`length`" in text


@pytest.mark.parametrize(
    "text, line",
    [
        ('[mission]\nname = "X"\n[tether]\nlength = "100 m\n', 4),
        ('[mission]\nname = "X"\n\n\n[tether\nlength = "100 m"\n', 5),
        ('[mission]\nname = "X"\nname = "Y"\n', 3),
        ('[mission]\nname = "X"\n[tether]\nlength = \n', 4),
    ],
)
def test_malformed_toml_gives_line(tmp_path, text, line):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    msg = str(exc.value)
    assert str(path) in msg
    assert f"line {line}" in msg
    assert "TOML" in msg


def test_missing_file(tmp_path):
    path = tmp_path / "nope.toml"
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert str(path) in str(exc.value) and "not found" in str(exc.value)


def test_directory(tmp_path):
    with pytest.raises(MissionError) as exc:
        load_mission(tmp_path)
    assert str(tmp_path) in str(exc.value) and "directory" in str(exc.value)


def test_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes(render(variant({("mission", "description"): '"Zürich"'})).encode("latin-1"))
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert str(path) in str(exc.value) and "UTF-8" in str(exc.value)


def test_binary_file(tmp_path):
    path = tmp_path / "binary.toml"
    path.write_bytes(bytes(range(256)))
    with pytest.raises(MissionError):
        load_mission(path)


def test_empty_file(tmp_path):
    path = tmp_path / "empty.toml"
    path.write_text("")
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert str(path) in str(exc.value)


# --- Python API: dicts with astropy and pint quantities ------------------------------


def test_astropy_quantities_accepted():
    m = mission_from_dict(
        set_like(length=0.1 * u.km, axial_field=70 * u.uT, bending_stiffness=[38 * u.N * u.m**2, "21 N m2"])
    )
    assert m.tether.length.to_value(u.m) == pytest.approx(100.0)
    assert scene(m).field.axial == pytest.approx(70e-6)


def test_pint_quantities_accepted():
    pint = pytest.importorskip("pint")
    ureg = pint.UnitRegistry()
    m = mission_from_dict(
        set_like(
            length=ureg("100 m"),
            mass_per_length=ureg("100 g/m"),
            bending_stiffness=[ureg("38 N*m**2"), ureg("21 N*m**2")],
            current=ureg("1000 mA"),
            axial_field=ureg("70 microtesla"),
            spin_rate=ureg("2 rpm"),
        )
    )
    assert m.tether.length.unit == u.m and m.tether.length.value == pytest.approx(100.0)
    assert m.tether.mass_per_length.to_value(u.kg / u.m) == pytest.approx(0.1)
    assert m.operation.worst_current.to_value(u.A) == pytest.approx(1.0)
    assert scene(m).field.axial == pytest.approx(70e-6)
    assert m.operation.spin_rate.to_value(u.rad / u.s) == pytest.approx(0.20944, rel=1e-5)
    m2 = mission_from_dict(set_like(spin_rate=ureg("1 Hz")))
    assert m2.operation.spin_rate.to_value(u.rad / u.s) == pytest.approx(2 * math.pi, rel=1e-14)


@pytest.mark.parametrize(
    "key, value, field",
    [
        ("length", "3 s", "tether.length"),
        ("current", "1 V", "operation.current"),
        ("axial_field", "1 m", "operation.axial_field"),
        ("spin_rate", "2 m", "operation.spin_rate"),
        ("bending_stiffness", "38 N*m", "tether.bending_stiffness"),
    ],
)
def test_pint_wrong_dimension_refused(key, value, field):
    pint = pytest.importorskip("pint")
    ureg = pint.UnitRegistry()
    with pytest.raises(MissionError) as exc:
        mission_from_dict(set_like(**{key: ureg(value)}), source="api-test")
    _assert_names(exc.value, "api-test", field, None)


def test_api_bare_number_refused():
    with pytest.raises(MissionError) as exc:
        mission_from_dict(set_like(length=100.0))
    assert "tether.length" in str(exc.value)


def test_api_nan_quantity_refused():
    with pytest.raises(MissionError) as exc:
        mission_from_dict(set_like(length=float("nan") * u.m))
    assert "tether.length" in str(exc.value)


def test_error_message_has_a_fix(tmp_path):
    path = write_mission(tmp_path, {("tether", "length"): None})
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert exc.value.fix  # says what would make it right
    assert exc.value.fix in str(exc.value)


@pytest.mark.parametrize("literal, ends", [(None, ("welded", "welded")), ('"pinned"', ("pinned", "pinned")),
                                           ('["welded", "pinned"]', ("welded", "pinned")),
                                           ('["swivel", "welded"]', ("swivel", "welded"))])
def test_end_conditions_lower_end_first(tmp_path, literal, ends):
    """[tether] end_conditions: one attachment for both ends, or [lower, upper]; welded by default; echoed as read,
    carried to the dimensionless problem (s = 0 is the lower end) and noted when not the paper's."""
    from etcheck.scaling import scale, scene

    m = load_mission(write_mission(tmp_path, {("tether", "end_conditions"): literal}))
    assert m.tether.end_conditions == ends
    assert m.echo().tether.end_conditions == tuple(ends)
    assert scale(scene(m)).params.ends == ends
    assert any("end_conditions" in n for n in m.provenance.notes) == (ends != ("welded", "welded"))
