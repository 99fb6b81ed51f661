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

# Lazy (PEP 562): reading a mission's [orbit] table (etcheck.orbit.spec, .models, .elements, .frames) must not
# load what evaluates the field (ppigrf and pandas, SGP4)
_EXPORTS = {
    "axial_component": "attitude", "tether_direction": "attitude", "worst_axial": "attitude",
    "KeplerianElements": "elements", "Trajectory": "elements", "TwoLineElements": "elements",
    "trajectory": "elements",
    "AxialFieldEnvelope": "envelope", "AxialFieldSeries": "envelope", "axial_field_envelope": "envelope",
    "axial_field_series": "envelope",
    "CentredDipole": "field", "LocalField": "field", "field_along": "field", "igrf_itrs": "field",
    "igrf_validity": "models",
    "OrbitSpec": "spec",
}


def __getattr__(name: str):
    if name in _EXPORTS:
        import importlib

        return getattr(importlib.import_module(f"etcheck.orbit.{_EXPORTS[name]}"), name)
    raise AttributeError(f"module 'etcheck.orbit' has no attribute {name!r}")


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
