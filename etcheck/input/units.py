"""The unit edge: strings, astropy and pint quantities -> astropy quantities.

astropy.units is the one internal quantity type. pint quantities are accepted
at the public API and converted through their SI value (unit names differ
between the two libraries: pint's ``mil`` is an angle, astropy's is 25.4 µm).
astropy has no ``rpm``; it is defined here as one cycle per minute.
"""

from __future__ import annotations

import math

import astropy.units as u

rpm = u.def_unit("rpm", u.cycle / u.min, doc="revolutions per minute")
u.add_enabled_units([rpm])

#: Expected kinds of quantity: SI unit, a human description and an example.
KINDS = {
    "length": (u.m, "a length", '"100 m"'),
    "bending_stiffness": (u.N * u.m**2, "a bending stiffness", '"38 N m2"'),
    "torsional_stiffness": (u.N * u.m**2, "a torsional stiffness", '"29 N m2"'),
    "mass_per_length": (u.kg / u.m, "a mass per length", '"0.05 kg/m"'),
    "pressure": (u.Pa, "a modulus (pressure)", '"132 GPa"'),
    "area": (u.m**2, "an area", '"3.1 mm2"'),
    "time": (u.s, "a time", '"0.02 s"'),
    "current": (u.A, "a current", '"1 A"'),
    "field": (u.T, "a magnetic flux density", '"70 uT"'),
    "angular_rate": (u.rad / u.s, "a spin rate", '"2 rpm" or "0.2 rad/s"'),
    "force": (u.N, "a force", '"5 N"'),
    "angle": (u.rad, "an angle", '"51.6 deg"'),
    "mass": (u.kg, "a mass", '"20 kg"'),
    "number_density": (u.m**-3, "a number density", '"1e11 m-3"'),
    "electric_field": (u.V / u.m, "an electric field", '"0.15 V/m"'),
    "conductivity": (u.S / u.m, "an electrical conductivity", '"3.5e7 S/m"'),
}


class QuantityProblem(ValueError):
    """Why a value is not the quantity that was expected (no field name yet)."""


def to_quantity(value, kind: str) -> u.Quantity:
    """Convert a TOML string, astropy or pint quantity to an astropy Quantity in SI.

    ``kind`` is a key of :data:`KINDS`. Spin rates given as a frequency
    (``Hz``, ``1/s``) are read as cycles per time (1 Hz = 2 pi rad/s), never as
    radians per time. Raises :class:`QuantityProblem` with a readable message.
    """
    unit, what, example = KINDS[kind]
    q = _read(value, unit, what, example)
    if not q.isscalar:
        raise QuantityProblem(f"expected a single value, got an array {value!r}")
    if kind == "angular_rate" and q.unit.is_equivalent(u.Hz):
        q = (q * u.cycle).to(u.rad / u.s)
    try:
        q = q.to(unit)
    except u.UnitConversionError:
        raise QuantityProblem(
            f"{value!r} is {_physical(q.unit)}, expected {what} such as {example}"
        ) from None
    if not math.isfinite(q.value):
        raise QuantityProblem(f"{value!r} is not a finite number")
    return q


def _read(value, unit: u.UnitBase, what: str, example: str) -> u.Quantity:
    """The quantity a TOML string, astropy or pint quantity stands for (any unit, not yet checked)."""
    if isinstance(value, bool) or isinstance(value, (int, float)):
        raise QuantityProblem(f"{value!r} has no unit; expected {what} such as {example}")
    if isinstance(value, u.Quantity):
        return value
    if _is_pint(value):
        return _from_pint(value, unit, what, example)
    if not isinstance(value, str):
        raise QuantityProblem(f"expected {what} such as {example}, got {type(value).__name__} {value!r}")
    try:
        q = u.Quantity(value)
    except (TypeError, ValueError) as exc:
        raise QuantityProblem(
            f"cannot read {value!r} as a quantity ({exc}); expected {what} such as {example}"
        ) from None
    if q.unit == u.dimensionless_unscaled and not value.strip().replace(".", "").isalpha():
        raise QuantityProblem(f"{value!r} has no unit; expected {what} such as {example}")
    return q


def _physical(unit: u.UnitBase) -> str:
    kind = str(unit.physical_type)
    return f"a quantity in {unit} ({kind})" if kind != "unknown" else f"a quantity in {unit}"


def _is_pint(value) -> bool:
    return type(value).__module__.startswith("pint") and hasattr(value, "magnitude")


def _from_pint(value, unit: u.UnitBase, what: str, example: str) -> u.Quantity:
    """pint -> astropy through the SI value of the expected unit."""

    si = _PINT_SI[unit.to_string()]
    if unit == u.rad / u.s and not any(a in str(value.units) for a in _PINT_ANGLES):
        # pint treats radians as dimensionless: a plain frequency is cycles per time
        si = "1/s"
    try:
        magnitude = value.to(si).magnitude
    except Exception:  # pint's DimensionalityError and friends
        raise QuantityProblem(
            f"{value} has dimension {value.dimensionality}, expected {what} such as {example}"
        ) from None
    if getattr(magnitude, "ndim", 0) != 0:
        raise QuantityProblem(f"expected a single value, got an array {value!r}")
    if si == "1/s":
        return (float(magnitude) * u.cycle / u.s).to(unit)
    return float(magnitude) * unit


_PINT_ANGLES = ("radian", "revolution", "turn", "degree", "cycle", "rpm", "arc")
_PINT_SI = {
    "m": "m",
    "m2 N": "N*m**2",
    "kg / m": "kg/m",
    "Pa": "Pa",
    "m2": "m**2",
    "s": "s",
    "A": "A",
    "T": "T",
    "rad / s": "rad/s",
    "N": "N",
    "rad": "radian",
    "kg": "kg",
    "1 / m3": "1/m**3",
    "V / m": "V/m",
    "S / m": "S/m",
}
