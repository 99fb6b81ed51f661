"""Parametric what-if: the straight-tether check over a grid of one or two mission quantities.

``sweep(mission, axes)`` varies any one or two of tether length, spin rate,
current, axial field and end tension (:mod:`etcheck.input.sweep_axes`), scales every grid
point from the mission (length moves every dimensionless number at once:
B ∝ L³, P ∝ L⁻², ω̄ ∝ L², T̄ ∝ L², gamma ∝ L⁻²; stiffnesses, mass per
length, damping time and the other inputs stay) and answers each with the
lowest rung that is exact for it:

* rung 0 (chi roots) for the critical load at zero spin and tension;
* rung 1 static pencils with damping (the Kelvin-Tait-Chetaev structure,
  :mod:`etcheck.rod.straight.collocation.damped_critical`): critical load at the point's spin,
  critical spin at the point's load, one small pencil per resolution;
* without damping (flutter windows are possible) the exact undamped
  determinant (:mod:`etcheck.rod.straight.exact.undamped`): divergence and
  flutter points located exactly along the load and spin lines.

Each point is an independent task keyed by its dimensionless parameters, the
solver settings and the etcheck version. Results go to a cache folder as they
arrive (one file per point, written by rename, so a kill loses at most the
points in flight), and a rerun takes them from there: an interrupted sweep
resumes and gives the same data. Points run on local worker processes by
default, or on a dask.distributed cluster (``scheduler=ADDRESS``). When length
is swept, the critical length is located exactly (Brent's method on the
point solver) for every value of the other axis.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import signal
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass, replace
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from etcheck import __version__
from etcheck.checks.orbit_field import resolve
from etcheck.checks.plan import EXACT, straight_route
from etcheck.checks.results.header import results_header
from etcheck.checks.verdict.validity import BOW_LIMIT, mid_span_bow
from etcheck.errors import EtcheckError, MissionError
from etcheck.input.gravity_gradient import circular_rate
from etcheck.input.mission import Mission
from etcheck.input.sweep_axes import Axis, check_axes
from etcheck.jsonable import finite_or_none, to_json
from etcheck.numerics.optimize import brentq
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.damped_critical import first_root
from etcheck.rod.straight.exact.roots import first_exact_root
from etcheck.rod.straight.exact.undamped import has_real_pair
from etcheck.runtime.blas import one_blas_thread
from etcheck.runtime.lifetime import die_with_parent, stop_words
from etcheck.runtime.parallel import serial
from etcheck.scaling import Scene, scale, with_length
from etcheck.studies.orbit_sweep import orbit_fields
from etcheck.studies.sweep_point import (
    STATUS_FAILED,
    STATUS_OK,
    STATUS_OUTSIDE,
    PointResult,
    PointStatus,
    point_key,
    solve_point,
)

__all__ = ["sweep", "SweepOptions", "DEFAULT_SWEEP", "SweepInterrupted", "critical_length", "point_scene",
           "load_axes_or_table", "Cache", "PointResult", "PointStatus", "solve_point", "point_key", "STATUS_OK",
           "STATUS_FAILED", "STATUS_OUTSIDE", "SWEEP_SCHEMA"]

SWEEP_SCHEMA = 3  # 2: the bow of each point and the verdict "outside", the verdict counts; 3: profiles (rung 1v)
REGION_STABLE, REGION_UNSTABLE, REGION_FAILED = "straight-stable", "straight-unstable", "failed"
REGION_BUCKLED = "buckled-stable"


class SweepInterrupted(EtcheckError):
    """The sweep was interrupted (Ctrl-C or a stop signal, ``stop``); what finished is in the cache. Exit code
    128 + the signal's number, as the shell reports it."""

    def __init__(self, message: str, stop: KeyboardInterrupt | None = None) -> None:
        super().__init__(message)
        self.exit_code = 128 + getattr(stop, "signum", signal.SIGINT)


@dataclass(frozen=True)
class SweepOptions:
    """How to run a sweep.

    ``tol``: relative two-resolution agreement required of every critical
    value; ``workers``: local processes (None: every core; 1: in this
    process); ``scheduler``: address of a dask.distributed scheduler (then
    ``workers`` is ignored); ``cache``: folder of per-point results (None:
    no cache); ``chunk``: points per task; ``connect_timeout``: seconds to
    wait for the dask scheduler; ``buckled``: at straight-unstable points,
    follow the first post-buckling branch b1 to the point and label it
    buckled-stable when the coiled state is stable (rungs 2-3; about a
    second per such point).
    """

    tol: float = 1e-8
    workers: int | None = None
    scheduler: str | None = None
    cache: Path | None = None
    chunk: int = 8
    connect_timeout: float = 10.0
    buckled: bool = False


