"""Envelope of the IGRF axial field along a LEO orbit: convergence of the
sampling, consistency of the summary with the series."""

from __future__ import annotations

import numpy as np
import pytest

from etcheck.input.orbit_table import parse_orbit
from etcheck.orbit import axial_field_envelope, axial_field_series

ORBIT = {
    "altitude": "500 km",
    "inclination": "51.6 deg",
    "raan": "40 deg",
    "epoch": "2027-03-01T00:00:00",
    "duration": "6 h",
    "libration_in_plane": "10 deg",
    "libration_out_of_plane": "5 deg",
}


@pytest.fixture(scope="module")
def envelope():
    return axial_field_envelope(parse_orbit(ORBIT))


def test_sampling_converges_and_a_finer_grid_agrees(envelope):
    env = envelope
    assert env.converged and env.step_change < 1e-3
    assert env.steps[-1] == env.step and len(env.steps) >= 2
    assert all(b >= a for a, b in zip(env.worst_by_step, env.worst_by_step[1:]))  # nested grids
    spec = parse_orbit(ORBIT)
    n = round(env.duration / (env.step / 4)) + 1
    fine = axial_field_series(spec, np.linspace(0.0, env.duration, n))
    ref = fine.axial_worst.max()
    assert ref >= env.worst * (1 - 1e-12)
    assert (ref - env.worst) / ref < 1e-3


def test_summary_is_consistent_with_the_series(envelope):
    env, s = envelope, envelope.series
    n = len(s)
    assert np.all(np.diff(s.time) > 0) and s.time[0] == 0 and s.time[-1] == pytest.approx(env.duration)
    np.testing.assert_allclose(np.diff(s.time), env.step)
    for name in ("latitude", "longitude", "altitude", "b_up", "b_along", "b_cross", "axial_nominal", "axial_worst"):
        assert getattr(s, name).shape == (n,)
    np.testing.assert_allclose(s.b_magnitude, np.sqrt(s.b_up**2 + s.b_along**2 + s.b_cross**2), rtol=1e-12)
    assert np.all(s.axial_worst >= np.abs(s.axial_nominal) - 1e-18)
    assert np.all(s.axial_worst <= s.b_magnitude * (1 + 1e-12))
    k = int(np.argmax(s.axial_worst))
    assert env.worst == s.axial_worst[k] and env.worst_time == s.time[k]
    assert env.worst_latitude == s.latitude[k] and env.worst_longitude == s.longitude[k]
    assert env.percentiles[-1] == pytest.approx(env.worst) and env.percentiles_nominal[-1] == pytest.approx(env.worst_nominal)
    assert env.histogram_counts.sum() == n and env.histogram_edges[-1] == pytest.approx(env.worst)
    # a LEO orbit at 51.6 deg: |B| between about 18 and 60 uT; latitudes within the inclination
    assert 18e-6 < s.b_magnitude.min() and s.b_magnitude.max() < 60e-6
    assert np.abs(s.latitude).max() < 51.8
    assert 480e3 < s.altitude.min() and s.altitude.max() < 530e3


def test_a_given_step_is_used_and_its_change_reported():
    orbit = dict(ORBIT, duration="2 h", step="20 s")
    env = axial_field_envelope(parse_orbit(orbit))
    assert env.step == pytest.approx(20.0) and env.steps == (env.step,)
    assert 0 <= env.step_change < 1e-2
    assert len(env.series) == 361
