"""Mission files (TOML) -> :class:`Mission`: schema, units and clear errors.

A mission is given in physical units; every quantity is a string parsed by
astropy.units (``"100 m"``, ``"38 N m2"``, ``"70 uT"``, ``"2 rpm"``). The
schema is documented in the README. Everything wrong with a file is reported
as a :class:`~etcheck.errors.MissionError` naming the file, the field and the
fix; nothing is guessed silently.
"""

from __future__ import annotations

import difflib
import hashlib
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import astropy.units as u

from etcheck.errors import MissionError
from etcheck.input.gravity_gradient import GravityGradient, parse_gravity_gradient
from etcheck.input.orbit_field import check_one_field_source, orbit_axial_field, orbit_echo, orbit_notes
from etcheck.input.sweep_axes import AXES, Axis, parse_table
from etcheck.input.uncertainty import INPUTS as UNCERTAIN_INPUTS
from etcheck.input.uncertainty import Uncertainty, parse_uncertainty
from etcheck.input.units import QuantityProblem, to_quantity
from etcheck.rod.parameters import F_CLAMPED

if TYPE_CHECKING:  # etcheck.orbit (IGRF, SGP4) is imported only for missions with an [orbit] table
    from etcheck.orbit.envelope import AxialFieldEnvelope
    from etcheck.orbit.spec import OrbitSpec

#: Dimensionless damping gamma assumed when a mission gives no damping_time:
#: the paper's estimate for a real tether in working conditions (Sec. VII B).
DEFAULT_GAMMA = 0.04375

FIDELITIES = ("auto", "draft", "analytic", "linear")

# table -> field -> (kind or "number"/"text"/..., required)
SCHEMA: dict[str, dict[str, tuple[str, bool]]] = {
    "mission": {"name": ("text", True), "description": ("text", False), "source": ("text", False)},
    "tether": {
        "length": ("length", True),
        "bending_stiffness": ("stiffness_pair", True),
        "poisson_ratio": ("number", False),
        "torsional_stiffness": ("torsional_stiffness", False),
        "mass_per_length": ("mass_per_length", True),
        "rotary_inertia_ratio": ("number", False),
        "youngs_modulus": ("pressure", False),
        "cross_section_area": ("area", False),
        "damping_time": ("time", False),
        "end_masses": ("mass_pair", False),  # [upper, lower]: gravity-gradient tension (etcheck.input.gravity_gradient)
    },
    "operation": {
        "current": ("current_range", True),
        "axial_field": ("field_range", False),  # required unless [orbit] is given (exactly one of the two)
        "spin_rate": ("angular_rate", False),
        "end_tension": ("force", False),
        "orbit_rate": ("angular_rate", False),  # with tether.end_masses; or orbit_altitude, or the [orbit] table
        "orbit_altitude": ("length", False),
    },
    "sweep": {name: ("sweep_axis", False) for name in AXES},
    "orbit": {},  # its fields are checked by etcheck.orbit.spec.parse_orbit (imported only when given)
    "uncertainty": {name: ("uncertainty", False) for name in UNCERTAIN_INPUTS},
    "check": {
        "required_margin": ("number", False),
        "fidelity": ("text", False),
        "scaling_constant": ("number", False),
        "resolution": ("number", False),
        "tolerance": ("number", False),
    },
}