#: a sweep's default settings
DEFAULT_SWEEP = SweepOptions()


# --------------------------------------------------------------------------- points


def point_scene(base: Scene, values: dict[str, float]) -> Scene:
    """The mission's worst-case scene with the swept quantities replaced (SI floats).

    ``values`` maps axis names to SI values; the current [A] and the axial field [T] not swept are the
    scene's worst case.
    """
    s = base
    if "length" in values:
        s = with_length(s, values["length"])  # a gravity-gradient tension is recomputed for the new length
    if "altitude" in values and s.gravity_gradient is not None and s.gravity_gradient.rate_source.startswith("[orbit]"):
        gg = replace(s.gravity_gradient, orbit_rate=circular_rate(values["altitude"]),
                     rate_source=f"circular at {values['altitude'] / 1e3:.6g} km (the sweep's altitude), mean motion")
        s = replace(s, gravity_gradient=gg, tension=gg.minimum)
    I_ = abs(values.get("current", s.current))
    B0 = abs(values.get("axial_field", s.field.axial))
    changes: dict[str, Any] = {"load": I_ * B0, "current": I_, "field": replace(s.field, axial=B0)}
    if "spin_rate" in values:
        changes["spin_rate"] = values["spin_rate"]
    if "end_tension" in values:
        changes["tension"] = values["end_tension"]
    return replace(s, **changes)


# --------------------------------------------------------------------------- critical length


def critical_length(base: Scene, values: dict[str, float], lo: float, hi: float, tol: float) -> dict[str, Any]:
    """Shortest length in [lo, hi] m at which the straight tether is no longer stable.

    ``lo`` must be a stable and ``hi`` an unstable length (from the grid).
    Brent's method with relative tolerance ``tol`` on h(L) = log t*(L), t*
    the first root of the static pencil along the ray from zero load and
    spin to the point's (B, omega^2) (damped: exact, Kelvin-Tait-Chetaev),
    or on the load margin minus one from the exact undamped determinant (undamped).
    Undamped, where the unloaded tether at ``hi`` already has a real pair of eigenvalues at its spin (and
    not at ``lo``), the load margin drops to zero there in a jump: the onset of that pair is bisected first
    (a cheap test per length) and is the answer if the tether is stable just short of it.
    """

    def at(L: float) -> RodParameters:
        return scale(point_scene(base, values | {"length": L})).params

    def h(L: float) -> float:
        return _length_margin(at(L), L, tol)

    t0 = time.perf_counter()
    rtol = max(tol, 4 * np.finfo(float).eps)
    spent = 0
    try:
        onset = _real_pair_onset(at, lo, hi, rtol)
        if onset is not None:
            a, b, spent = onset
            if h(a) > 0:
                return {"status": STATUS_OK.value, "reason": "the unloaded tether gains a real pair of eigenvalues "
                        "(divergence) at this spin", "length_m": b, "evaluations": spent + 1,
                        "time_s": time.perf_counter() - t0}
            hi, spent = a, spent + 1
        L, res = brentq(h, lo, hi, xtol=1e-12, rtol=rtol, full_output=True)
    except _NoAnswer as exc:
        return {"status": STATUS_FAILED.value, "reason": str(exc), "length_m": None, "time_s": time.perf_counter() - t0}
    return {"status": (STATUS_OK if res.converged else STATUS_FAILED).value, "reason": res.flag, "length_m": float(L),
            "evaluations": int(res.function_calls) + spent, "time_s": time.perf_counter() - t0}


def _length_margin(p: RodParameters, L: float, tol: float) -> float:
    """h(L) of :func:`critical_length` at the scene ``p`` of length L [m]: positive where stable."""
    if p.B == 0 and p.omega == 0:
        return 1.0
    if p.gamma > 0:  # exact: with damping, stable iff the ray root t* exceeds 1
        t = (first_exact_root if straight_route(p) == EXACT else first_root)(p, "ray", tol)
        if not t.converged:
            raise _NoAnswer(f"at L = {L:.6g} m: ray root not converged at N = {t.N} (error {t.error:.1e})")
        return math.log(t.value)
    r = solve_point(p, tol, spin=False)
    if r.status != STATUS_OK:
        raise _NoAnswer(f"at L = {L:.6g} m: {r.reason}")
    if p.B > 0:
        return (r.B_c / p.B if r.B_c is not None else math.inf) - 1.0
    return (r.omega_c / p.omega if r.omega_c is not None else math.inf) - 1.0


