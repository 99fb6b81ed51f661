"""A sweep point is a typed record inside etcheck and JSON only in the cache: the record round-trips, keeps the
layout the cache had, and a record of another layout is refused (the point is then solved again)."""

from __future__ import annotations

import json

import pytest

from etcheck.rod.core.parameters import RodParameters
from etcheck.studies.sweep_point import PointResult, PointStatus, solve_point

SET = RodParameters(P=1e-3, R=21 / 38, Gamma=1 / 1.3, B=0.3, omega=0.25, gamma=0.04375)


@pytest.mark.parametrize("p", [SET, SET.with_(gamma=0.0), SET.with_(P=0.5)])
def test_a_point_round_trips_through_its_json_record(p):
    r = solve_point(p, 1e-8)
    record = json.loads(json.dumps(r.as_dict(), allow_nan=False))
    assert PointResult.from_dict(record) == r
    assert isinstance(r.status, PointStatus) and record["status"] == r.status.value
    assert set(PointResult.ALWAYS) <= set(record)  # the keys the cache files always had
    assert "time_s" not in record and "buckled_stable" not in record  # only where computed


def test_the_outside_point_says_why():
    r = solve_point(SET.with_(P=0.5), 1e-8)
    assert r.status == PointStatus.OUTSIDE and r.stable is None and "P = 0.5" in r.reason


@pytest.mark.parametrize("record", [{"status": "ok"}, {**PointResult().as_dict(), "B_crit": 1.0},
                                    {**PointResult().as_dict(), "status": "fine"}])
def test_a_record_of_another_layout_is_refused(record):
    with pytest.raises((ValueError, TypeError)):
        PointResult.from_dict(record)