@dataclass(frozen=True)
class Mission:
    """A validated mission in physical units (astropy Quantities, SI).

    Ranges (current, axial field) are (low, high) pairs; the check uses the
    worst case |I| * |B0| and says so. ``notes`` records every assumption
    etcheck made (defaults taken, derived values) for the report.
    """

    name: str
    description: str
    length: u.Quantity
    bending_stiffness: tuple[u.Quantity, u.Quantity]  # (EI1, EI2), EI1 >= EI2
    torsional_stiffness: u.Quantity  # GJ
    mass_per_length: u.Quantity
    rotary_inertia_ratio: float  # P
    current: tuple[u.Quantity, u.Quantity]
    axial_field: tuple[u.Quantity, u.Quantity]
    spin_rate: u.Quantity = 0.0 * u.rad / u.s
    end_tension: u.Quantity = 0.0 * u.N
    damping_time: u.Quantity | None = None
    poisson_ratio: float | None = None
    youngs_modulus: u.Quantity | None = None
    cross_section_area: u.Quantity | None = None
    required_margin: float = 2.0
    fidelity: str = "auto"
    resolution: int | None = None
    tolerance: float = 1e-8
    scaling_constant: float = F_CLAMPED
    source: str = ""
    file: str = "mission"
    sha256: str = ""
    notes: tuple[str, ...] = field(default_factory=tuple)
    sweep: tuple[Axis, ...] = ()  # the [sweep] table: default axes of `etcheck sweep`
    uncertainty: Uncertainty | None = None  # the [uncertainty] table (etcheck.input.uncertainty)
    # the [orbit] table (etcheck.orbit.spec) and its envelope, computed once at load: axial_field is then
    # (env.worst, env.worst) T, the worst axial field over the orbit and the libration set
    orbit: OrbitSpec | None = None
    orbit_envelope: AxialFieldEnvelope | None = field(default=None, compare=False, repr=False)
    # tether.end_masses + orbit rate: the tension profile; end_tension is then its minimum (conservative)
    gravity_gradient: GravityGradient | None = None

    @property
    def slug(self) -> str:
        """File-system safe version of the name (the report folder)."""
        return slugify(self.name)

    @property
    def worst_current(self) -> u.Quantity:
        return max(abs(self.current[0]), abs(self.current[1]))

    @property
    def worst_field(self) -> u.Quantity:
        return max(abs(self.axial_field[0]), abs(self.axial_field[1]))

    @property
    def operating_load(self) -> u.Quantity:
        """Worst-case magnetic load per length |I| |B0| [N/m]."""
        return (self.worst_current * self.worst_field).to(u.N / u.m)

    def echo(self) -> dict[str, Any]:
        """The inputs as JSON-able {field: "value unit"} for reports."""

        def q(x):
            return None if x is None else f"{x.value:.6g} {_UNIT_TEXT.get(x.unit.to_string(), x.unit.to_string())}"

        def pair(p):
            return [q(p[0])] if p[0] == p[1] else [q(p[0]), q(p[1])]

        def microtesla(p):
            return [f"{x.to_value(u.uT):.6g} µT" for x in ([p[0]] if p[0] == p[1] else p)]

        return {
            "name": self.name,
            "description": self.description,
            "source": self.source,
            "file": self.file,
            "sha256": self.sha256,
            "tether": {
                "length": q(self.length),
                "bending_stiffness": pair(self.bending_stiffness),
                "torsional_stiffness": q(self.torsional_stiffness),
                "poisson_ratio": self.poisson_ratio,
                "mass_per_length": q(self.mass_per_length),
                "rotary_inertia_ratio": self.rotary_inertia_ratio,
                "youngs_modulus": q(self.youngs_modulus),
                "cross_section_area": q(self.cross_section_area),
                "damping_time": q(self.damping_time),
            },
            "operation": {
                "current": pair(self.current),
                "axial_field": microtesla(self.axial_field),
                "spin_rate": q(self.spin_rate),
                "spin_rate_rpm": float(self.spin_rate.to(u.cycle / u.min).value),
                "end_tension": q(self.end_tension),
                "gravity_gradient": None if self.gravity_gradient is None else self.gravity_gradient.as_dict(),
            },
            "check": {
                "required_margin": self.required_margin,
                "fidelity": self.fidelity,
                "scaling_constant": self.scaling_constant,
                "resolution": self.resolution,
                "tolerance": self.tolerance,
            },
            "notes": list(self.notes),
        } | ({"orbit": orbit_echo(self.orbit, self.orbit_envelope)} if self.orbit_envelope is not None else {})


_UNIT_TEXT = {"m2 N": "N m²", "kg / m": "kg/m", "rad / s": "rad/s", "m2": "m²"}


def slugify(name: str) -> str:
    slug = re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")
    return slug or "mission"


