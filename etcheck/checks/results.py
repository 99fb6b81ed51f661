"""The common head of every results file (check, sweep, diagram, damping map).

Results stay plain JSON-able data; this is the one place that stamps them
with the schema version, the etcheck version, the time and the mission echo.
"""

from __future__ import annotations

import datetime as dt

from etcheck import __version__
from etcheck.checks.sections import ResultsHeader
from etcheck.input.mission import Mission

#: version of the results.json layout (bump when a field changes meaning or moves)
SCHEMA_VERSION = 4  # 2: fidelity, plan.route, margin route; 3: the uncertainty probabilities; 4: verdict "outside",
#   model_validity, assumptions, design_limits, flight, natural frequencies under the end tension


def results_header(mission: Mission, schema_version: int = SCHEMA_VERSION) -> ResultsHeader:
    """Schema version, etcheck version, UTC time stamp and the mission as read."""
    return {"schema_version": schema_version, "etcheck_version": __version__,
            "generated": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"), "mission": mission.echo()}