def _real_pair_onset(at: Callable[[float], RodParameters], lo: float, hi: float,
                     rtol: float) -> tuple[float, float, int] | None:
    """Undamped and spinning: the lengths (a, b), b - a <= rtol b, between which the unloaded tether gains a
    real pair of eigenvalues, bisected from [lo, hi], and the tests spent; None when it has none at ``hi`` or
    one at ``lo`` already (damped: the ray root answers)."""
    p_hi = at(hi)
    if p_hi.gamma > 0 or p_hi.omega == 0 or not has_real_pair(p_hi.with_(B=0.0)):
        return None
    if has_real_pair(at(lo).with_(B=0.0)):
        return None
    a, b, spent = lo, hi, 2
    while b - a > rtol * b:
        m = 0.5 * (a + b)
        a, b = (a, m) if has_real_pair(at(m).with_(B=0.0)) else (m, b)
        spent += 1
    return a, b, spent


class _NoAnswer(Exception):
    pass


# --------------------------------------------------------------------------- tasks and executors


def _worker_init(parent: int) -> None:
    """Local worker: one BLAS thread (its chunks run without forked helpers, :func:`_serially`), freed matrices
    kept for reuse (:mod:`etcheck.runtime.heap`: the worker is etcheck's own process); it ends with the sweep
    process (:func:`~etcheck.runtime.lifetime.die_with_parent`: kill -9 leaves no orphans)."""
    from threadpoolctl import threadpool_limits

    from etcheck.runtime.heap import keep_freed_memory

    die_with_parent(parent)
    threadpool_limits(limits=1)  # for the life of the worker
    keep_freed_memory()


def _solve_chunk(items: list[tuple]) -> list[tuple[str, PointResult]]:
    """Worker entry: solve a list of (key, params dict, tol, buckled, tether or None, damping fixed); adds wall
    time."""
    out = []
    with one_blas_thread():
        for key, pdict, tol, buckled, tether, fixed in items:
            t0 = time.perf_counter()
            r = solve_point(RodParameters(**pdict), tol, buckled=buckled, tether=tether, damping_fixed=fixed)
            out.append((key, replace(r, time_s=time.perf_counter() - t0)))
    return out


def _solve_lengths(items: list[tuple[str, tuple]]) -> list[tuple[str, dict]]:
    with one_blas_thread():
        return [(key, critical_length(*args)) for key, args in items]


class Cache:
    """One JSON file per result, named by its key; written by rename (kill-safe)."""

    def __init__(self, folder: Path | None):
        self.folder = Path(folder) if folder is not None else None
        if self.folder is not None:
            try:
                self.folder.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise MissionError("command line", "--cache", f"cannot create {self.folder}: {exc.strerror}") from None

    def get(self, key: str) -> dict | None:
        if self.folder is None:
            return None
        try:
            return json.loads((self.folder / f"{key}.json").read_text())
        except (OSError, ValueError):
            return None

    def put(self, key: str, value: dict) -> None:
        if self.folder is None:
            return
        path = self.folder / f"{key}.json"
        tmp = path.with_name(f".{key}.{os.getpid()}.tmp")
        tmp.write_text(json.dumps(value, allow_nan=False))
        os.replace(tmp, path)


def _run(fn: Callable, chunks: list[list], options: SweepOptions, on_result: Callable[[str, dict], None]) -> None:
    """Run fn over chunks (serial, local processes or dask) and hand every result to on_result."""
    if not chunks:
        return
    if options.scheduler:
        _run_dask(fn, chunks, options.scheduler, options.connect_timeout, on_result)
        return
    workers = options.workers or len(os.sched_getaffinity(0))
    if workers <= 1:
        for chunk in chunks:
            for key, r in _serially(fn, chunk):
                on_result(key, r)
        return
    pool = ProcessPoolExecutor(max_workers=min(workers, len(chunks)), initializer=_worker_init,
                               initargs=(os.getpid(),))
    try:
        futures = [pool.submit(_serially, fn, c) for c in chunks]
        for fut in as_completed(futures):
            for key, r in fut.result():
                on_result(key, r)
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()