def load_mission(path: str | Path) -> Mission:
    """Read and validate a mission TOML file. Raises MissionError."""
    path = Path(path)
    source = str(path)
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise MissionError(source, None, "file not found", "check the path") from None
    except IsADirectoryError:
        raise MissionError(source, None, "is a directory, not a mission file", "give a .toml file") from None
    except OSError as exc:
        raise MissionError(source, None, f"cannot read the file ({exc.strerror})", "check permissions") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise MissionError(source, None, "is not UTF-8 text", "save the mission file as UTF-8 TOML") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MissionError(source, None, f"malformed TOML: {exc}", "fix the syntax at that line") from None
    return mission_from_dict(data, source=source, sha256=hashlib.sha256(raw).hexdigest())


def mission_from_dict(data: dict[str, Any], source: str = "mission", sha256: str = "") -> Mission:
    """Validate a mission given as nested dicts (TOML tables).

    Values may be strings (``"100 m"``), astropy or pint quantities; pint is
    converted through SI at this edge. Raises MissionError naming the field.
    """
    _check_tables(data, source)
    notes: list[str] = []
    t = data.get("tether", {})
    o = data.get("operation", {})
    c = data.get("check", {})
    m = data.get("mission", {})

    def err(fld: str, problem: str, fix: str = "") -> MissionError:
        return MissionError(source, fld, problem, fix)

    def get(table: str, key: str, kind: str, tbl: dict) -> Any:
        fld = f"{table}.{key}"
        value = tbl[key]
        try:
            return to_quantity(value, kind)
        except QuantityProblem as exc:
            raise err(fld, str(exc)) from None

    def positive(table: str, key: str, kind: str, tbl: dict) -> u.Quantity:
        q = get(table, key, kind, tbl)
        if q.value <= 0:
            raise err(f"{table}.{key}", f"must be positive, got {tbl[key]!r}")
        return q

    def number(table: str, key: str, tbl: dict, lo: float, hi: float, lo_open=False, hi_open=False) -> float:
        fld = f"{table}.{key}"
        value = tbl[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise err(fld, f"expected a plain number, got {value!r}")
        value = float(value)
        if not math.isfinite(value):
            raise err(fld, f"must be a finite number, got {value!r}")
        below = value <= lo if lo_open else value < lo
        above = value >= hi if hi_open else value > hi
        if below or above:
            lb = "(" if lo_open else "["
            hb = ")" if hi_open else "]"
            raise err(fld, f"must lie in {lb}{lo:g}, {hi:g}{hb}, got {value:g}")
        return value

    def text(table: str, key: str, tbl: dict, default: str = "") -> str:
        value = tbl.get(key, default)
        if not isinstance(value, str):
            raise err(f"{table}.{key}", f"expected text in quotes, got {value!r}")
        return value

    name = text("mission", "name", m).strip()
    if not name:
        raise err("mission.name", "is empty", 'give the mission a name, e.g. name = "SET"')

    length = positive("tether", "length", "length", t)

    # bending stiffness: [EI1, EI2] or one value (isotropic)
    bs = t["bending_stiffness"]
    items = bs if isinstance(bs, list) else [bs]
    if len(items) not in (1, 2):
        raise err("tether.bending_stiffness", f"expected one value or [EI1, EI2], got {len(items)} values")
    stiff = []
    for item in items:
        try:
            q = to_quantity(item, "bending_stiffness")
        except QuantityProblem as exc:
            raise err("tether.bending_stiffness", str(exc)) from None
        if q.value <= 0:
            raise err("tether.bending_stiffness", f"must be positive, got {item!r}")
        stiff.append(q)
    EI1, EI2 = (stiff[0], stiff[0]) if len(stiff) == 1 else (stiff[0], stiff[1])
    if EI2 > EI1:
        raise err(
            "tether.bending_stiffness",
            f"EI2 = {EI2} is larger than EI1 = {EI1}: the axes are swapped",
            "list the stiff axis first, [EI1, EI2] with EI1 >= EI2 (d1 is the stiff axis)",
        )

    # torsion
    has_nu, has_gj = "poisson_ratio" in t, "torsional_stiffness" in t
    if has_nu == has_gj:
        raise err(
            "tether.poisson_ratio",
            "give exactly one of poisson_ratio or torsional_stiffness" + (" (both given)" if has_nu else ""),
            "e.g. poisson_ratio = 0.3",
        )
    nu = None
    if has_nu:
        nu = number("tether", "poisson_ratio", t, -1.0, 0.5, lo_open=True)
        # GJ = G (I1 + I2) = E (I1 + I2) / (2 (1 + nu))
        GJ = (EI1 + EI2) / (2.0 * (1.0 + nu))
        notes.append(f"torsional stiffness GJ = (EI1 + EI2) / (2 (1 + nu)) = {GJ.value:.4g} N m2 (solid symmetric section)")
    else:
        GJ = positive("tether", "torsional_stiffness", "torsional_stiffness", t)

    mass = positive("tether", "mass_per_length", "mass_per_length", t)

    # rotary inertia
    E = A = None
    has_p = "rotary_inertia_ratio" in t
    has_section = "youngs_modulus" in t or "cross_section_area" in t
    if has_p and has_section:
        raise err(
            "tether.rotary_inertia_ratio",
            "give either rotary_inertia_ratio or youngs_modulus + cross_section_area, not both",
        )
    if has_p:
        P = number("tether", "rotary_inertia_ratio", t, 0.0, 1.0)
    elif has_section:
        for key in ("youngs_modulus", "cross_section_area"):
            if key not in t:
                raise err(f"tether.{key}", "missing", "give youngs_modulus and cross_section_area together")
        E = positive("tether", "youngs_modulus", "pressure", t)
        A = positive("tether", "cross_section_area", "area", t)
        P = float(((EI1 / E) / (A * length**2)).to(u.one).value)
        notes.append(f"rotary inertia ratio P = EI1 / (E A L^2) = {P:.4g} from youngs_modulus and cross_section_area")
    else:
        raise err(
            "tether.rotary_inertia_ratio",
            "missing",
            "give rotary_inertia_ratio (P = I1/(A L^2)) or youngs_modulus and cross_section_area",
        )

    damping = None
    if "damping_time" in t:
        damping = get("tether", "damping_time", "time", t)
        if damping.value < 0:
            raise err("tether.damping_time", f"must be >= 0, got {t['damping_time']!r}")

    current = _range(o, "operation", "current", "current", err)
    check_one_field_source(o, data, source)
    orbit = envelope = None
    if "orbit" in data:  # the field along the orbit (IGRF), evaluated once here: its worst case is the load's field
        orbit, envelope = orbit_axial_field(data["orbit"], source)
        bfield = (envelope.worst * u.T, envelope.worst * u.T)
        notes.extend(orbit_notes(orbit, envelope))
    else:
        bfield = _range(o, "operation", "axial_field", "field", err)
    spin = 0.0 * u.rad / u.s
    if "spin_rate" in o:
        spin = get("operation", "spin_rate", "angular_rate", o)
        if spin.value < 0:
            spin = -spin
            notes.append("spin_rate given negative: the direction of spin does not change stability; its magnitude is used")
    tension = get("operation", "end_tension", "force", o) if "end_tension" in o else 0.0 * u.N
    gg = parse_gravity_gradient(t, o, orbit, float(length.to_value(u.m)), float(mass.to_value(u.kg / u.m)), source)
    if gg is not None:  # the smallest tension along the tether: tension stabilises, so this is conservative
        tension = gg.minimum * u.N
        notes.append(gg.statement())

    required = number("check", "required_margin", c, 1.0, math.inf, hi_open=True) if "required_margin" in c else 2.0
    fidelity = text("check", "fidelity", c, "auto")
    if fidelity not in FIDELITIES:
        raise err("check.fidelity", f"unknown fidelity {fidelity!r}", f"use one of {', '.join(FIDELITIES)}")
    f = number("check", "scaling_constant", c, 0.0, math.inf, lo_open=True, hi_open=True) if "scaling_constant" in c else F_CLAMPED

    resolution = None
    if "resolution" in c:
        value = c["resolution"]
        if isinstance(value, bool) or not isinstance(value, int) or not 8 <= value <= 128:
            raise err("check.resolution", f"expected a whole number of Chebyshev points in [8, 128], got {value!r}",
                      "leave it out to let etcheck choose the resolution for the tolerance")
        resolution = value
    tolerance = number("check", "tolerance", c, 1e-13, 1e-3) if "tolerance" in c else 1e-8

    if current[0] != current[1] or bfield[0] != bfield[1]:
        notes.append("current and/or field given as a range: the check uses the worst case |I| x |B0|")
    uncertainty = None
    if "uncertainty" in data:
        nominal = {"EI1": EI1, "EI2": EI2, "torsional_stiffness": GJ, "mass_per_length": mass, "length": length,
                   "current": max(abs(current[0]), abs(current[1])), "axial_field": max(abs(bfield[0]), abs(bfield[1])),
                   "spin_rate": spin, "end_tension": tension, "damping_time": damping}
        fixed = {"torsional_stiffness": "GJ follows from poisson_ratio and the bending stiffnesses; give "
                 "[tether] torsional_stiffness instead of poisson_ratio to vary it"} if nu is not None else {}
        uncertainty = parse_uncertainty(data["uncertainty"], source, nominal, fixed)
        notes.extend(uncertainty.notes)
    if damping is None:
        notes.append(
            f"no damping_time given: dimensionless damping gamma = {DEFAULT_GAMMA} assumed "
            "(the paper's estimate for a real tether, Sec. VII B)"
        )

    return Mission(
        name=name,
        description=text("mission", "description", m),
        source=text("mission", "source", m),
        length=length,
        bending_stiffness=(EI1, EI2),
        torsional_stiffness=GJ,
        poisson_ratio=nu,
        mass_per_length=mass,
        rotary_inertia_ratio=P,
        youngs_modulus=E,
        cross_section_area=A,
        damping_time=damping,
        current=current,
        axial_field=bfield,
        spin_rate=spin,
        end_tension=tension,
        required_margin=required,
        fidelity=fidelity,
        resolution=resolution,
        tolerance=tolerance,
        scaling_constant=f,
        file=source,
        sha256=sha256,
        notes=tuple(notes),
        sweep=parse_table(data["sweep"], source) if data.get("sweep") else (),
        uncertainty=uncertainty,
        orbit=orbit,
        orbit_envelope=envelope,
        gravity_gradient=gg,
    )


def _range(tbl: dict, table: str, key: str, kind: str, err) -> tuple[u.Quantity, u.Quantity]:
    fld = f"{table}.{key}"
    value = tbl[key]
    items = value if isinstance(value, list) else [value, value]
    if len(items) != 2:
        raise err(fld, f"expected one value or a [min, max] range, got {len(items)} values")
    try:
        lo, hi = (to_quantity(x, kind) for x in items)
    except QuantityProblem as exc:
        raise err(fld, str(exc)) from None
    if lo > hi:
        raise err(fld, f"range [{items[0]}, {items[1]}] has min > max", "write it as [min, max]")
    return lo, hi


def _check_tables(data: dict[str, Any], source: str) -> None:
    """Unknown tables/fields (typos) and missing required fields."""
    for table, value in data.items():
        if table not in SCHEMA:
            raise MissionError(source, table, "unknown table" + _suggest(table, SCHEMA), f"tables are {', '.join('[' + k + ']' for k in SCHEMA)}")
        if not isinstance(value, dict):
            raise MissionError(source, table, "must be a table", f"write it as [{table}] followed by its fields")
        if table == "orbit":
            continue  # parse_orbit names unknown orbit.FIELDs with its own suggestions
        for key in value:
            if key not in SCHEMA[table]:
                raise MissionError(
                    source,
                    f"{table}.{key}",
                    "unknown field" + _suggest(key, SCHEMA[table]),
                    f"fields of [{table}] are {', '.join(SCHEMA[table])}",
                )
    for table, fields in SCHEMA.items():
        for key, (_, required) in fields.items():
            if required and key not in data.get(table, {}):
                raise MissionError(source, f"{table}.{key}", "missing required field", _example(table, key))


def _suggest(word: str, options) -> str:
    close = difflib.get_close_matches(word, list(options), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _example(table: str, key: str) -> str:
    examples = {
        "name": 'e.g. name = "SET"',
        "length": 'e.g. length = "100 m"',
        "bending_stiffness": 'e.g. bending_stiffness = ["38 N m2", "21 N m2"]',
        "mass_per_length": 'e.g. mass_per_length = "0.05 kg/m"',
        "current": 'e.g. current = "1 A" or ["0.2 A", "1 A"]',
        "axial_field": 'e.g. axial_field = "70 uT"',
    }
    return f"add it under [{table}]: " + examples.get(key, f"{key} = ...")
