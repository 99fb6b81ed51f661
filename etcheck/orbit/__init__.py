"""Orbit -> axial field: the geomagnetic field along the tether from
the orbit and the attitude, instead of a given ``axial_field``.

Entry point::

    from etcheck.input.orbit_table import parse_orbit
    from etcheck.orbit import axial_field_envelope
    spec = parse_orbit({"altitude": "500 km", "inclination": "51.6 deg", "epoch": "2027-03-01T00:00:00",
                        "libration_in_plane": "10 deg", "libration_out_of_plane": "5 deg"})
    env = axial_field_envelope(spec)
    env.worst        # T: worst |B . t| over the day and the libration set
    env.series       # time, lat, lon, alt, field components, axial nominal and worst

Modules: ``elements`` (orbit descriptions, propagation, ITRS trajectory),
``frames`` (time scales, GCRS/TEME -> ITRS, geodetic), ``field`` (IGRF through
ppigrf, centred dipole, local components), ``attitude`` (libration set and
the exact worst case), ``envelope`` (series, envelope, convergence), ``spec``
(what to evaluate, as a value). SI units throughout; degrees only where named.
Nothing here reads a mission file or imports the input layer.
"""

from etcheck.orbit.attitude import axial_component, tether_direction, worst_axial
from etcheck.orbit.elements import KeplerianElements, Trajectory, TwoLineElements, trajectory
from etcheck.orbit.envelope import AxialFieldEnvelope, AxialFieldSeries, axial_field_envelope, axial_field_series
from etcheck.orbit.field import CentredDipole, LocalField, field_along, igrf_itrs, igrf_validity
from etcheck.orbit.spec import OrbitSpec

__all__ = [
    "AxialFieldEnvelope",
    "AxialFieldSeries",
    "CentredDipole",
    "KeplerianElements",
    "LocalField",
    "OrbitSpec",
    "Trajectory",
    "TwoLineElements",
    "axial_component",
    "axial_field_envelope",
    "axial_field_series",
    "field_along",
    "igrf_itrs",
    "igrf_validity",
    "tether_direction",
    "trajectory",
    "worst_axial",
]
