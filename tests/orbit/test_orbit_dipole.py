"""The centred-dipole limit against its closed form.

On a circular polar orbit of radius r under a centred axial dipole with
equatorial field B0 at radius a, the radial field is

    B_r = -2 B0 (a/r)^3 cos(theta)      (theta the geocentric colatitude)

so |B_r| = 2 B0 (a/r)^3 |cos(theta)|, the horizontal field is B0 (a/r)^3
sin(theta), and the largest |B . t| over the orbit, for a tether on the local
vertical or anywhere in a libration cone, is 2 B0 (a/r)^3 (over the poles,
where B is vertical; elsewhere |B| = B0 (a/r)^3 sqrt(1 + 3 cos^2 theta) is
smaller).
"""

from __future__ import annotations

import numpy as np

from etcheck.orbit import CentredDipole, KeplerianElements, OrbitSpec, axial_field_envelope, field_along, trajectory
from etcheck.orbit.elements import R_EARTH

B0 = 30e-6
A = 6371.2e3
H = 600e3
EPOCH = "2027-03-01T00:00:00"


def _polar():
    return KeplerianElements.circular(H, np.pi / 2, raan=0.3, mean_anomaly=0.1, epoch=EPOCH)


def test_radial_field_on_a_polar_orbit_is_the_closed_form():
    t = np.linspace(0.0, 6000.0, 601)
    traj = trajectory(_polar(), EPOCH, t)
    b = field_along(traj, CentredDipole.axial(B0, A))
    r = np.linalg.norm(traj.position, axis=1)
    np.testing.assert_allclose(r, R_EARTH + H, rtol=1e-12)
    cos_theta = traj.position[:, 2] / r
    scale = B0 * (A / r) ** 3
    np.testing.assert_allclose(b.up, -2 * scale * cos_theta, atol=1e-15)
    np.testing.assert_allclose(np.abs(b.up), 2 * scale * np.abs(cos_theta), atol=1e-15)
    horizontal = np.hypot(b.along_track, b.cross_track)
    np.testing.assert_allclose(horizontal, scale * np.sqrt(1 - cos_theta**2), atol=1e-15)
    # the orbit plane contains the GCRS pole, 0.15 deg from the ITRS pole in 2027:
    # the cross-track field is that small fraction of the horizontal field
    assert np.max(np.abs(b.cross_track)) < 5e-3 * scale.max()


def test_envelope_under_an_axial_dipole_reaches_the_pole_value():
    spec = OrbitSpec(_polar(), EPOCH, duration=6000.0, libration_in_plane=np.radians(15), libration_out_of_plane=np.radians(10))
    env = axial_field_envelope(spec, model=CentredDipole.axial(B0, A))
    exact = 2 * B0 * (A / (R_EARTH + H)) ** 3
    assert env.converged and env.step_change < 1e-3
    assert abs(env.worst_nominal - exact) / exact < 1e-3
    assert abs(env.worst - exact) / exact < 1e-3
    assert env.worst <= exact * (1 + 1e-12)
    assert abs(abs(env.worst_latitude) - 90) < 3
