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
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import astropy.units as u

from etcheck.errors import MissionError
from etcheck.input.current_profile import parse_current_profile
from etcheck.input.echo import CheckEcho, FlightEcho, MissionEcho, OperationEcho, TetherEcho
from etcheck.input.gravity_gradient import GravityGradient, parse_gravity_gradient
from etcheck.input.mission_parts import Operation, Provenance, Studies, TetherProperties
from etcheck.input.orbit_field import check_one_field_source, orbit_echo
from etcheck.input.sweep_axes import AXES, parse_table
from etcheck.input.uncertainty import INPUTS as UNCERTAIN_INPUTS
from etcheck.input.uncertainty import Uncertainty, parse_uncertainty
from etcheck.input.units import QuantityProblem, to_quantity
from etcheck.jsonable import OMITTED
from etcheck.rod.core.ends import ALL_WELDED, Ends, describe, is_welded
from etcheck.rod.core.ends import KINDS as END_KINDS
from etcheck.rod.core.parameters import F_CLAMPED

if TYPE_CHECKING:  # etcheck.orbit (IGRF, SGP4) is imported only for missions with an [orbit] table
    from etcheck.orbit.spec import OrbitSpec

#: Dimensionless damping gamma assumed when a mission gives no damping_time:
#: the paper's estimate for a real tether in working conditions (Sec. VII B).
DEFAULT_GAMMA = 0.04375

FIDELITIES = ("auto", "draft", "analytic", "linear")
#: which model answers (``[check] fidelity`` but "draft") and how precisely (sign-off or draft)
MODELS = ("auto", "analytic", "linear")
PRECISIONS = ("sign-off", "draft")


@dataclass(frozen=True)
class Field:
    """How one field of a mission table is read and checked.

    ``kind`` is a quantity kind of :data:`etcheck.input.units.KINDS` (the value
    is converted to SI; ``sign`` "positive" asks > 0, "non-negative" >= 0),
    ``"number"`` (a plain number in [lo, hi], an end excluded where ``lo_open``
    or ``hi_open``), ``"text"`` (one of ``choices`` where given),
    ``"chebyshev_points"`` (a whole number in [lo, hi]) or a structured kind
    read by its own parser (stiffness_pair, mass_pair, current_range,
    field_range, sweep_axis, uncertainty). ``default`` is the value of a field
    left out.
    """

    kind: str
    required: bool = False
    default: Any = None
    lo: float = -math.inf
    hi: float = math.inf
    lo_open: bool = False
    hi_open: bool = False
    sign: str = ""
    choices: tuple[str, ...] = ()


#: table -> field -> how it is read. [orbit] fields are checked by etcheck.input.orbit_table.parse_orbit
#: (imported only when the table is given); tether.end_masses and operation.orbit_rate/orbit_altitude by
#: etcheck.input.gravity_gradient; [sweep] by etcheck.input.sweep_axes; [uncertainty] by etcheck.input.uncertainty.
SCHEMA: dict[str, dict[str, Field]] = {
    "mission": {"name": Field("text", required=True, default=""), "description": Field("text", default=""),
                "source": Field("text", default=""),
                "assumed": Field("assumed_fields"),  # fields whose values are assumptions (flagged on page 1)
                "flight": Field("flight")},  # { outcome = "coiled" | "straight", reported = "who said so" }
    "tether": {
        "length": Field("length", required=True, sign="positive"),
        "bending_stiffness": Field("stiffness_pair", required=True),
        "poisson_ratio": Field("number", lo=-1.0, hi=0.5, lo_open=True),
        "torsional_stiffness": Field("torsional_stiffness", sign="positive"),
        "mass_per_length": Field("mass_per_length", required=True, sign="positive"),
        "rotary_inertia_ratio": Field("number", lo=0.0, hi=1.0),
        "youngs_modulus": Field("pressure", sign="positive"),
        "cross_section_area": Field("area", sign="positive"),
        "damping_time": Field("time", sign="non-negative"),
        "end_masses": Field("mass_pair"),  # [upper, lower]: gravity-gradient tension
        "end_conditions": Field("end_conditions", default=ALL_WELDED, choices=END_KINDS),  # [lower, upper]
    },
    "operation": {
        "current": Field("current_range", required=True),
        "current_profile": Field("current_profile"),  # I(s)/I_max: points or "OML" (etcheck.input.current_profile)
        "collection": Field("collection"),  # the [operation.collection] table of current_profile = "OML"
        "axial_field": Field("field_range"),  # required unless [orbit] is given (exactly one of the two)
        "cross_field": Field("field_range"),  # the field across the tether (its bow); not with [orbit]
        "spin_rate": Field("angular_rate", default=0.0 * u.rad / u.s),
        "end_tension": Field("force", default=0.0 * u.N),
        "orbit_rate": Field("angular_rate"),  # with tether.end_masses; or orbit_altitude, or the [orbit] table
        "orbit_altitude": Field("length"),  # one altitude (circular) or [perigee, apogee]
    },
    "sweep": {name: Field("sweep_axis") for name in AXES},
    "orbit": {},
    "uncertainty": {name: Field("uncertainty") for name in UNCERTAIN_INPUTS},
    "check": {
        "required_margin": Field("number", default=2.0, lo=1.0, hi_open=True),
        "fidelity": Field("text", default="auto", choices=FIDELITIES),
        "scaling_constant": Field("number", default=F_CLAMPED, lo=0.0, lo_open=True, hi_open=True),
        "resolution": Field("chebyshev_points", lo=8, hi=128),
        "tolerance": Field("number", default=1e-8, lo=1e-13, hi=1e-3),
    },
}


