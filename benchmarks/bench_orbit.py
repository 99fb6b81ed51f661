"""Orbit -> axial field timing (a measurement, not a test).

1. One day of a LEO orbit (500 km, 51.6 deg, libration 10 deg / 5 deg):
   the whole envelope with the step chosen by convergence (steps tried, the
   worst case at each, the converged step and its change), and one evaluation
   at fixed steps split into propagation + rotation, IGRF and the worst case.
2. The Earth-fixed rotation: ours (erfa, UT1 = UTC) against astropy's
   GCRS -> ITRS (IERS table extrapolated for 2027, offline) and against a
   GMST-only rotation, for 10^4 samples: time and largest position difference.
Run:  python benchmarks/bench_orbit.py
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from etcheck.input.orbit_table import parse_orbit
from etcheck.orbit import axial_field_envelope, field_along, trajectory, worst_axial
from etcheck.orbit.elements import kepler_state
from etcheck.orbit.frames import gcrs_to_itrs, parse_utc, rotate

LEO = {
    "altitude": "500 km",
    "inclination": "51.6 deg",
    "epoch": "2027-03-01T00:00:00",
    "duration": "1 d",
    "libration_in_plane": "10 deg",
    "libration_out_of_plane": "5 deg",
}


def _best(fn, repeat=3):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def envelope():
    dt, env = _best(lambda: axial_field_envelope(parse_orbit(LEO)))
    print("1. one day, 500 km, 51.6 deg, libration 10/5 deg, IGRF-14, 2027-03-01")
    print(f"   envelope with converged step: {dt:.3f} s, {len(env.series)} samples")
    for h, w in zip(env.steps, env.worst_by_step):
        print(f"     step {h:6.2f} s: worst {w * 1e6:.4f} uT")
    print(f"   converged step {env.step:g} s, change {env.step_change:.2e} (tolerance {env.tolerance:g})")
    print(f"   worst {env.worst * 1e6:.3f} uT (nominal vertical {env.worst_nominal * 1e6:.3f} uT) at {env.worst_utc}, "
          f"lat {env.worst_latitude:.2f}, lon {env.worst_longitude:.2f}, alt {env.worst_altitude / 1e3:.1f} km")
    spec = parse_orbit(LEO)
    for step in (30.0, 10.0):
        t = np.arange(0.0, spec.duration + 1e-9, step)
        t_traj, traj = _best(lambda t=t: trajectory(spec.orbit, spec.start, t))
        t_field, b = _best(lambda traj=traj: field_along(traj))
        t_att, _ = _best(lambda b=b: worst_axial(b.up, b.along_track, b.cross_track, 0.17, 0.087))
        print(f"   fixed step {step:g} s ({t.size} samples): propagation+rotation {t_traj * 1e3:.1f} ms, "
              f"IGRF {t_field * 1e3:.1f} ms, worst over cone {t_att * 1e3:.1f} ms")


def rotation():
    import astropy.units as u
    from astropy.coordinates import GCRS, ITRS, CartesianRepresentation
    from astropy.utils import iers

    spec = parse_orbit(LEO)
    n = 10_000
    t = np.linspace(0.0, 86400.0, n)
    start = parse_utc(spec.start)
    r, _ = kepler_state(spec.orbit, t)
    t_ours, ours = _best(lambda: rotate(gcrs_to_itrs(start, t), r))
    obstime = start + t * u.s

    def astropy_itrs():
        with iers.conf.set_temp("auto_download", False), iers.conf.set_temp("auto_max_age", None), \
                iers.conf.set_temp("iers_degraded_accuracy", "ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            c = GCRS(CartesianRepresentation(r.T, unit=u.m), obstime=obstime).transform_to(ITRS(obstime=obstime))
            return c.cartesian.xyz.to_value(u.m).T

    t_astropy, ref = _best(astropy_itrs, repeat=1)
    gmst = obstime.sidereal_time("mean", longitude=0).to_value(u.rad)
    c, s = np.cos(gmst), np.sin(gmst)
    gmst_only = np.stack([c * r[:, 0] + s * r[:, 1], -s * r[:, 0] + c * r[:, 1], r[:, 2]], axis=1)
    diff = lambda a: np.max(np.linalg.norm(a - ref, axis=1))
    print(f"2. GCRS -> ITRS, {n} samples over a day, 2027")
    print(f"   ours (erfa C2I per half day + ERA, UT1 = UTC): {t_ours * 1e3:.2f} ms, {diff(ours):.0f} m from astropy")
    print(f"   astropy GCRS -> ITRS (IERS extrapolated):     {t_astropy * 1e3:.0f} ms")
    print(f"   GMST rotation only (no precession-nutation):   {diff(gmst_only) / 1e3:.1f} km from astropy")


if __name__ == "__main__":
    envelope()
    rotation()
