"""One point of a what-if sweep: the straight tether's critical values at one set of dimensionless parameters.

:func:`solve_point` answers a point with the lowest rung that is exact for it (rung 0's static loads where
there is no spin and tension, the static pencils or the exact determinant with damping, the exact undamped
determinant without, rung 1v with a current or a tension along the tether) and returns a frozen
:class:`PointResult`; :mod:`etcheck.studies.sweep` runs the points, caches them (``as_dict``, JSON) and
assembles the grid. :func:`point_key` names a point in the cache.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict, dataclass, fields, replace
from enum import StrEnum
from typing import TYPE_CHECKING, Any

import numpy as np

from etcheck import __version__
from etcheck.checks.plan import EXACT, PROFILES_MODEL, straight_route
from etcheck.checks.rungs.buckled import buckled_point
from etcheck.checks.verdict.validity import P_LIMIT
from etcheck.errors import EtcheckError
from etcheck.rod.core.ends import BUCKLED_WELDED_ONLY, is_welded
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.rod.straight.exact.roots import MODEL as EXACT_ROOTS
from etcheck.rod.straight.exact.roots import exact_critical, pencil_or_exact
from etcheck.rod.straight.exact.undamped import MODEL as UNDAMPED_MODEL
from etcheck.rod.straight.exact.undamped import undamped_critical
from etcheck.runtime.memory import OverBudget

if TYPE_CHECKING:  # rung 1v (scipy.sparse) is imported only for a sweep of a mission with profiles
    from etcheck.rod.straight.varying.profiles import Tether

#: Rod theory assumes a slender rod: P = I1 / (A L^2) << 1 (the check's limit).
P_MAX = P_LIMIT


class PointStatus(StrEnum):
    """Whether a sweep point was answered (a str: written to JSON as its value)."""

    OK = "ok"
    FAILED = "failed"
    OUTSIDE = "outside validated range"


STATUS_OK, STATUS_FAILED, STATUS_OUTSIDE = PointStatus.OK, PointStatus.FAILED, PointStatus.OUTSIDE


@dataclass(frozen=True)
class PointResult:
    """The critical values at one sweep point (dimensionless).

    ``B_c``: critical load at the point's spin and tension (0 if unstable without load; inf: no critical load);
    ``omega_c``: critical spin at the point's load (0 if statically buckled; None: not asked); ``omega_rest``:
    critical spin without load (damped only); ``*_error``: their relative errors; ``stable``: the point itself
    (None unless answered); ``N``: the resolution (None or 0: no grid). Rung 1v adds ``kind`` (divergence or
    flutter) and ``gamma_used`` (the damping its critical load is at); a buckled sweep adds ``buckled_stable``,
    ``buckled_deflection`` (units of L) and ``buckled_reason`` at straight-unstable points; ``time_s`` is the
    wall time the point took in its worker.
    """

    status: PointStatus = PointStatus.OK
    reason: str = ""
    model: str = ""
    B_c: float | None = None
    B_c_error: float | None = None
    omega_c: float | None = None
    omega_c_error: float | None = None
    omega_rest: float | None = None
    stable: bool | None = None
    N: int | None = None
    kind: str | None = None
    gamma_used: float | None = None
    buckled_stable: bool | None = None
    buckled_deflection: float | None = None
    buckled_reason: str | None = None
    time_s: float | None = None

    #: the keys every point's record has; the others only where they were computed
    ALWAYS = ("status", "reason", "model", "B_c", "B_c_error", "omega_c", "omega_c_error", "omega_rest", "stable",
              "N")

    def as_dict(self) -> dict[str, Any]:
        """The JSON record of the point (the sweep's cache file): every key of :data:`ALWAYS`, the others where
        set; the status as its value."""
        out = {k: v for k, v in asdict(self).items() if k in self.ALWAYS or v is not None}
        return out | {"status": self.status.value}

    @classmethod
    def from_dict(cls, record: dict[str, Any]) -> PointResult:
        """The point of a record written by :meth:`as_dict` (ValueError for a record of another layout)."""
        names = {f.name for f in fields(cls)}
        if not set(record) <= names or not set(cls.ALWAYS) <= set(record):
            raise ValueError(f"not a sweep point record: keys {sorted(record)}")
        return cls(**(record | {"status": PointStatus(record["status"])}))


def solve_point(params: RodParameters, tol: float, spin: bool = True, buckled: bool = False,
                tether: Tether | None = None, damping_fixed: bool = True) -> PointResult:
    """The straight-tether critical values at one point (dimensionless): :class:`PointResult`, status ok,
    failed (with the reason) or outside the validated range.

    ``spin=False`` skips the critical spin (damped only). ``buckled=True`` adds ``buckled_stable`` (and
    ``buckled_deflection``, units of L) at straight-unstable points: is the coiled state on b1 stable there
    (rungs 2-3). ``tether``: the point's problem with its current and tension along it (rung 1v; ``params`` then
    ignored), ``damping_fixed`` whether the mission gives its damping (:func:`profiles_point`).
    """
    if params.P > P_MAX:
        return PointResult(STATUS_OUTSIDE,
                           f"P = {params.P:.3g} > {P_MAX}: the tether is too short for rod theory (P << 1)")
    try:
        if tether is not None:
            out = profiles_point(tether, tol, spin, damping_fixed)
        else:
            out = _damped(params, tol, spin) if params.gamma > 0 else _undamped(params, tol, spin)
    except (np.linalg.LinAlgError, ValueError, ArithmeticError) as exc:
        out = PointResult(STATUS_FAILED, f"solver error: {type(exc).__name__}: {exc}")
    except OverBudget as exc:  # no route fits the memory budget: this point is not answered, the others are
        out = PointResult(STATUS_FAILED, str(exc))
    out = _finite(out, spin)
    if out.status != STATUS_OK:
        return replace(out, stable=None)
    if buckled and out.stable is False and params.gamma > 0:
        return _buckled(out, params)
    return out


def _damped(params: RodParameters, tol: float, spin: bool) -> PointResult:
    """With damping, static pencils or the exact determinant (Kelvin-Tait-Chetaev)."""
    exact = straight_route(params) == EXACT  # boundary layers too thin for collocation
    d = exact_critical(params, tol, spin=spin) if exact else pencil_or_exact(params, tol, spin=spin)
    exact = exact or d.critical_load.model == EXACT_ROOTS  # a pencil root next to the end of its line
    pencil = "rung 1 (exact determinant)" if exact else "rung 1 (static pencil)"
    out = PointResult(model=d.critical_load.model if params.omega == 0 and params.T == 0 else pencil,
                      B_c=d.critical_load.value, B_c_error=d.critical_load.error,
                      omega_c=d.critical_spin.value, omega_c_error=d.critical_spin.error,
                      omega_rest=d.spin_at_rest.value, stable=d.stable,
                      N=max(d.critical_load.N, d.critical_spin.N))
    return out if d.converged else replace(out, status=STATUS_FAILED, reason=d.message)


def _finite(out: PointResult, spin: bool) -> PointResult:
    """Infinite values stay (no root: None in JSON later), NaN ones fail the point."""
    for key in ("B_c", "omega_c", "omega_rest", "B_c_error", "omega_c_error"):
        v = getattr(out, key)
        if v is not None and not math.isfinite(v):
            if math.isnan(v) and out.status == STATUS_OK and (spin or not key.startswith("omega_c")):
                out = replace(out, status=STATUS_FAILED, reason=f"{key} is not a number")
            out = replace(out, **{key: None if math.isnan(v) else v})
    return out


def _buckled(out: PointResult, params: RodParameters) -> PointResult:
    """``out`` with whether the coiled state on b1 is stable at this straight-unstable point (rungs 2-3; welded
    ends only)."""
    if not is_welded(params.ends):
        return replace(out, buckled_reason=f"not computed: rungs 2-3 are {BUCKLED_WELDED_ONLY}")
    try:
        b = buckled_point(params)
    except (ArithmeticError, ValueError, EtcheckError, np.linalg.LinAlgError) as exc:
        return replace(out, buckled_reason=f"rung 2 failed: {exc}")
    return replace(out, buckled_stable=b.stable, buckled_deflection=b.max_deflection, buckled_reason=b.reason)


def _undamped(params: RodParameters, tol: float, spin: bool) -> PointResult:
    """Without damping flutter is possible: the exact undamped determinant (rung 1u), located
    divergence and flutter points along the load and spin lines through the point (``spin=False``:
    the load line alone where there is a load)."""
    u = undamped_critical(params, tol, windows=False, spin=spin)
    values = {}
    for name, c in (("B_c", u.critical_load), ("omega_c", u.critical_spin)):
        if c.kind == CriticalKind.UNSTABLE_AT_START:
            values |= {name: 0.0, f"{name}_error": 0.0}
        elif c.kind in (CriticalKind.NONE_FOUND, CriticalKind.NEVER):
            values |= {name: math.inf, f"{name}_error": 0.0}
        else:
            values |= {name: c.value, f"{name}_error": c.error / abs(c.value) if c.value else c.error}
    out = PointResult(model=UNDAMPED_MODEL, stable=bool(u.stable), **values)
    if not u.converged:
        bad = [c.message for c in (u.critical_load, u.critical_spin)
               if not c.converged and c.kind not in (CriticalKind.UNSTABLE_AT_START, CriticalKind.NONE_FOUND,
                                                     CriticalKind.NEVER)]
        if bad:
            out = replace(out, status=STATUS_FAILED, reason="rung 1u did not converge: " + "; ".join(bad))
    return out


#: The damping of a sweep point with a circulatory load and no damping fixed by the mission: none, a thousandth of
#: the paper's estimate (the limit of small damping, Ziegler) and the estimate itself; the point takes the least
#: favourable (the check's map has five).
SWEEP_DAMPING = (0.0, 1e-3, 1.0)


def profiles_point(tether: Tether, tol: float, spin: bool = True, damping_fixed: bool = True) -> PointResult:
    """Rung 1v at one sweep point: the critical load at the point's spin (the least favourable of
    :data:`SWEEP_DAMPING` for a circulatory load without a fixed damping, else at the point's damping) and the
    critical spin at its load at that damping (dimensionless, as :func:`solve_point`)."""
    from etcheck.rod.straight.varying.circulatory import critical, critical_spin

    p = tether.params
    fractions = SWEEP_DAMPING if tether.circulatory and not damping_fixed and p.gamma > 0 else (1.0,)
    worst, near = None, None
    for frac in fractions:
        c = critical(tether.with_(gamma=frac * p.gamma), tol=tol, mode=False, near=near)
        located = CriticalKind(c.kind).located
        near = (0.8 * c.value, 1.25 * c.value) if located and c.value > 0 else None
        value = c.value if located else 0.0 if c.kind == CriticalKind.UNSTABLE_AT_START else math.inf
        if worst is None or value < worst[0]:
            worst = (value, c, frac * p.gamma)
    value, c, gamma = worst
    out = PointResult(model=PROFILES_MODEL, N=c.N, B_c=value,
                      B_c_error=c.error / value if 0 < value < math.inf else 0.0, kind=str(c.kind), gamma_used=gamma)
    if c.kind == CriticalKind.NOT_LOCATED:
        out = replace(out, status=STATUS_FAILED, reason=f"rung 1v: {c.message}")
    if spin and p.omega > 0:
        w = critical_spin(tether.with_(gamma=gamma), tol=tol)
        located = CriticalKind(w.kind).located
        out = replace(out, omega_c=(w.value if located else 0.0 if w.kind == CriticalKind.UNSTABLE_AT_START
                                    else math.inf),
                      omega_c_error=w.error / w.value if located and w.value > 0 else 0.0)
    out = replace(out, stable=bool(p.B < value and (out.omega_c is None or p.omega < out.omega_c)))
    if math.isinf(value):  # stable up to the end of the line: the margin shown is a lower bound
        out = replace(out, B_c=c.hi, reason=f"stable up to B = {c.hi:.6g}, the end of the scanned line (a lower bound)")
    return out


def point_key(params: RodParameters, tol: float, kind: str = "point", tether: Tether | None = None,
              damping_fixed: bool = True) -> str:
    """Cache key: dimensionless parameters (exact floats), the profiles along the tether, settings and version."""
    # welded ends (the paper's) leave the key as it was before the ends were a parameter
    params_fields = {k: repr(v) for k, v in asdict(params).items() if not (k == "ends" and is_welded(v))}
    extra = {} if tether is None else {"tether": repr(tether), "damping_fixed": damping_fixed}
    text = json.dumps({"kind": kind, "params": params_fields, "tol": repr(tol), "version": __version__} | extra,
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()
