"""Sweep axes: which mission quantity varies, over which values, in which units.

An axis is written ``START:STOP:POINTS[:log]`` on the command line
(``--length 50m:5km:40:log``) or as an inline table in the mission's
``[sweep]`` table (``length = { from = "50 m", to = "5 km", points = 40,
spacing = "log" }``). Values are converted to SI at this edge; the sweep
works with floats.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from etcheck.errors import MissionError
from etcheck.input.units import QuantityProblem, to_quantity


class AxisKind(NamedTuple):
    """What a sweep axis varies: ``kind`` of :data:`etcheck.input.units.KINDS`, the SI unit of its values, the
    display unit, the factor SI -> display and a label."""

    kind: str
    si_unit: str
    unit: str
    to_display: float
    label: str


#: axis name -> what it varies
AXES = {
    "length": AxisKind("length", "m", "m", 1.0, "tether length"),
    "spin_rate": AxisKind("angular_rate", "rad/s", "rpm", 60.0 / (2.0 * math.pi), "spin rate"),
    "current": AxisKind("current", "A", "A", 1.0, "current"),
    "axial_field": AxisKind("field", "T", "uT", 1e6, "axial field"),
    "end_tension": AxisKind("force", "N", "N", 1.0, "end tension"),
    # orbit axes (need the mission's [orbit] table): the axial field of each point is the worst case over that orbit
    "altitude": AxisKind("length", "m", "km", 1e-3, "orbit altitude"),
    "inclination": AxisKind("angle", "rad", "deg", 180.0 / math.pi, "orbit inclination"),
}
#: command-line option -> axis name
OPTIONS = {"length": "length", "spin": "spin_rate", "current": "current", "field": "axial_field",
           "tension": "end_tension", "altitude": "altitude", "inclination": "inclination"}
MAX_POINTS = 400
#: Lowest orbit altitude (m) of an altitude axis (etcheck.orbit.spec.MIN_ALTITUDE).
MIN_ORBIT_ALTITUDE = 150e3


@dataclass(frozen=True)
class Axis:
    """One swept quantity: ``values`` in SI (``si_unit``), ascending."""

    name: str
    start: float
    stop: float
    points: int
    spacing: str  # "linear" or "log"

    @property
    def values(self) -> np.ndarray:
        if self.spacing == "log":
            return np.geomspace(self.start, self.stop, self.points)
        return np.linspace(self.start, self.stop, self.points)

    si_unit = property(lambda self: AXES[self.name].si_unit, doc="SI unit of ``values``")
    unit = property(lambda self: AXES[self.name].unit, doc="Display unit (rpm for spin rates, uT for fields)")
    to_display = property(lambda self: AXES[self.name].to_display, doc="Factor SI -> display unit")
    label = property(lambda self: AXES[self.name].label, doc="What the axis varies, in words")

    def as_dict(self) -> dict:
        return {"name": self.name, "label": self.label, "si_unit": self.si_unit, "unit": self.unit,
                "start": self.start, "stop": self.stop, "points": self.points, "spacing": self.spacing,
                "values": self.values.tolist(), "display_values": (self.values * self.to_display).tolist()}


def make_axis(name: str, start, stop, points, spacing: str, source: str, where: str) -> Axis:
    """Validate one axis; errors name ``where`` (a field or an option)."""
    if name not in AXES:
        raise MissionError(source, where, f"cannot sweep {name!r}", f"sweep any of {', '.join(AXES)}")
    try:
        lo, hi = (float(to_quantity(v, AXES[name].kind).value) for v in (start, stop))
    except QuantityProblem as exc:
        raise MissionError(source, where, str(exc)) from None
    if isinstance(points, bool) or not isinstance(points, int) or not 2 <= points <= MAX_POINTS:
        raise MissionError(source, where, f"points must be a whole number in [2, {MAX_POINTS}], got {points!r}")
    if spacing not in ("linear", "log"):
        raise MissionError(source, where, f"unknown spacing {spacing!r}", 'use "linear" or "log"')
    _check_span(name, start, stop, lo, hi, spacing, source, where)
    return Axis(name, lo, hi, points, spacing)


def _check_span(name: str, start, stop, lo: float, hi: float, spacing: str, source: str, where: str) -> None:
    """START < STOP (SI ``lo``, ``hi``) within what the swept quantity and the spacing allow."""
    problem, fix = "", ""
    if not lo < hi:
        problem, fix = f"start {start!r} must be below stop {stop!r}", "write START:STOP with START < STOP"
    elif lo < 0 or (name == "length" and lo <= 0):
        problem = f"start {start!r} must be {'positive' if name == 'length' else 'zero or positive'}"
    elif spacing == "log" and lo <= 0:
        problem, fix = "log spacing needs a positive start", "start above zero, or use linear spacing"
    elif name == "altitude" and lo < MIN_ORBIT_ALTITUDE:
        problem = f"start {start!r} is below {MIN_ORBIT_ALTITUDE / 1e3:.0f} km: the atmosphere would decay the orbit"
        fix = "sweep altitudes of at least 150 km above the equatorial radius"
    elif name == "inclination" and hi > math.pi * (1 + 1e-15):
        problem, fix = f"stop {stop!r} is above 180 deg", "sweep inclinations within 0-180 deg"
    if problem:
        raise MissionError(source, where, problem, fix)


def parse_option(option: str, text: str) -> Axis:
    """``--length 50m:5km:40[:log]`` -> Axis (errors name the option)."""
    where = f"--{option}"
    parts = [p.strip() for p in text.split(":")]
    if len(parts) not in (3, 4):
        raise MissionError("command line", where, f"expected START:STOP:POINTS[:log|:linear], got {text!r}",
                           f"e.g. {where} {_EXAMPLES[OPTIONS[option]]}")
    try:
        points = int(parts[2])
    except ValueError:
        raise MissionError("command line", where, f"POINTS must be a whole number, got {parts[2]!r}") from None
    spacing = {"log": "log", "lin": "linear", "linear": "linear"}.get(parts[3].lower(), parts[3]) if len(parts) == 4 else "linear"
    return make_axis(OPTIONS[option], parts[0], parts[1], points, spacing, "command line", where)


def parse_table(table: dict, source: str) -> tuple[Axis, ...]:
    """The mission's ``[sweep]`` table -> axes (errors name ``sweep.FIELD``)."""
    axes = []
    for name, spec in table.items():
        where = f"sweep.{name}"
        if name not in AXES:
            raise MissionError(source, where, "unknown sweep axis", f"sweep any of {', '.join(AXES)}")
        if not isinstance(spec, dict):
            raise MissionError(source, where, "expected an inline table",
                               f'e.g. {name} = {{ from = "...", to = "...", points = 40, spacing = "log" }}')
        unknown = set(spec) - {"from", "to", "points", "spacing"}
        if unknown or not {"from", "to", "points"} <= set(spec):
            raise MissionError(source, where, "needs from, to, points (and optionally spacing)",
                               f"unexpected: {', '.join(sorted(unknown))}" if unknown else "")
        axes.append(make_axis(name, spec["from"], spec["to"], spec["points"], spec.get("spacing", "linear"),
                              source, where))
    return check_axes(tuple(axes), source)


def check_axes(axes: tuple[Axis, ...], source: str) -> tuple[Axis, ...]:
    if not 1 <= len(axes) <= 2:
        raise MissionError(source, "sweep", f"sweep one or two quantities, got {len(axes)}",
                           "e.g. --length 50m:5km:40:log --spin 0rpm:2rpm:40")
    if len({a.name for a in axes}) != len(axes):
        raise MissionError(source, "sweep", "the same quantity is swept twice")
    return axes


_EXAMPLES = {"length": "50m:5km:40:log", "spin_rate": "0rpm:2rpm:40", "current": "0.1A:5A:30",
             "axial_field": "20uT:70uT:20", "end_tension": "0N:1N:20", "altitude": "300km:1500km:20",
             "inclination": "0deg:98deg:20"}