@dataclass(frozen=True)
class CheckSettings:
    """The ``[check]`` table: what a check must show and how it computes.

    ``model`` says which model answers ("auto": the plan's choice; "analytic": rung 0 only, incomplete where it
    cannot answer; "linear": rung 1 even where rung 0 is exact) and ``precision`` how precisely ("sign-off", or
    "draft": the margins only, at a looser tolerance). The file's one field ``fidelity`` sets both
    (:func:`check_settings`: "draft" is the automatic model at draft precision).
    """

    required_margin: float = 2.0
    model: str = "auto"
    precision: str = "sign-off"
    resolution: int | None = None
    tolerance: float = 1e-8
    scaling_constant: float = F_CLAMPED

    @property
    def fidelity(self) -> str:
        """``[check] fidelity`` as the file says it (one of :data:`FIDELITIES`)."""
        return "draft" if self.precision == "draft" else self.model

    @property
    def draft(self) -> bool:
        return self.precision == "draft"


def check_settings(fidelity: str = "auto", **settings: Any) -> CheckSettings:
    """The check settings of a ``[check] fidelity`` (one of :data:`FIDELITIES`) and the table's other fields."""
    draft = fidelity == "draft"
    return CheckSettings(model="auto" if draft else fidelity, precision="draft" if draft else "sign-off", **settings)


