"""The current along the tether: ``[operation] current_profile`` (the unit edge for it).

A bare tether collects its current from the plasma along its length, so the current grows from
near zero at one end to its largest value near the other; an insulated one carries one current.
The mission gives I(s) / I_max, with ``current`` the largest current I_max:

* as points, piecewise linear between them, at fractions of the length from the lower end::

    current_profile = { at = [0, 0.3, 1], fraction = [0, 0.8, 1] }

* or from orbital-motion-limited (OML) collection by the bare tether itself (Sanmartín,
  Martínez-Sánchez & Ahedo, "Bare wire anodes for electrodynamic tethers", J. Propulsion and Power
  9(3), 353-360, 1993)::

    current_profile = "OML"
    [operation.collection]
    plasma_density = "1e11 m-3"       # electron density of the ambient plasma N_e
    motional_field = "0.15 V/m"       # E_m = (v x B) . t along the tether
    conductivity = "3.5e7 S/m"        # of the conductor (aluminium 3.5e7 S/m)
    perimeter = "50 mm"               # of the cross-section: 2 (w + h) for a tape, pi d for a wire
    conductive_area = "1 mm2"         # default: tether.cross_section_area
    anode_end = "upper"               # where electrons are collected: "upper" (deorbit, drag mode) or "lower"

**The OML model** (every assumption it makes is stated in the check's notes and report). A thin
bare conductor (radius, or a quarter of a tape's width, below the Debye length and the electron
thermal gyroradius) at a positive bias dV to the plasma collects the orbital-motion-limited
electron current per length e N_e (p / pi) sqrt(2 e dV / m_e); the bias falls along the tether
from its anodic end as the motional field drives it and the ohmic drop I / (sigma A) returns it:

    dI/dx = e N_e (p / pi) sqrt(2 e dV / m_e),    d(dV)/dx = I / (sigma A) - E_m,
    I(0) = 0 at the anodic end,                  dV = 0 at the cathodic end (x = L),

x measured from the anodic end. With i = I / (sigma E_m A), phi = dV / (E_m L*), xi = x / L* this is
di/dxi = (3/4) sqrt(phi), dphi/dxi = i - 1 with the characteristic length

    L* = [9 pi^2 m_e sigma^2 A^2 E_m / (32 e^3 N_e^2 p^2)]^(1/3)

(the paper's 9 pi^2 m_e sigma^2 h^2 E_m / (128 e^3 N_e^2) for a tape of thickness h, where
A / p = h / 2). The shape I(x) / I(L) depends on L / L* alone; the largest current sigma E_m A i(L / L*)
is reported beside the mission's ``current`` (which the check uses). Assumed: an unmagnetised,
collisionless, stationary plasma of uniform density and motional field along the tether; the
whole tether anodic, ending at an ideal contactor (hollow cathode) that holds the cathodic end at the
plasma potential, with no load and no cathode drop (the tether short-circuited: the largest current);
ion collection, secondary and photo-emission and the tether's own field neglected.

Pure functions of SI floats; :func:`parse_current_profile` is the unit edge used by
:mod:`etcheck.input.mission`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from etcheck.errors import MissionError
from etcheck.input.echo import CollectionEcho, CurrentProfileEcho
from etcheck.input.units import QuantityProblem, to_quantity
from etcheck.rod.core.profile import Profile

__all__ = ["CurrentProfile", "OMLCollection", "oml_current", "parse_current_profile"]

#: Electron charge [C] and mass [kg] (CODATA 2018).
E_CHARGE = 1.602176634e-19
M_ELECTRON = 9.1093837015e-31
#: The OML collection table: key -> quantity kind (``None``: text).
COLLECTION = {"plasma_density": "number_density", "motional_field": "electric_field", "conductivity": "conductivity",
              "perimeter": "length", "conductive_area": "area", "anode_end": None}
#: Breaks of the OML profile's pieces from its cathodic end (fractions of the length): the current there
#: goes as 1 - c x^(3/2), which pieces shrinking towards that end represent to 1e-9.
_OML_BREAKS = (1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.4)


@dataclass(frozen=True)
class OMLCollection:
    """Orbital-motion-limited collection along a bare tether (SI: m^-3, V/m, S/m, m, m^2, m, A)."""

    plasma_density: float
    motional_field: float
    conductivity: float
    perimeter: float
    conductive_area: float
    length: float
    anode_end: str = "upper"

    @property
    def characteristic_length(self) -> float:
        """L* [m] (module docstring)."""
        return (9 * math.pi**2 * M_ELECTRON * self.conductivity**2 * self.conductive_area**2 * self.motional_field
                / (32 * E_CHARGE**3 * self.plasma_density**2 * self.perimeter**2)) ** (1.0 / 3.0)

    @property
    def short_circuit_current(self) -> float:
        """sigma E_m A [A]: the current an infinitely long tether would approach."""
        return self.conductivity * self.motional_field * self.conductive_area


def oml_current(xi_L: float):
    """The dimensionless OML solution on a tether of length xi_L = L / L*: (i, phi_A) with i(xi) the continuous
    current i = I / (sigma E_m A) at xi from the anodic end (DOP853's dense output) and phi_A the anodic bias
    dV / (E_m L*) that puts the zero bias at the cathodic end (shooting, Brent on phi_A)."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    def rhs(_, y):
        return [0.75 * math.sqrt(max(y[1], 0.0)), y[0] - 1.0]

    def solve(phi_a: float, dense: bool = False):
        return solve_ivp(rhs, (0.0, xi_L), [0.0, phi_a], rtol=1e-12, atol=1e-14 * max(phi_a, 1e-300),
                         method="DOP853", dense_output=dense)

    def end_bias(phi_a: float) -> float:
        return float(solve(phi_a).y[1, -1])

    lo, hi = 0.5 * xi_L, 2.0 * xi_L + 1.0
    while end_bias(hi) <= 0:
        hi *= 2.0
    while end_bias(lo) >= 0:
        lo *= 0.5
    phi_a = brentq(end_bias, lo, hi, xtol=1e-15 * hi, rtol=1e-14)
    sol = solve(phi_a, dense=True)
    return (lambda x: sol.sol(np.asarray(x, dtype=float))[0]), phi_a


@dataclass(frozen=True)
class CurrentProfile:
    """I(s) / I_max along the tether: ``profile`` as a dimensionless :class:`~etcheck.rod.straight.varying.profiles.Profile`
    of s, the fraction of the length from the lower end; ``at``, ``fraction`` the points given (or samples of
    the OML profile); ``collection`` the OML inputs (None for points); ``oml_current`` [A] the largest current
    OML predicts (None for points); ``notes`` what was assumed."""

    model: str
    profile: Profile
    at: tuple[float, ...]
    fraction: tuple[float, ...]
    collection: OMLCollection | None = None
    oml_current: float | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def uniform(self) -> bool:
        return self.profile.uniform_value is not None

    def echo(self) -> CurrentProfileEcho:
        """The profile as read, for the results."""
        c = self.collection
        coll = None if c is None else CollectionEcho(
            plasma_density_per_m3=c.plasma_density, motional_field_V_per_m=c.motional_field,
            conductivity_S_per_m=c.conductivity, perimeter_m=c.perimeter,
            conductive_area_m2=c.conductive_area, anode_end=c.anode_end,
            characteristic_length_m=c.characteristic_length, length_ratio=c.length / c.characteristic_length,
            short_circuit_current_A=c.short_circuit_current, largest_current_A=self.oml_current or 0.0,
        )
        return CurrentProfileEcho(model=self.model, at=self.at, fraction=self.fraction, collection=coll,
                                  notes=self.notes)


def parse_current_profile(operation: dict, tether: dict, length: float, cross_section_area: float | None,
                          current: float, source: str) -> CurrentProfile | None:
    """``operation.current_profile`` (and ``operation.collection``) -> :class:`CurrentProfile`; None without
    one (a uniform current). ``length`` [m], ``cross_section_area`` [m^2] or None, ``current`` [A] the
    mission's largest current. Raises MissionError naming the field."""
    del tether
    value = operation.get("current_profile")
    if "collection" in operation and value != "OML":
        raise MissionError(source, "operation.collection", "given without current_profile = \"OML\"",
                           "the collection table is read only for the orbital-motion-limited profile")
    if value is None:
        return None
    if value == "OML":
        return _oml(operation.get("collection"), length, cross_section_area, current, source)
    if isinstance(value, str):
        raise MissionError(source, "operation.current_profile", f"unknown profile {value!r}",
                           'use "OML" or a table { at = [0, 0.3, 1], fraction = [0, 0.8, 1] }')
    if not isinstance(value, dict):
        raise MissionError(source, "operation.current_profile", f"expected a table or \"OML\", got {value!r}",
                           "e.g. current_profile = { at = [0, 0.3, 1], fraction = [0, 0.8, 1] }")
    return _points(value, source)


def _numbers(value: Any, fld: str, source: str) -> np.ndarray:
    if not isinstance(value, list) or len(value) < 2:
        raise MissionError(source, fld, f"expected a list of at least two plain numbers, got {value!r}")
    if any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in value):
        raise MissionError(source, fld, f"expected plain numbers (fractions), got {value!r}")
    out = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(out)):
        raise MissionError(source, fld, f"must be finite numbers, got {value!r}")
    return out


