"""The geomagnetic field along an orbit: IGRF (through ``ppigrf``) and a
centred dipole for verification, in ITRS and in the local orbital frame.

IGRF: ``ppigrf.igrf_gc`` evaluates the degree-13 spherical-harmonic model at
geocentric (r, colatitude, longitude) for one set of coefficients per call.
Samples are grouped into blocks of at most half a day and 20 000 samples and
each block uses the coefficients at its middle instant: the secular variation
of the field in LEO is < 200 nT/yr, so this moves the field by < 0.2 nT.

Units: positions in metres (ITRS), fields in tesla.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from datetime import datetime
from functools import lru_cache

import astropy.units as u
import numpy as np
import ppigrf
from astropy.time import Time
from ppigrf.ppigrf import read_shc, shc_fn_igrf13, shc_fn_igrf14

from etcheck.orbit import frames
from etcheck.orbit.elements import Trajectory
from etcheck.orbit.models import DEFAULT_MODEL

#: IGRF reference radius (m).
IGRF_RADIUS = 6371.2e3
#: Coefficient files shipped by ppigrf.
IGRF_MODELS = {"IGRF-14": shc_fn_igrf14, "IGRF-13": shc_fn_igrf13}
_BLOCK_SECONDS = 43200.0
_BLOCK_SAMPLES = 20000
_NT = 1e-9


@lru_cache(maxsize=4)
def _coefficients(model: str):
    return read_shc(IGRF_MODELS[model])


def _datetime(t: Time) -> datetime:
    return datetime.fromisoformat(frames.iso(t))


def _spherical_basis(position: np.ndarray):
    """r (m), colatitude and longitude (rad), and unit vectors e_r, e_theta
    (south), e_phi (east) in ITRS, for positions (n, 3)."""
    x, y, z = position.T
    r = np.linalg.norm(position, axis=1)
    theta = np.arccos(np.clip(z / r, -1.0, 1.0))
    phi = np.arctan2(y, x)
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    e_r = position / r[:, None]
    e_t = np.stack([ct * cp, ct * sp, -st], axis=1)
    e_p = np.stack([-sp, cp, np.zeros_like(sp)], axis=1)
    return r, theta, phi, e_r, e_t, e_p


def igrf_itrs(position: np.ndarray, start, t: np.ndarray, model: str = DEFAULT_MODEL) -> np.ndarray:
    """IGRF field (T), shape (n, 3) in ITRS, at ITRS ``position`` (n, 3) m and
    instants ``start + t`` (t in s)."""
    position = np.atleast_2d(np.asarray(position, dtype=float))
    t = np.atleast_1d(np.asarray(t, dtype=float))
    start = frames.parse_utc(start)
    r, theta, phi, e_r, e_t, e_p = _spherical_basis(position)
    # ppigrf divides B_phi by sin(colatitude): keep off the exact pole (1e-9 deg
    # is 0.1 mm; P_n^m contains sin^m, so the limit is finite and is reached)
    theta_deg = np.clip(np.degrees(theta), 1e-9, 180.0 - 1e-9)
    phi_deg = np.degrees(phi)
    out = np.empty_like(position)
    block = np.floor((t - t.min()) / _BLOCK_SECONDS).astype(int) if t.size else t.astype(int)
    for b in np.unique(block):
        idx = np.flatnonzero(block == b)
        for chunk in np.array_split(idx, max(1, math.ceil(idx.size / _BLOCK_SAMPLES))):
            with frames.quiet():  # UTC arithmetic goes through TAI: constant past the leap-second table
                mid = start + 0.5 * (t[chunk].min() + t[chunk].max()) * u.s
            Br, Bt, Bp = ppigrf.igrf_gc(
                r[chunk] / 1e3, theta_deg[chunk], phi_deg[chunk], _datetime(mid), coeff_fn=IGRF_MODELS[model]
            )
            out[chunk] = _NT * (Br[0][:, None] * e_r[chunk] + Bt[0][:, None] * e_t[chunk] + Bp[0][:, None] * e_p[chunk])
    return out


@dataclass(frozen=True)
class CentredDipole:
    """The degree-1 part of a field model: g10, g11, h11 (T) on the reference
    sphere of radius ``reference_radius`` (m). Its field is

        B(r) = (a/|r|)^3 [3 (g . r_hat) r_hat - g],   g = (g11, h11, g10)

    (ITRS components), so an axial dipole g10 = -B0 has B0 at the equator of the
    reference sphere, radial field 2 B0 (a/r)^3 |cos(colatitude)| and points
    north along the equator, like the Earth's.
    """

    g10: float
    g11: float = 0.0
    h11: float = 0.0
    reference_radius: float = IGRF_RADIUS

    @classmethod
    def axial(cls, b0: float, reference_radius: float = IGRF_RADIUS) -> CentredDipole:
        """Earth-like axial dipole with equatorial field ``b0`` (T) at ``reference_radius``."""
        return cls(-b0, 0.0, 0.0, reference_radius)

    @classmethod
    def from_igrf(cls, instant, model: str = DEFAULT_MODEL) -> CentredDipole:
        """g10, g11, h11 of the IGRF at ``instant`` (interpolated linearly in time
        between the model's 5-yearly coefficients, as the IGRF is defined)."""
        g, h = _coefficients(model)
        when = frames.parse_utc(instant)
        years = np.array([frames.parse_utc(d.to_pydatetime()).jd for d in g.index])
        x = float(when.jd)
        coef = [float(np.interp(x, years, col.to_numpy(dtype=float))) for col in (g[(1, 0)], g[(1, 1)], h[(1, 1)])]
        return cls(*(c * _NT for c in coef))

    @property
    def b0(self) -> float:
        """Equatorial field of the equivalent axial dipole, sqrt(g10^2 + g11^2 + h11^2), T."""
        return math.sqrt(self.g10**2 + self.g11**2 + self.h11**2)

    def field_itrs(self, position: np.ndarray) -> np.ndarray:
        """Field (T), shape (n, 3) ITRS, at ITRS positions (n, 3) m."""
        position = np.atleast_2d(np.asarray(position, dtype=float))
        g = np.array([self.g11, self.h11, self.g10])
        r = np.linalg.norm(position, axis=1)
        rhat = position / r[:, None]
        scale = (self.reference_radius / r) ** 3
        return scale[:, None] * (3.0 * (rhat @ g)[:, None] * rhat - g)


@dataclass(frozen=True)
class LocalField:
    """Field along a trajectory. itrs: (n, 3) T. up, along_track, cross_track:
    components (T) on the trajectory's local orbital frame. magnitude: T."""

    model: str
    itrs: np.ndarray
    up: np.ndarray
    along_track: np.ndarray
    cross_track: np.ndarray
    magnitude: np.ndarray


def field_along(traj: Trajectory, model: str | CentredDipole = DEFAULT_MODEL) -> LocalField:
    """The field of ``model`` ("IGRF-14", "IGRF-13" or a :class:`CentredDipole`)
    along ``traj``, in ITRS and in the local orbital frame."""
    if isinstance(model, CentredDipole):
        b = model.field_itrs(traj.position)
        name = f"centred dipole (g10, g11, h11) = ({model.g10:.6g}, {model.g11:.6g}, {model.h11:.6g}) T"
    else:
        if model not in IGRF_MODELS:
            raise ValueError(f"unknown field model {model!r}; use one of {', '.join(IGRF_MODELS)} or a CentredDipole")
        b = igrf_itrs(traj.position, traj.start, traj.time, model)
        name = model
    return LocalField(
        model=name,
        itrs=b,
        up=np.einsum("ni,ni->n", b, traj.radial),
        along_track=np.einsum("ni,ni->n", b, traj.along_track),
        cross_track=np.einsum("ni,ni->n", b, traj.cross_track),
        magnitude=np.linalg.norm(b, axis=1),
    )