def _run_dask(fn: Callable, chunks: list[list], address: str, timeout: float, on_result) -> None:
    try:
        from distributed import Client
        from distributed import as_completed as dask_completed
    except ImportError:
        raise MissionError("command line", "--scheduler", "dask.distributed is not installed",
                           'pip install "etcheck[distributed]"') from None
    try:
        client = Client(address, timeout=f"{timeout}s")
    except (OSError, TimeoutError) as exc:
        raise MissionError("command line", "--scheduler", f"cannot reach the dask scheduler at {address}: {exc}",
                           "start one (dask scheduler) or leave --scheduler out to run locally") from None
    try:
        futures = client.map(partial(_serially, fn), chunks, pure=False)
        for fut in dask_completed(futures):
            for key, r in fut.result():
                on_result(key, r)
    finally:
        client.close()


def _serially(fn: Callable, chunk: list) -> list:
    """``fn(chunk)`` without forked helpers: the points of a sweep share memoised roots (the lines at zero load
    of a length), which a helper would keep to itself, and the sweep's own workers keep every core busy."""
    with serial():
        return fn(chunk)


def _chunks(items: list, size: int) -> list[list]:
    return [items[i:i + size] for i in range(0, len(items), max(1, size))]


# --------------------------------------------------------------------------- the sweep


def sweep(mission: Mission, axes: tuple[Axis, ...], options: SweepOptions = DEFAULT_SWEEP,
          progress: Callable[[int, int, int], None] | None = None) -> dict[str, Any]:
    """Run the sweep; returns JSON-able results (dimensionless and SI).

    ``progress(done, total, from_cache)`` is called as points finish.
    Length, if swept, is put first (neighbouring tasks share their operators).
    """
    started = time.perf_counter()
    axes = tuple(sorted(axes, key=lambda a: a.name != "length"))
    resolved = resolve(mission)
    mission, base = resolved.mission, resolved.scene
    grids = [a.values for a in axes]
    shape = tuple(len(g) for g in grids)
    cache = Cache(options.cache)
    orbit = orbit_fields(mission, axes, options, cache, _run)  # altitude/inclination axes: worst field per orbit
    fixed = mission.tether.damping_time is not None

    points = []
    for idx in np.ndindex(*shape):
        values = {a.name: float(g[i]) for a, g, i in zip(axes, grids, idx)}
        if orbit is not None:
            values["axial_field"] = orbit.field(values)
        sc = point_scene(base, values)
        scaled = scale(sc)
        kind = "point+buckled" if options.buckled else "point"
        points.append((idx, values, sc, scaled, point_key(scaled.params, options.tol, kind, scaled.tether, fixed)))

    results: dict[str, PointResult] = {}
    todo, queued = [], set()
    for _, _, _, scaled, key in points:
        hit = _cached_point(cache, key)
        if hit is not None:
            results[key] = hit
        elif key not in queued:
            queued.add(key)
            todo.append((key, asdict(scaled.params), options.tol, options.buckled, scaled.tether, fixed))
    total, cached = len({p[4] for p in points}), len(results)

    def arrived(key: str, r: PointResult) -> None:
        cache.put(key, r.as_dict())  # JSON only here, at the edge
        results[key] = r
        if progress:
            progress(len(results), total, cached)

    if progress:
        progress(len(results), total, cached)
    t_solve = time.perf_counter()
    try:
        _run(_solve_chunk, _chunks(todo, options.chunk), options, arrived)
        grid = _assemble(points, results, axes, shape, mission)
        lengths = _critical_lengths(points, results, axes, shape, base, options, cache)
    except KeyboardInterrupt as stop:
        raise SweepInterrupted(f"sweep {stop_words(stop)}: {len(results)} of {total} points are saved"
                               + (f" in {cache.folder}; run the same command again to resume" if cache.folder else
                                  " (no cache folder: nothing kept)"), stop) from None
    solve_time = time.perf_counter() - t_solve
    solved = [r for k, r in results.items() if k in queued]
    cpu = sum(r.time_s or 0.0 for r in solved)
    return {
        **to_json(results_header(mission, SWEEP_SCHEMA)),
        "axes": [a.as_dict() for a in axes],
        "tolerance": options.tol,
        "buckled_assessed": options.buckled,
        "required_margin": mission.check.required_margin,
        "operating": _operating(base) | (orbit.operating if orbit else {}),
        "grid": grid,
        "critical_length": lengths,
        "orbit": orbit.as_dict() if orbit else None,
        "cost": {
            "points": total,
            "solved": len(todo),
            "from_cache": cached,
            "workers": "dask " + options.scheduler if options.scheduler else
            (options.workers or len(os.sched_getaffinity(0))),
            "wall_s": time.perf_counter() - started,
            "solve_wall_s": solve_time,
            "cpu_s_solved_points": cpu,
            "points_per_s_per_core": len(todo) / cpu if cpu > 0 else None,
            "max_resolution": max((r.N or 0 for r in results.values()), default=0),
        },
    }