@dataclass(frozen=True)
class Mission:
    """A validated mission in physical units (astropy Quantities, SI), one record per concern.

    ``tether`` is the tether, ``operation`` how it is run, ``orbit`` the ``[orbit]`` table as read (None
    without one; the field over it is the check's orbit stage, :func:`etcheck.checks.orbit_field.resolve`,
    whose mission holds the worst axial field over the orbit and libration as ``operation.axial_field``),
    ``check`` what a check must show, ``provenance`` where the mission comes from and every assumption
    etcheck made reading it, ``studies`` the sweep and uncertainty studies the file asks for. A changed
    mission is :meth:`with_tether`, :meth:`with_operation`, ... of the record that changes.
    """

    tether: TetherProperties
    operation: Operation
    provenance: Provenance
    check: CheckSettings = CheckSettings()  # the [check] table
    studies: Studies = Studies()
    orbit: OrbitSpec | None = None

    @property
    def slug(self) -> str:
        """File-system safe version of the name (the report folder)."""
        return slugify(self.provenance.name)

    def with_tether(self, **changes: Any) -> Mission:
        """The mission with ``changes`` to its tether (e.g. ``length=200 * u.m``)."""
        return replace(self, tether=replace(self.tether, **changes))

    def with_operation(self, **changes: Any) -> Mission:
        """The mission with ``changes`` to its operation (e.g. ``spin_rate=0.1 * u.rad / u.s``)."""
        return replace(self, operation=replace(self.operation, **changes))

    def with_provenance(self, **changes: Any) -> Mission:
        """The mission with ``changes`` to its provenance (e.g. more ``notes``)."""
        return replace(self, provenance=replace(self.provenance, **changes))

    def with_check(self, **changes: Any) -> Mission:
        """The mission with ``changes`` to its ``[check]`` settings (e.g. ``required_margin=3.0``)."""
        return replace(self, check=replace(self.check, **changes))

    def with_studies(self, **changes: Any) -> Mission:
        """The mission with ``changes`` to its studies (e.g. ``uncertainty=None``)."""
        return replace(self, studies=replace(self.studies, **changes))

    def with_fidelity(self, fidelity: str) -> Mission:
        """The mission checked at another ``[check] fidelity`` (one of :data:`FIDELITIES`), its other settings kept."""
        c = self.check
        return replace(self, check=check_settings(fidelity, required_margin=c.required_margin, resolution=c.resolution,
                                                  tolerance=c.tolerance, scaling_constant=c.scaling_constant))

    def echo(self) -> MissionEcho:
        """The inputs as read, for the results: quantities as "value unit" texts."""

        def q(x):
            return None if x is None else f"{x.value:.6g} {_UNIT_TEXT.get(x.unit.to_string(), x.unit.to_string())}"

        def pair(p):
            return (q(p[0]),) if p[0] == p[1] else (q(p[0]), q(p[1]))

        def microtesla(p):
            return tuple(f"{x.to_value(u.uT):.6g} µT" for x in ([p[0]] if p[0] == p[1] else p))

        t, op, pv = self.tether, self.operation, self.provenance
        return MissionEcho(
            name=pv.name,
            description=pv.description,
            source=pv.source,
            file=pv.file,
            sha256=pv.sha256,
            tether=TetherEcho(
                length=q(t.length),
                bending_stiffness=pair(t.bending_stiffness),
                torsional_stiffness=q(t.torsional_stiffness),
                poisson_ratio=t.poisson_ratio,
                mass_per_length=q(t.mass_per_length),
                rotary_inertia_ratio=t.rotary_inertia_ratio,
                youngs_modulus=q(t.youngs_modulus),
                cross_section_area=q(t.cross_section_area),
                damping_time=q(t.damping_time),
                end_conditions=tuple(t.end_conditions),
            ),
            operation=OperationEcho(
                current=pair(op.current),
                current_profile=None if op.current_profile is None else op.current_profile.echo(),
                axial_field=None if op.axial_field is None else microtesla(op.axial_field),
                cross_field=None if op.cross_field is None else microtesla(op.cross_field),
                spin_rate=q(op.spin_rate),
                spin_rate_rpm=float(op.spin_rate.to(u.cycle / u.min).value),
                end_tension=q(op.end_tension),
                gravity_gradient=None if op.gravity_gradient is None else op.gravity_gradient.echo(),
            ),
            check=CheckEcho(
                required_margin=self.check.required_margin,
                fidelity=self.check.fidelity,
                scaling_constant=self.check.scaling_constant,
                resolution=self.check.resolution,
                tolerance=self.check.tolerance,
            ),
            notes=tuple(pv.notes),
            assumed=tuple(pv.assumed),
            flight=None if pv.flight is None else FlightEcho(**pv.flight),
            orbit=OMITTED if self.orbit is None else orbit_echo(self.orbit),
        )


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
    Fields are read in a fixed order, so a file with several problems always
    reports the same one first.
    """
    _check_tables(data, source)
    t, o, c, m = (data.get(table, {}) for table in ("tether", "operation", "check", "mission"))
    name = _name(m, source)
    length = read_field(t, "tether", "length", source)
    EI1, EI2 = _bending_stiffness(t["bending_stiffness"], source)
    GJ, nu, torsion_notes = _torsion(t, EI1, EI2, source)
    mass = read_field(t, "tether", "mass_per_length", source)
    P, E, A, inertia_notes = _rotary_inertia(t, EI1, length, source)
    damping = read_field(t, "tether", "damping_time", source)
    ends = read_field(t, "tether", "end_conditions", source)
    current = _range(o, "operation", "current", "current", source)
    bfield, orbit = _axial_field(o, data, source)
    cross = _cross_field(o, orbit, source)
    spin, spin_notes = _spin_rate(o, source)
    tension, gg, tension_notes = _tension(t, o, orbit, length, mass, source)
    profile = parse_current_profile(o, t, float(length.to_value(u.m)),
                                    None if A is None else float(A.to_value(u.m**2)),
                                    float(max(abs(current[0]), abs(current[1])).to_value(u.A)), source)
    settings = {key: read_field(c, "check", key, source) for key in SCHEMA["check"]}
    nominal = {"EI1": EI1, "EI2": EI2, "torsional_stiffness": GJ, "mass_per_length": mass, "length": length,
               "current": max(abs(current[0]), abs(current[1])),
               "axial_field": None if bfield is None else max(abs(bfield[0]), abs(bfield[1])),
               "spin_rate": spin, "end_tension": tension, "damping_time": damping}
    uncertainty, uncertainty_notes = _uncertainty(data, source, nominal, gj_derived=nu is not None)
    assumed, assumed_notes = _assumed(m, data, source)
    notes = (*_end_notes(ends), *torsion_notes, *inertia_notes, *spin_notes, *tension_notes,
             *(profile.notes if profile else ()),
             *_range_notes(current, bfield), *uncertainty_notes, *_damping_notes(damping), *assumed_notes)
    tether = TetherProperties(length=length, bending_stiffness=(EI1, EI2), torsional_stiffness=GJ, poisson_ratio=nu,
                              mass_per_length=mass, rotary_inertia_ratio=P, youngs_modulus=E, cross_section_area=A,
                              damping_time=damping, end_conditions=ends)
    operation = Operation(current=current, axial_field=bfield, spin_rate=spin, end_tension=tension, cross_field=cross,
                          gravity_gradient=gg, current_profile=profile)
    provenance = Provenance(
        name=name, description=read_field(m, "mission", "description", source),
        source=read_field(m, "mission", "source", source), file=source, sha256=sha256, notes=notes,
        assumed=assumed, flight=_flight(m, source),
        given=frozenset(f"{table}.{key}" for table, fields in data.items() if table != "orbit" for key in fields))
    studies = Studies(sweep=parse_table(data["sweep"], source) if data.get("sweep") else (), uncertainty=uncertainty)
    return Mission(tether=tether, operation=operation, provenance=provenance, check=check_settings(**settings),
                   studies=studies, orbit=orbit)


def read_field(tbl: dict[str, Any], table: str, key: str, source: str) -> Any:
    """The value of ``[table] key`` read as :data:`SCHEMA` says (its default when the field is left out).

    For the scalar kinds: quantities (astropy, SI), numbers (float), text and
    Chebyshev point counts (int). Raises MissionError naming ``table.key``.
    """
    spec = SCHEMA[table][key]
    if key not in tbl:
        return spec.default
    reader = _READERS.get(spec.kind, _quantity)
    return reader(tbl[key], spec, f"{table}.{key}", source)


def _quantity(value: Any, spec: Field, fld: str, source: str) -> u.Quantity:
    try:
        q = to_quantity(value, spec.kind)
    except QuantityProblem as exc:
        raise MissionError(source, fld, str(exc)) from None
    if spec.sign == "positive" and q.value <= 0:
        raise MissionError(source, fld, f"must be positive, got {value!r}")
    if spec.sign == "non-negative" and q.value < 0:
        raise MissionError(source, fld, f"must be >= 0, got {value!r}")
    return q


def _number(value: Any, spec: Field, fld: str, source: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise MissionError(source, fld, f"expected a plain number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise MissionError(source, fld, f"must be a finite number, got {value!r}")
    below = value <= spec.lo if spec.lo_open else value < spec.lo
    above = value >= spec.hi if spec.hi_open else value > spec.hi
    if below or above:
        lb = "(" if spec.lo_open else "["
        hb = ")" if spec.hi_open else "]"
        raise MissionError(source, fld, f"must lie in {lb}{spec.lo:g}, {spec.hi:g}{hb}, got {value:g}")
    return value


def _text(value: Any, spec: Field, fld: str, source: str) -> str:
    if not isinstance(value, str):
        raise MissionError(source, fld, f"expected text in quotes, got {value!r}")
    if spec.choices and value not in spec.choices:
        raise MissionError(source, fld, f"unknown {fld.split('.')[-1]} {value!r}", f"use one of {', '.join(spec.choices)}")
    return value


def _chebyshev_points(value: Any, spec: Field, fld: str, source: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not spec.lo <= value <= spec.hi:
        raise MissionError(source, fld, f"expected a whole number of Chebyshev points in [{spec.lo:g}, {spec.hi:g}], "
                           f"got {value!r}", "leave it out to let etcheck choose the resolution for the tolerance")
    return value


def _end_conditions(value: Any, spec: Field, fld: str, source: str) -> tuple[str, str]:
    """One attachment for both ends or [lower, upper], each one of ``spec.choices``; not a swivel at both."""
    items = value if isinstance(value, list) else [value, value]
    if len(items) != 2:
        raise MissionError(source, fld, f"expected one attachment or [lower, upper], got {len(items)} values",
                           'e.g. end_conditions = ["welded", "pinned"]')
    for item in items:
        if not isinstance(item, str) or item not in spec.choices:
            raise MissionError(source, fld, f"unknown attachment {item!r}", f"use one of {', '.join(spec.choices)}")
    try:
        return Ends.of(items)
    except ValueError:
        raise MissionError(source, fld, "a swivel at both ends leaves the tether free to turn about its axis",
                           "hold the twist at one end at least: welded or pinned") from None


def _end_notes(ends: tuple[str, str]) -> list[str]:
    if is_welded(ends):
        return []
    return [f"tether.end_conditions: {describe(ends)}; a pinned end passes no bending moment and holds the twist "
            "(a gimbal), a swivel passes no moment at all"]


_READERS = {"number": _number, "text": _text, "chebyshev_points": _chebyshev_points, "end_conditions": _end_conditions}


def _name(m: dict[str, Any], source: str) -> str:
    name = read_field(m, "mission", "name", source).strip()
    if not name:
        raise MissionError(source, "mission.name", "is empty", 'give the mission a name, e.g. name = "SET"')
    return name


def _bending_stiffness(value: Any, source: str) -> tuple[u.Quantity, u.Quantity]:
    """tether.bending_stiffness: [EI1, EI2] or one value (isotropic), N m^2, EI1 >= EI2."""
    items = value if isinstance(value, list) else [value]
    if len(items) not in (1, 2):
        raise MissionError(source, "tether.bending_stiffness",
                           f"expected one value or [EI1, EI2], got {len(items)} values")
    stiff = [_quantity(item, _STIFFNESS, "tether.bending_stiffness", source) for item in items]
    EI1, EI2 = stiff[0], stiff[-1]
    if EI2 > EI1:
        raise MissionError(
            source,
            "tether.bending_stiffness",
            f"EI2 = {EI2} is larger than EI1 = {EI1}: the axes are swapped",
            "list the stiff axis first, [EI1, EI2] with EI1 >= EI2 (d1 is the stiff axis)",
        )
    return EI1, EI2


_STIFFNESS = Field("bending_stiffness", sign="positive")


def _torsion(t: dict[str, Any], EI1: u.Quantity, EI2: u.Quantity, source: str) -> tuple[u.Quantity, float | None, list[str]]:
    """GJ (N m^2) given, or from the Poisson ratio nu: GJ = (EI1 + EI2) / (2 (1 + nu)); (GJ, nu or None, notes)."""
    has_nu, has_gj = "poisson_ratio" in t, "torsional_stiffness" in t
    if has_nu == has_gj:
        raise MissionError(
            source,
            "tether.poisson_ratio",
            "give exactly one of poisson_ratio or torsional_stiffness" + (" (both given)" if has_nu else ""),
            "e.g. poisson_ratio = 0.3",
        )
    if has_gj:
        return read_field(t, "tether", "torsional_stiffness", source), None, []
    nu = read_field(t, "tether", "poisson_ratio", source)
    # GJ = G (I1 + I2) = E (I1 + I2) / (2 (1 + nu))
    GJ = (EI1 + EI2) / (2.0 * (1.0 + nu))
    return GJ, nu, [f"torsional stiffness GJ = (EI1 + EI2) / (2 (1 + nu)) = {GJ.value:.4g} N m2 (solid symmetric section)"]


def _rotary_inertia(t: dict[str, Any], EI1: u.Quantity, length: u.Quantity, source: str):
    """P given, or P = EI1 / (E A L^2) from youngs_modulus and cross_section_area; (P, E or None, A or None, notes)."""
    has_p = "rotary_inertia_ratio" in t
    has_section = "youngs_modulus" in t or "cross_section_area" in t
    if has_p and has_section:
        raise MissionError(
            source,
            "tether.rotary_inertia_ratio",
            "give either rotary_inertia_ratio or youngs_modulus + cross_section_area, not both",
        )
    if has_p:
        return read_field(t, "tether", "rotary_inertia_ratio", source), None, None, []
    if not has_section:
        raise MissionError(
            source,
            "tether.rotary_inertia_ratio",
            "missing",
            "give rotary_inertia_ratio (P = I1/(A L^2)) or youngs_modulus and cross_section_area",
        )
    for key in ("youngs_modulus", "cross_section_area"):
        if key not in t:
            raise MissionError(source, f"tether.{key}", "missing", "give youngs_modulus and cross_section_area together")
    E = read_field(t, "tether", "youngs_modulus", source)
    A = read_field(t, "tether", "cross_section_area", source)
    P = float(((EI1 / E) / (A * length**2)).to(u.one).value)
    return P, E, A, [f"rotary inertia ratio P = EI1 / (E A L^2) = {P:.4g} from youngs_modulus and cross_section_area"]


def _axial_field(o: dict[str, Any], data: dict[str, Any], source: str):
    """(operation.axial_field as a range in T, None), or (None, the [orbit] table as an OrbitSpec): the field over
    the orbit is evaluated by the check's orbit stage, not here."""
    check_one_field_source(o, data, source)
    if "orbit" not in data:
        return _range(o, "operation", "axial_field", "field", source), None
    from etcheck.input.orbit_table import parse_orbit  # astropy.time and SGP4 only for a mission with an orbit

    return None, parse_orbit(data["orbit"], source)