def _points(value: dict, source: str) -> CurrentProfile:
    fld = "operation.current_profile"
    unknown = set(value) - {"at", "fraction"}
    if unknown:
        raise MissionError(source, f"{fld}.{sorted(unknown)[0]}", "unknown key", "the keys are at and fraction")
    for key in ("at", "fraction"):
        if key not in value:
            raise MissionError(source, f"{fld}.{key}", "missing", "e.g. { at = [0, 0.3, 1], fraction = [0, 0.8, 1] }")
    at = _numbers(value["at"], f"{fld}.at", source)
    frac = _numbers(value["fraction"], f"{fld}.fraction", source)
    if at.size != frac.size:
        raise MissionError(source, f"{fld}.fraction", f"{frac.size} fractions for {at.size} points of at",
                           "give one fraction per point")
    if at[0] != 0.0 or at[-1] != 1.0 or np.any(np.diff(at) <= 0):
        raise MissionError(source, f"{fld}.at", f"must rise strictly from 0 (the lower end) to 1 (the upper end), "
                           f"got {value['at']!r}", "fractions of the length measured from the lower end")
    if np.any(frac < 0) or np.any(frac > 1):
        raise MissionError(source, f"{fld}.fraction", f"fractions of the largest current lie in [0, 1], got "
                           f"{value['fraction']!r}")
    if frac.max() != 1.0:
        raise MissionError(source, f"{fld}.fraction", f"the largest fraction is {frac.max():g}, not 1",
                           "operation.current is the largest current along the tether: scale the fractions to it")
    profile = Profile.piecewise_linear(at, frac)
    note = ("current along the tether: I(s) / I_max piecewise linear through "
            + ", ".join(f"{f:g} at {a:g}" for a, f in zip(at, frac))
            + " (s from the lower end, as a fraction of the length; I_max = operation.current)")
    return CurrentProfile("given", profile, tuple(at.tolist()), tuple(frac.tolist()), notes=(note,))