def _cached_point(cache: Cache, key: str) -> PointResult | None:
    """The point cached under ``key`` (None when there is none, or its file is of another layout: solved again)."""
    hit = cache.get(key)
    try:
        return None if hit is None else PointResult.from_dict(hit)
    except (TypeError, ValueError):
        return None


def _operating(base: Scene) -> dict[str, float]:
    return {"length": base.length, "spin_rate": base.spin_rate, "current": base.current,
            "axial_field": base.field.axial, "end_tension": base.tension, "load_N_per_m": base.load,
            "spin_rpm": base.spin_rpm}


def _assemble(points, results, axes, shape, mission: Mission) -> dict[str, Any]:
    """Per-point SI data as arrays of the grid shape (lists, JSON-able)."""
    required = mission.check.required_margin
    fields = ("load_N_per_m", "critical_load_N_per_m", "load_margin", "load_error", "spin_rpm", "critical_spin_rpm",
              "spin_margin", "spin_error", "critical_spin_at_rest_rpm", "B", "omega", "T", "gamma", "P", "N",
              "buckled_deflection_m", "bow_over_length")
    data: dict[str, np.ndarray] = {f: np.full(shape, np.nan) for f in fields}
    text = {f: np.full(shape, "", dtype=object) for f in ("status", "region", "model", "reason", "verdict")}
    meets = np.zeros(shape, dtype=bool)
    for (idx, _, sc, scaled, key), bow in zip(points, _bows(points, mission)):
        r, p, scales = results[key], scaled.params, scaled.scales
        d = {"load_N_per_m": sc.load, "spin_rpm": sc.spin_rpm, "B": p.B, "omega": p.omega, "T": p.T,
             "gamma": p.gamma, "P": p.P, "N": r.N or np.nan, "bow_over_length": bow}
        ok = r.status == STATUS_OK
        if ok:
            Bc, wrest = r.B_c, r.omega_rest
            wcrit = np.nan if r.omega_c is None else r.omega_c  # None: not asked (rung 1v without spin)
            d |= {"critical_load_N_per_m": scales.line_load(Bc), "critical_spin_rpm": scales.rpm(wcrit),
                  "load_error": r.B_c_error, "spin_error": r.omega_c_error,
                  "critical_spin_at_rest_rpm": np.nan if wrest is None else scales.rpm(wrest),
                  "load_margin": Bc / p.B if p.B > 0 else np.inf,
                  "spin_margin": wcrit / p.omega if p.omega > 0 else np.inf}
            if r.buckled_deflection is not None:
                d["buckled_deflection_m"] = scales.distance(r.buckled_deflection)
        for f, v in d.items():
            data[f][idx] = v
        text["status"][idx] = r.status.value
        text["reason"][idx] = r.reason or r.buckled_reason or ""
        text["model"][idx] = r.model
        text["region"][idx] = (REGION_FAILED if not ok else REGION_STABLE if r.stable else
                               REGION_BUCKLED if r.buckled_stable else REGION_UNSTABLE)
        if ok:
            meets[idx] = r.stable and d["load_margin"] >= required and d["spin_margin"] >= required
            text["verdict"][idx] = "outside" if bow > BOW_LIMIT else "pass" if meets[idx] else "fail"
        else:
            text["verdict"][idx] = "no answer"
    out = {f: finite_or_none(v) for f, v in data.items()}
    out |= {f: v.tolist() for f, v in text.items()}
    out["shape"] = list(shape)
    status = text["status"].ravel().tolist()
    out["counts"] = {s.value: status.count(s.value) for s in PointStatus}
    region = text["region"].ravel().tolist()
    out["regions"] = {s: region.count(s) for s in (REGION_STABLE, REGION_BUCKLED, REGION_UNSTABLE, REGION_FAILED)}
    verdict = text["verdict"].ravel().tolist()
    out["verdicts"] = {s: verdict.count(s) for s in ("pass", "fail", "outside", "no answer")}
    stable = text["region"] == REGION_STABLE
    out["meet_margin"] = int(meets.sum())  # stable and both margins met, within the model's validity or not
    out["stable_short"] = int((stable & ~meets).sum())  # straight-stable but short of the required margin
    out["bow_limit"] = BOW_LIMIT
    out["max_error"] = max([e for e in np.concatenate([data["load_error"].ravel(), data["spin_error"].ravel()])
                            if np.isfinite(e)], default=None)
    return out


