"""The common head of every results file (check, sweep, diagram, damping map).

This is the one place that stamps results with the schema version, the etcheck version, the time and the
mission echo (a record of :mod:`etcheck.checks.results.sections`; :func:`etcheck.jsonable.to_json` writes it).
"""

from __future__ import annotations

import datetime as dt
from dataclasses import fields

from etcheck import __version__
from etcheck.checks.results.sections import ResultsHeader
from etcheck.input.mission import Mission

#: version of the results.json layout (bump when a field changes meaning or moves)
SCHEMA_VERSION = 4  # 2: fidelity, plan.route, margin route; 3: the uncertainty probabilities; 4: verdict "outside",
#   model_validity, assumptions, design_limits, flight, natural frequencies under the end tension


def results_header(mission: Mission, schema_version: int = SCHEMA_VERSION) -> ResultsHeader:
    """Schema version, etcheck version, UTC time stamp and the mission as read."""
    return ResultsHeader(schema_version=schema_version, etcheck_version=__version__,
                         generated=dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
                         mission=mission.echo())


def header_fields(header: ResultsHeader) -> dict:
    """The header's fields by name (not converted: the head of a record that extends it)."""
    return {f.name: getattr(header, f.name) for f in fields(header)}