def _collection_value(tbl: dict, key: str, source: str) -> float:
    try:
        q = to_quantity(tbl[key], COLLECTION[key])
    except QuantityProblem as exc:
        raise MissionError(source, f"operation.collection.{key}", str(exc)) from None
    if not q.value > 0:
        raise MissionError(source, f"operation.collection.{key}", f"must be positive, got {tbl[key]!r}")
    return float(q.value)


def _oml(tbl: Any, length: float, area: float | None, current: float, source: str) -> CurrentProfile:
    if not isinstance(tbl, dict):
        raise MissionError(source, "operation.collection", "missing: current_profile = \"OML\" needs the plasma and "
                           "the conductor", 'add [operation.collection] with plasma_density = "1e11 m-3", '
                           'motional_field = "0.15 V/m", conductivity = "3.5e7 S/m", perimeter = "50 mm"')
    for key in tbl:
        if key not in COLLECTION:
            raise MissionError(source, f"operation.collection.{key}", "unknown field",
                               f"fields of [operation.collection] are {', '.join(COLLECTION)}")
    for key in ("plasma_density", "motional_field", "conductivity", "perimeter"):
        if key not in tbl:
            raise MissionError(source, f"operation.collection.{key}", "missing required field")
    values = {key: _collection_value(tbl, key, source) for key in COLLECTION if key in tbl and COLLECTION[key]}
    if "conductive_area" not in values:
        if area is None:
            raise MissionError(source, "operation.collection.conductive_area", "missing (and no "
                               "tether.cross_section_area to take it from)", 'e.g. conductive_area = "1 mm2"')
        values["conductive_area"] = area
    anode = tbl.get("anode_end", "upper")
    if anode not in ("upper", "lower"):
        raise MissionError(source, "operation.collection.anode_end", f"expected \"upper\" or \"lower\", got {anode!r}")
    c = OMLCollection(length=length, anode_end=anode, **values)
    return _oml_profile(c, current)