def _bows(points, mission: Mission) -> list[float]:
    """The bow at mid-span over the length of each point under the lateral Lorentz load
    (:func:`etcheck.checks.verdict.validity.mid_span_bow`): the field across the tether as the mission states it, else
    the point's own axial field where the sweep sets one (field or orbit axes), else the check's."""
    stated = mission.operation.cross_field is not None
    out = []
    for _, values, sc, _, _ in points:
        b_perp = sc.field.cross if stated else values.get("axial_field", sc.field.cross)
        q = sc.current * b_perp
        out.append(mid_span_bow(q, sc.length, sc.tension, sc.EI2) / sc.length)
    return out


def _critical_lengths(points, results, axes, shape, base, options, cache) -> list[dict] | None:
    """Exact critical length for each value of the other axis (length swept only; not with profiles along the
    tether, whose grid points answer where it lies)."""
    if axes[0].name != "length" or base.profiles:
        return None
    other = axes[1] if len(axes) > 1 else None
    by_idx = {idx: (values, results[key]) for idx, values, _, _, key in points}
    tasks, rows = [], []
    for j in range(shape[1] if other else 1):
        col = [by_idx[(i, j) if other else (i,)] for i in range(shape[0])]
        row, task = _length_row(col, other, axes[0], base, options, cache)
        rows.append(row)
        if task is not None:
            tasks.append(task)
    found: dict[str, dict] = {}

    def arrived(key, r):
        cache.put(key, r)
        found[key] = r

    _run(_solve_lengths, _chunks(tasks, 1), options, arrived)
    for row in rows:
        key = row.pop("key", None)
        if key in found:
            row |= found[key]
    return rows


def _length_row(col: list, other: Axis | None, length: Axis, base: Scene, options: SweepOptions,
                cache: Cache) -> tuple[dict, tuple | None]:
    """The critical-length row of one column of the grid (points in order of length) and the
    task that locates it (None when the column says where it is without one, or from the cache)."""
    row: dict[str, Any] = {"other": None if other is None else col[0][0][other.name], "status": "", "reason": "",
                           "length_m": None}
    if other is not None:
        row["other_display"] = row["other"] * other.to_display
    first_bad = next((i for i, (_, r) in enumerate(col) if r.status != STATUS_OK or not r.stable), None)
    if first_bad is None:
        return row | {"status": "beyond range", "reason": f"stable up to the longest length swept ({length.stop:.6g} m)"}, None
    if first_bad == 0:
        return row | {"status": "below range", "reason": f"not stable at the shortest length swept ({length.start:.6g} m)"}, None
    if col[first_bad][1].status != STATUS_OK:
        return row | {"status": STATUS_FAILED.value, "reason": "the first unstable-looking point did not converge: "
                      + col[first_bad][1].reason}, None
    values = {k: v for k, v in col[0][0].items() if k != "length"}
    lo, hi = col[first_bad - 1][0]["length"], col[first_bad][0]["length"]
    args = (base, values, lo, hi, options.tol)
    key = hashlib.sha256(json.dumps(["critical_length", repr(args), options.tol, __version__]).encode()).hexdigest()
    row |= {"key": key, "bracket_m": [lo, hi]}
    hit = cache.get(key)
    return (row | hit, None) if hit is not None else (row, (key, args))


def load_axes_or_table(mission: Mission, axes: Iterable[Axis]) -> tuple[Axis, ...]:
    """Command-line axes if given, else the mission's [sweep] table."""
    axes = tuple(axes)
    if axes:
        return check_axes(axes, "command line")
    if mission.studies.sweep:
        return mission.studies.sweep
    raise MissionError(mission.provenance.file, "sweep", "no sweep axes given",
                       "pass e.g. --length 50m:5km:40:log --spin 0rpm:2rpm:40, or add a [sweep] table to the mission")