def _cross_field(o: dict[str, Any], orbit: OrbitSpec | None, source: str) -> tuple[u.Quantity, u.Quantity] | None:
    """operation.cross_field as a range in T (None where not given); not with an [orbit] table, which gives it."""
    if "cross_field" not in o:
        return None
    if orbit is not None:
        raise MissionError(source, "operation.cross_field", "given together with an [orbit] table",
                           "leave it out: the field across the tether is then computed along the orbit")
    return _range(o, "operation", "cross_field", "field", source)


def _assumed(m: dict[str, Any], data: dict[str, Any], source: str) -> tuple[tuple[str, ...], list[str]]:
    """[mission] assumed: a list of "table.field" names (or a table's name for all of it) whose values are
    assumptions rather than data, and a note for each that this file does not give (it took its default);
    MissionError naming an unknown entry."""
    if "assumed" not in m:
        return (), []
    value = m["assumed"]
    if not isinstance(value, list) or not all(isinstance(x, str) for x in value):
        raise MissionError(source, "mission.assumed", f"expected a list of field names, got {value!r}",
                           'e.g. assumed = ["tether.end_masses", "operation.axial_field"]')
    for name in value:
        table, _, key = name.partition(".")
        known = table in SCHEMA and table != "mission" and (not key or table == "orbit" or key in SCHEMA[table])
        if not known:
            raise MissionError(source, "mission.assumed", f"unknown field {name!r}",
                               'name fields as "table.field", e.g. "tether.end_masses"')
    given = [n for n in value if (n.partition(".")[2] in data.get(n.partition(".")[0], {})
                                  if "." in n else n in data)]
    notes = [f"mission.assumed lists {n}, which this file does not give: it took its default" for n in value
             if n not in given]
    return tuple(given), notes