def _oml_profile(c: OMLCollection, current: float) -> CurrentProfile:
    """The OML profile on the tether as a Profile of s from the lower end, and what it assumed."""
    xi_L = c.length / c.characteristic_length
    i, _ = oml_current(xi_L)
    i_max = float(i(xi_L))

    def shape(s):  # s from the lower end; the distance from the anodic end is 1 - s for an upper anode
        s = np.clip(np.asarray(s, dtype=float), 0.0, 1.0)
        return i(xi_L * (s if c.anode_end == "lower" else 1.0 - s)) / i_max

    cathode_breaks = (b if c.anode_end == "upper" else 1.0 - b for b in _OML_BREAKS)
    profile = Profile.from_function(shape, tuple(sorted({0.0, 1.0, *cathode_breaks})), degree=16)
    at = np.linspace(0.0, 1.0, 33)
    largest = c.short_circuit_current * i_max
    notes = (
        f"current along the tether from orbital-motion-limited collection (Sanmartín, Martínez-Sánchez & Ahedo "
        f"1993): plasma density {c.plasma_density:.3g} m^-3, motional field {c.motional_field:.3g} V/m, "
        f"conductivity {c.conductivity:.3g} S/m, perimeter {c.perimeter:.3g} m, conductive area "
        f"{c.conductive_area:.3g} m^2; characteristic length L* = {c.characteristic_length:.4g} m, L/L* = "
        f"{xi_L:.4g}; the current rises from 0 at the {c.anode_end} (anodic) end to its largest value at the other",
        "OML collection assumes a thin bare conductor (radius, or a quarter of a tape's width, below the Debye length "
        "and the electron gyroradius) in an unmagnetised, collisionless, stationary plasma of uniform density and "
        "motional field along the tether; the whole tether anodic, its cathodic end held at the plasma potential by "
        "an ideal contactor with no load (short circuit: the largest current); ion collection and electron emission "
        "neglected",
        f"OML predicts a largest current of {largest:.4g} A; the check uses operation.current = {current:.4g} A as the "
        "largest current, with the OML shape",
    )
    return CurrentProfile("orbital-motion-limited collection", profile, tuple(at.tolist()),
                          tuple(float(v) for v in profile(at)), c, largest, notes)
