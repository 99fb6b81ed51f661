"""Sweep data as files: CSV (one row per point, units in the header) and NetCDF
(labelled arrays via xarray, units in the attributes), and reading them back
with units (astropy Quantities / an xarray Dataset).

Neither file holds a timestamp or a timing, so an interrupted-and-resumed
sweep writes byte-identical data to an uninterrupted one.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

#: grid field -> (NetCDF/CSV name, unit, description)
FIELDS = {
    "load_N_per_m": ("load", "N/m", "magnetic load per length |I B0| at the point"),
    "critical_load_N_per_m": ("critical_load", "N/m", "first I B0 at which the straight tether loses stability "
                              "(at the point's spin and tension)"),
    "load_margin": ("load_margin", "", "critical_load / load (inf: no load)"),
    "load_error": ("load_error", "", "relative numerical error of critical_load (two resolutions)"),
    "spin_rpm": ("spin", "rpm", "spin rate at the point"),
    "critical_spin_rpm": ("critical_spin", "rpm", "first spin rate at which the straight tether loses stability "
                          "(at the point's load and tension)"),
    "spin_margin": ("spin_margin", "", "critical_spin / spin (inf: no spin)"),
    "spin_error": ("spin_error", "", "relative numerical error of critical_spin"),
    "critical_spin_at_rest_rpm": ("critical_spin_without_load", "rpm", "critical spin rate with no magnetic load"),
    "B": ("B", "", "dimensionless load (arXiv:0810.3668 eq. (36))"),
    "omega": ("omega", "", "dimensionless spin"),
    "T": ("T", "", "dimensionless end tension"),
    "gamma": ("gamma", "", "dimensionless Kelvin-Voigt damping"),
    "P": ("P", "", "rotary inertia ratio"),
    "N": ("resolution", "", "Chebyshev resolution that met the tolerance (0: rung 0)"),
    "buckled_deflection_m": ("buckled_deflection", "m", "maximum lateral deflection of the coiled tether on b1 "
                             "(sweeps with --buckled, straight-unstable points)"),
    "bow_over_length": ("bow_over_length", "", "bow at mid-span under the lateral Lorentz load / length (the model's "
                        "limit: bow_limit)"),
}
TEXT = ("status", "region", "verdict", "model", "reason")
UNLIMITED = ("load_margin", "spin_margin")


def grid_array(results: dict, field: str) -> np.ndarray:
    """Grid field as a float array: NaN = no value, inf = unlimited margin."""
    g = results["grid"]
    a = np.array(g[field], dtype=object)
    out = np.where(a == None, np.nan, a).astype(float)  # noqa: E711 (element-wise)
    if field in UNLIMITED:
        ok = np.array(g["status"], dtype=object) == "ok"
        out[ok & np.isnan(out)] = np.inf
    return out


def _axis_columns(results: dict) -> list[tuple[str, np.ndarray]]:
    cols = []
    for a in results["axes"]:
        cols.append((f"{a['name']} [{a['si_unit']}]", np.asarray(a["values"])))
        if a["unit"] != a["si_unit"]:
            cols.append((f"{a['name']} [{a['unit']}]", np.asarray(a["display_values"])))
    return cols


def to_csv(results: dict) -> bytes:
    """One row per grid point; header ``name [unit]``; inf = unlimited, empty = no value."""
    shape = tuple(results["grid"]["shape"])
    axes = results["axes"]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    header = [name for name, _ in _axis_columns(results)]
    header += [f"{FIELDS[f][0]} [{FIELDS[f][1]}]" if FIELDS[f][1] else FIELDS[f][0] for f in FIELDS]
    header += list(TEXT)
    w.writerow(header)
    arrays = {f: grid_array(results, f) for f in FIELDS}
    text = {t: np.array(results["grid"][t], dtype=object) for t in TEXT}
    for idx in np.ndindex(*shape):
        row = []
        for k, a in enumerate(axes):
            row.append(repr(a["values"][idx[k]]))
            if a["unit"] != a["si_unit"]:
                row.append(repr(a["display_values"][idx[k]]))
        row += [_num(arrays[f][idx]) for f in FIELDS]
        row += [text[t][idx] for t in TEXT]
        w.writerow(row)
    return buf.getvalue().encode()


def _num(v: float) -> str:
    if math.isnan(v):
        return ""
    return "inf" if math.isinf(v) else repr(float(v))


def to_dataset(results: dict):
    """The sweep as an xarray Dataset with units and descriptions in the attributes."""
    import xarray as xr

    axes = results["axes"]
    dims = [a["name"] for a in axes]
    coords = {a["name"]: (a["name"], np.asarray(a["values"]), {"units": a["si_unit"], "long_name": a["label"]})
              for a in axes}
    for a in axes:
        if a["unit"] != a["si_unit"]:
            coords[f"{a['name']}_{a['unit']}"] = (a["name"], np.asarray(a["display_values"]),
                                                   {"units": a["unit"], "long_name": a["label"]})
    data = {}
    for f, (name, unit, desc) in FIELDS.items():
        data[name] = (dims, grid_array(results, f), {"units": unit or "1", "long_name": desc})
    for t in TEXT:
        data[t] = (dims, np.array(results["grid"][t], dtype=str), {"long_name": t})
    ds = xr.Dataset(data, coords=coords)
    if results.get("critical_length"):
        rows = results["critical_length"]
        values = np.array([np.nan if r["length_m"] is None else r["length_m"] for r in rows])
        cl_dims = (dims[1],) if len(dims) > 1 else ()
        ds["critical_length"] = (cl_dims, values if cl_dims else values[0],
                                 {"units": "m", "long_name": "shortest length at which the straight tether is "
                                  "no longer stable (Brent's method on the point solver)"})
    op = results["operating"]
    ds.attrs = {
        "title": f"etcheck sweep of {results['mission']['name']}",
        "etcheck_version": results["etcheck_version"],
        "mission_file": results["mission"]["file"],
        "mission_sha256": results["mission"]["sha256"],
        "tolerance": results["tolerance"],
        "required_margin": results["required_margin"],
        "operating_length_m": op["length"],
        "operating_spin_rate_rad_s": op["spin_rate"],
        "operating_load_N_per_m": op["load_N_per_m"],
        "operating_end_tension_N": op["end_tension"],
        "conventions": "NaN: no value (see status and reason); inf margin: no load or no spin at the point",
    }
    return ds


def to_netcdf(results: dict) -> bytes:
    """NetCDF (classic format, written by xarray's scipy backend: no extra library)."""
    return bytes(to_dataset(results).to_netcdf(engine="scipy"))


def read_netcdf(path: str | Path):
    """Load a sweep NetCDF file as an xarray Dataset (units in ``.attrs['units']``)."""
    import xarray as xr

    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()


def read_csv(path: str | Path) -> dict:
    """Load a sweep CSV: numeric columns as astropy Quantities (units from the header), text as lists."""
    import astropy.units as u

    from etcheck.input import units  # noqa: F401  (enables the rpm unit)

    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    out = {}
    for k, name in enumerate(header):
        col = [r[k] for r in body]
        if name in TEXT:
            out[name] = col
            continue
        base, _, unit = name.partition(" [")
        unit = unit.rstrip("]")
        values = np.array([float(v) if v else np.nan for v in col])
        out[f"{base} [{unit}]" if unit else base] = values * (u.Unit(unit) if unit else u.one)
    return out