#: what a flown tether did: left the straight state (buckled, coiled, tangled) or stayed straight
FLIGHT_OUTCOMES = ("coiled", "straight")


def _flight(m: dict[str, Any], source: str) -> dict[str, str] | None:
    """[mission] flight = { outcome = "coiled" | "straight", reported = "who reported it" } (None: not flown)."""
    if "flight" not in m:
        return None
    value = m["flight"]
    if not isinstance(value, dict) or set(value) - {"outcome", "reported"} or "outcome" not in value:
        raise MissionError(source, "mission.flight", f"expected {{ outcome = ..., reported = ... }}, got {value!r}",
                           'e.g. flight = { outcome = "coiled", reported = "flight report, 1995" }')
    if value["outcome"] not in FLIGHT_OUTCOMES:
        raise MissionError(source, "mission.flight", f"unknown outcome {value['outcome']!r}",
                           f"use one of {', '.join(FLIGHT_OUTCOMES)}")
    if not isinstance(value.get("reported", ""), str):
        raise MissionError(source, "mission.flight", "reported must be text", "say who reported the outcome")
    return {"outcome": value["outcome"], "reported": value.get("reported", "")}


def _spin_rate(o: dict[str, Any], source: str) -> tuple[u.Quantity, list[str]]:
    """Its magnitude (rad/s): the direction of spin does not change stability."""
    spin = read_field(o, "operation", "spin_rate", source)
    if spin.value >= 0:
        return spin, []
    return -spin, ["spin_rate given negative: the direction of spin does not change stability; its magnitude is used"]


