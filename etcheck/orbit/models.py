"""Which IGRF generations etcheck evaluates, and the span each covers: read from the coefficient files that
``ppigrf`` ships without importing it (or pandas), so that reading a mission's ``[orbit]`` table checks its
window against the model and loads nothing that evaluates the field (:mod:`etcheck.orbit.field` does).
"""

from __future__ import annotations

import calendar
import importlib.util
from datetime import datetime, timedelta
from pathlib import Path

from astropy.time import Time

from etcheck.orbit import frames

#: IGRF generation -> its coefficient file in the ppigrf package
COEFFICIENT_FILES = {"IGRF-14": "IGRF14.shc", "IGRF-13": "IGRF13.shc"}
DEFAULT_MODEL = "IGRF-14"


def coefficient_file(model: str) -> str:
    """The path of the model's coefficient file (found without importing ppigrf)."""
    spec = importlib.util.find_spec("ppigrf")
    return str(Path(next(iter(spec.submodule_search_locations))) / COEFFICIENT_FILES[model])


def igrf_validity(model: str = DEFAULT_MODEL) -> tuple[Time, Time]:
    """First and last instant covered by the model's coefficient file (UTC): the first and last of the times
    (decimal years) its header lists, as ppigrf reads them."""
    times = _times(coefficient_file(model))
    return frames.parse_utc(_datetime(times[0])), frames.parse_utc(_datetime(times[-1]))


def _times(path: str) -> list[float]:
    """The decimal years of an .shc file: the line after its parameters, past the comments."""
    with open(path) as f:
        lines = (line for line in f if not line.startswith("#"))
        next(lines)  # N_MIN N_MAX N_TIMES SPLINE_ORDER N_STEPS
        return [float(x) for x in next(lines).split()]


def _datetime(year: float) -> datetime:
    """A decimal year as a date and time (the fraction of that year's days, as ppigrf converts it)."""
    whole = int(year)
    return datetime(whole, 1, 1) + timedelta(days=(year - whole) * (365 + calendar.isleap(whole)))


__all__ = ["COEFFICIENT_FILES", "DEFAULT_MODEL", "coefficient_file", "igrf_validity"]