def _tension(t: dict[str, Any], o: dict[str, Any], orbit: OrbitSpec | None, length: u.Quantity, mass: u.Quantity,
             source: str) -> tuple[u.Quantity, GravityGradient | None, list[str]]:
    """operation.end_tension (N), or the smallest gravity-gradient tension along the tether (tension stabilises,
    so this is conservative); (tension, profile or None, notes)."""
    tension = read_field(o, "operation", "end_tension", source)
    gg = parse_gravity_gradient(t, o, orbit, float(length.to_value(u.m)), float(mass.to_value(u.kg / u.m)), source)
    if gg is None:
        return tension, None, []
    return gg.minimum * u.N, gg, [gg.statement()]


def _range_notes(current: tuple[u.Quantity, u.Quantity], bfield: tuple[u.Quantity, u.Quantity] | None) -> list[str]:
    if current[0] != current[1] or (bfield is not None and bfield[0] != bfield[1]):
        return ["current and/or field given as a range: the check uses the worst case |I| x |B0|"]
    return []


def _uncertainty(data: dict[str, Any], source: str, nominal: dict[str, Any],
                 gj_derived: bool) -> tuple[Uncertainty | None, tuple[str, ...]]:
    """The [uncertainty] table about the nominal values (None without it) and its notes."""
    if "uncertainty" not in data:
        return None, ()
    fixed = {"torsional_stiffness": "GJ follows from poisson_ratio and the bending stiffnesses; give "
             "[tether] torsional_stiffness instead of poisson_ratio to vary it"} if gj_derived else {}
    uncertainty = parse_uncertainty(data["uncertainty"], source, nominal, fixed)
    return uncertainty, uncertainty.notes


def _damping_notes(damping: u.Quantity | None) -> list[str]:
    if damping is not None:
        return []
    return [f"no damping_time given: dimensionless damping gamma = {DEFAULT_GAMMA} assumed "
            "(the paper's estimate for a real tether, Sec. VII B)"]


def _range(tbl: dict, table: str, key: str, kind: str, source: str) -> tuple[u.Quantity, u.Quantity]:
    """One value or a [min, max] range of quantities of ``kind`` (SI)."""
    fld = f"{table}.{key}"
    value = tbl[key]
    items = value if isinstance(value, list) else [value, value]
    if len(items) != 2:
        raise MissionError(source, fld, f"expected one value or a [min, max] range, got {len(items)} values")
    spec = Field(kind)
    lo, hi = (_quantity(x, spec, fld, source) for x in items)
    if lo > hi:
        raise MissionError(source, fld, f"range [{items[0]}, {items[1]}] has min > max", "write it as [min, max]")
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
        for key, spec in fields.items():
            if spec.required and key not in data.get(table, {}):
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
