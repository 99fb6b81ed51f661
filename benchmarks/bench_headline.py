"""The headline: every command and solver row against its target, in one run.

    python benchmarks/bench_headline.py [--quick] [--missions missions/set.toml,...] [--no-missions]
                                        [--markdown docs/performance.md]

Prints, for each row (the cold CLI runs, the draft check, the damped critical
load and spin at the operating point, the undamped spin windows, b1 with its
stability and secondary pitchfork, B*(omega) at 10 spins, the bifurcation
diagram and the damping map from the CLI, the 40 x 40 damped and undamped
sweeps), the wall time, the largest stated error and the ratio to the target;
then the draft and sign-off margins of every shipped mission side by side (the
trade the user chooses). ``--quick`` skips the slow rows (B*(omega) at 10 spins,
diagram, damping map, undamped sweep) and compares SET only. ``--markdown FILE``
rewrites the table between the markers ``<!-- bench_headline:begin -->`` and
``<!-- bench_headline:end -->`` of FILE with this run's rows (skipped rows keep
their previous line). One BLAS thread; the solvers are called through their
public functions and the CLI, so the benchmark follows their changes. A row
whose function does not exist (yet) prints "n/a". A measurement, not a test:
on a shared machine, repeat it.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from etcheck.checks.pipeline import check  # noqa: E402
from etcheck.input.mission import load_mission  # noqa: E402
from etcheck.runtime.heap import keep_freed_memory  # noqa: E402
from etcheck.scaling import scale, scene  # noqa: E402

keep_freed_memory()  # as the CLI's process (etcheck.runtime.heap): the rows measure what a user of the CLI gets

ROOT = Path(__file__).resolve().parents[1]
SET = ROOT / "missions" / "set.toml"
#: a row run in a child process (the CLI, the sweeps) is stopped after this many times its target (at least 2 min)
PATIENCE = 10.0


@dataclass(frozen=True)
class Row:
    """One line of the table: what, target wall time [s], whether --quick skips it, how to measure it.

    ``measure()`` returns (wall time [s], largest stated relative error or None, a note) or raises
    NotImplementedError when the function it needs does not exist.
    """

    what: str
    target: float
    slow: bool
    measure: Callable[[], tuple[float, float | None, str]]


def _operating_point():
    """SET at its operating point (dimensionless), damped with the mission's (assumed) damping."""
    return scale(scene(load_mission(SET))).params


def _best_cold(fn, p, repeat: int = 3) -> tuple[float, object]:
    """Best wall time of ``fn(p')`` over ``repeat`` runs, each on a rotary-inertia ratio changed by 1e-9 relative
    (misses every memo of operators; changes no digit that is reported), after one warm-up for the imports."""
    fn(p.with_(P=p.P * (1 - 1e-9)))
    best, out = math.inf, None
    for k in range(1, repeat + 1):
        t0 = time.perf_counter()
        out = fn(p.with_(P=p.P * (1 + 1e-9 * k)))
        best = min(best, time.perf_counter() - t0)
    return best, out


# ----------------------------------------------------------------------------- cold CLI

def _run(cmd: list[str], timeout: float) -> subprocess.CompletedProcess | None:
    """``cmd`` in its own process group; None when it ran past ``timeout`` [s] (then the whole group is ended:
    a study's worker and report processes too)."""
    with subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          start_new_session=True) as proc:
        try:
            out, err = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            return None
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


def _cli(args: list[str], timeout: float, out: Path) -> tuple[float, subprocess.CompletedProcess | None]:
    t0 = time.perf_counter()
    proc = _run([sys.executable, "-m", "etcheck", *args, "--out", str(out)], timeout)
    return time.perf_counter() - t0, proc


def _stopped(wall: float) -> tuple[float, None, str]:
    return wall, None, f"stopped after {wall:.0f} s"


def _cli_check(extra: list[str], target: float, repeat: int = 3):
    """The best wall time of ``repeat`` cold processes (each a new interpreter; the machine's noise only adds)."""
    def measure():
        best = math.inf
        for _ in range(repeat):
            with tempfile.TemporaryDirectory() as out:
                wall, proc = _cli([str(SET.relative_to(ROOT)), *extra], max(PATIENCE * target, 120.0), Path(out))
                if proc is None:
                    return _stopped(wall)
                if wall < best:
                    best, code = wall, proc.returncode
                    results = json.loads((Path(out) / "set" / "results.json").read_text())
        errors = [m["error"] for m in results["margins"] if m.get("error") is not None]
        return best, max(errors, default=None), (f"best of {repeat}, exit {code}, "
                                                 f"{results.get('elapsed_s', math.nan):.2f} s in the check")
    return measure


def _compile_bytecode() -> None:
    """Compile etcheck's modules, as ``pip install`` does: an editable install compiles them on a first run, and
    never where PYTHONDONTWRITEBYTECODE is set, so that every cold run would compile ~0.25 s of source."""
    import compileall

    compileall.compile_dir(ROOT / "etcheck", quiet=1)


def _cli_study(args: list[str], target: float, result: str, error: Callable[[dict], float | None],
               repeat: int = 1):
    """The best wall time of ``repeat`` cold runs of a study (as :func:`_cli_check`)."""
    def measure():
        best = None
        for _ in range(repeat):
            with tempfile.TemporaryDirectory() as out:
                wall, proc = _cli(args, max(PATIENCE * target, 120.0), Path(out))
                if proc is None:
                    return _stopped(wall)
                files = sorted(Path(out).glob(f"**/{result}"))
                if proc.returncode not in (0, 1) or not files:
                    return wall, None, f"exit {proc.returncode}: {proc.stderr.strip()[-200:]}"
                if best is None or wall < best[0]:
                    best = (wall, error(json.loads(files[0].read_text())), f"exit {proc.returncode}")
        return best if repeat == 1 else (best[0], best[1], f"best of {repeat}, {best[2]}")
    return measure


def _diagram_error(d: dict) -> float | None:
    errs = [b.get(k) for b in d["diagram"]["branches"] for k in ("measure1_error", "deflection_error")]
    errs = [e for e in errs if isinstance(e, (int, float)) and math.isfinite(e)]
    return max(errs, default=None)


def _damping_error(d: dict) -> float | None:
    return d["study"]["largest_error"]


# ----------------------------------------------------------------------------- in-process rows

DRAFT = """
import json, time
from dataclasses import replace
from etcheck.runtime.heap import keep_freed_memory
keep_freed_memory()
from etcheck.checks.pipeline import check
from etcheck.input.mission import load_mission
m = load_mission("missions/set.toml").with_fidelity("draft")
t0 = time.perf_counter()
r = check(m).results
print(json.dumps({"wall": time.perf_counter() - t0,
                  "error": max((g["error"] for g in r["margins"] if g["error"] is not None), default=None)}))
"""


def _draft_check():
    """The first check of a fresh process, best of 3 processes (like the cold CLI rows: one sample of 30-50 ms
    moves with whatever else the machine did in that instant)."""
    best = None
    for _ in range(3):
        wall, out = _child(DRAFT, [], 0.05)
        if isinstance(out, str):
            return wall, None, out
        best = out if best is None or out["wall"] < best["wall"] else best
    return best["wall"], best["error"], "first check in a fresh process, best of 3"


def _damped_root(axis: str):
    def measure():
        from etcheck.rod.straight.collocation.damped_critical import first_root

        wall, root = _best_cold(lambda p: first_root(p, axis, 1e-8), _operating_point())
        return wall, root.error, f"{axis} = {root.value:.12g}, N = {root.N}"
    return measure


def _undamped_windows():
    try:
        from etcheck.rod.straight.exact.undamped import undamped_critical
    except ImportError as exc:
        raise NotImplementedError(str(exc)) from None
    wall, c = _best_cold(lambda p: undamped_critical(p, 1e-8, windows=True), _operating_point().with_(gamma=0.0))
    rel = [pt.error / abs(pt.value) for pt in (c.critical_load, c.critical_spin)
           if math.isfinite(pt.value) and pt.value != 0]
    return wall, max(rel, default=None), f"{len(c.windows)} stable spin windows up to omega = {c.scanned_to:.3g}"


def _b1_with_stability():
    import numpy as np

    from etcheck.rod.buckled import branches as br
    from etcheck.rod.buckled import secondary, spectra

    p = _operating_point()
    t0 = time.perf_counter()
    start = next(s for s in br.primary_branches(p.with_(B=0.0), 1, 32) if s.which == "S1")
    b1 = br.continue_branch(p, start, stop=(0.0, 4.0 * start.load), N=32)
    spectra = spectra.branch_spectra(b1, p.gamma)
    pf = secondary.secondary_pitchfork(p, p.omega, 32, branch=b1)
    wall = time.perf_counter() - t0
    err = max(pf.error / pf.B, float(np.nanmax(spectra.max_real_error)))  # B* and the stability verdicts
    return wall, err, (f"omega = {p.omega:.3g}: {len(b1.states)} states to B = {b1.values[-1]:.4g}, "
                       f"B* = {pf.B:.10g} (error {pf.error:.1e})")


def _pitchfork_curve():
    import numpy as np

    from etcheck.rod.buckled import secondary

    p = _operating_point().with_(B=0.0, omega=0.0)
    t0 = time.perf_counter()
    c = secondary.secondary_pitchfork_curve(p, np.linspace(0.0, 1.0, 10), N=32)
    wall = time.perf_counter() - t0
    return wall, max(pt.error / pt.B for pt in c.points), "omega = 0 ... 1, N = 32 and its check resolution"


SWEEP = """
import json, sys, time
from dataclasses import replace
from etcheck.runtime.heap import keep_freed_memory
keep_freed_memory()
import astropy.units as u
from etcheck.input.mission import load_mission
from etcheck.input.sweep_axes import parse_option
from etcheck.studies.sweep import SweepOptions, sweep
m = load_mission("missions/set.toml")
if sys.argv[1] == "undamped":
    m = m.with_tether(damping_time=0.0 * u.s)
axes = (parse_option("length", "50m:5km:40:log"), parse_option("spin", "0rpm:20rpm:40"))
t0 = time.perf_counter()
r = sweep(m, axes, SweepOptions(cache=None))
print(json.dumps({"wall": time.perf_counter() - t0, "error": r["grid"]["max_error"], "workers": r["cost"]["workers"]}))
"""


def _child(code: str, args: list[str], target: float) -> tuple[float, dict | str]:
    """Run ``code`` in a fresh interpreter; (wall [s], the JSON it printed last) or (wall, why it has none)."""
    t0 = time.perf_counter()
    proc = _run([sys.executable, "-c", code, *args], max(PATIENCE * target, 120.0))
    if proc is None:
        return time.perf_counter() - t0, f"stopped after {time.perf_counter() - t0:.0f} s"
    if proc.returncode != 0:
        return time.perf_counter() - t0, f"failed: {proc.stderr.strip()[-200:]}"
    return time.perf_counter() - t0, json.loads(proc.stdout.strip().splitlines()[-1])


def _sweep(kind: str, target: float):
    def measure():
        wall, out = _child(SWEEP, [kind], target)
        if isinstance(out, str):
            return wall, None, out
        return out["wall"], out["error"], f"{out['workers']} workers, in the sweep function"
    return measure


ROWS = (
    Row("etcheck missions/set.toml (HTML + PDF + JSON), cold", 4.0, False, _cli_check([], 4.0)),
    Row("etcheck missions/set.toml --format json, cold", 1.5, False, _cli_check(["--format", "json"], 1.5)),
    Row("etcheck missions/set.toml --draft --format json, cold", 1.0, False,
        _cli_check(["--draft", "--format", "json"], 1.0)),
    Row("draft check of SET itself (in a fresh process)", 0.05, False, _draft_check),
    Row("damped critical load at the operating spin", 0.03, False, _damped_root("B")),
    Row("damped critical spin at the operating load", 0.03, False, _damped_root("omega")),
    Row("undamped: critical values and stable spin windows", 0.3, False, _undamped_windows),
    Row("b1 pitchfork -> 4 B1, stability of every state, B*", 3.0, False, _b1_with_stability),
    Row("B*(omega) at 10 spins", 5.0, True, _pitchfork_curve),
    Row("etcheck diagram missions/set.toml --spin 0.25 --branches 3", 10.0, True,
        _cli_study(["diagram", "missions/set.toml", "--spin", "0.25", "--branches", "3"], 10.0, "diagram.json",
                   _diagram_error, repeat=2)),
    Row("etcheck damping-map missions/set.toml", 60.0, True,
        _cli_study(["damping-map", "missions/set.toml"], 60.0, "damping.json", _damping_error)),
    Row("40 x 40 length x spin sweep of SET, damped", 5.0, False, _sweep("damped", 5.0)),
    Row("40 x 40 length x spin sweep of SET, undamped", 60.0, True, _sweep("undamped", 60.0)),
)


def _reference_workload(repeat: int = 5, pick=min) -> float:
    """Milliseconds of a fixed mix of the rows' kinds of work, best of 5 (``pick`` of ``repeat`` runs): dense LU
    factors and solves at n = 396 (a branch state's operator at N = 32) and numpy on small arrays (the exact
    determinants). The same code everywhere: it tells how fast this machine is in this hour, to read the rows
    against (the speed of a shared machine drifts by 10-30 % within an hour, every row with it)."""
    import numpy as np
    import scipy.linalg as sla

    rng = np.random.default_rng(0)
    A, b, x = rng.standard_normal((396, 396)), rng.standard_normal(396), np.linspace(0.0, 1.0, 64)

    def once() -> None:
        for _ in range(20):
            lu = sla.lu_factor(A, check_finite=False)
            for _ in range(10):
                sla.lu_solve(lu, b, check_finite=False)
        for _ in range(3000):
            np.sin(x) * x + 1.0

    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        once()
        times.append(time.perf_counter() - t0)
    return 1e3 * pick(times)


def _machine_now() -> float:
    """The reference workload now, the median of 3 (a best-of hides a slow stretch), in milliseconds."""
    return _reference_workload(3, statistics.median)


def headline(quick: bool) -> list[tuple[str, float, float, float | None]]:
    """Print every row; returns the measured ones as (what, wall [s], target [s], largest stated error)."""
    measured = []
    _compile_bytecode()
    print(f"{len(os.sched_getaffinity(0))} cores, load average {os.getloadavg()[0]:.1f} at the start "
          "(times are wall times: on a busy machine they are longer); etcheck's bytecode compiled first")
    print(f"this machine now: reference workload {_reference_workload():.1f} ms (fixed work, best of 5; lower is "
          "faster: compare it between runs before comparing their rows)")
    print("machine: the reference workload (median of 3) just before and after the row, against its median now "
          "(1.00: as fast as at the start; 1.30: the row ran on a machine 30 % slower)")
    start = _machine_now()
    print(f"{'row':<62} {'time [s]':>9} {'target':>7} {'ratio':>6} {'error':>8} {'machine':>8}  note")
    for row in ROWS:
        if quick and row.slow:
            print(f"{row.what:<62} {'skipped':>9} {row.target:>7.3g} {'':>6} {'':>8} {'':>8}  --quick")
            continue
        before = _machine_now()
        try:
            wall, err, note = row.measure()
        except NotImplementedError as exc:
            print(f"{row.what:<62} {'n/a':>9} {row.target:>7.3g} {'':>6} {'':>8} {'':>8}  not available: {exc}")
            continue
        except Exception as exc:  # a failing row must not hide the others
            print(f"{row.what:<62} {'failed':>9} {row.target:>7.3g} {'':>6} {'':>8} {'':>8}  {type(exc).__name__}: {exc}")
            continue
        e = "n/a" if err is None else f"{err:.1e}"
        slow = max(before, _machine_now()) / start
        print(f"{row.what:<62} {wall:>9.3f} {row.target:>7.3g} {wall / row.target:>6.2f} {e:>8} {slow:>8.2f}  {note}",
              flush=True)
        measured.append((row.what, wall, row.target, err))
    return measured


BEGIN, END = "<!-- bench_headline:begin -->", "<!-- bench_headline:end -->"


def _seconds(x: float) -> str:
    return f"{x * 1e3:.3g} ms" if x < 0.1 else f"{x:.3g} s"


def write_markdown(path: Path, measured: list[tuple[str, float, float, float | None]]) -> None:
    """Rewrite the table between BEGIN and END of ``path``: a row measured now replaces the line of the same
    'what'; the others are kept."""
    text = path.read_text()
    head, rest = text.split(BEGIN, 1)
    body, tail = rest.split(END, 1)
    lines = [line for line in body.strip().splitlines() if line.startswith("| ")]
    header, rows = lines[:2], {line.split("|")[1].strip(): line for line in lines[2:]}
    stamp = time.strftime("%Y-%m-%d")
    for what, wall, target, err in measured:
        e = "" if err is None else f"{err:.1e}"
        rows[what] = f"| {what} | {_seconds(wall)} ({stamp}) | {_seconds(target)} | {e} |"
    header = header or ["| what | time | target | largest stated error |", "| --- | --- | --- | --- |"]
    path.write_text(head + BEGIN + "\n" + "\n".join(header + list(rows.values())) + "\n" + END + tail)


# ----------------------------------------------------------------------------- the fidelity trade

def _timed(mission):
    t0 = time.perf_counter()
    r = check(mission).results
    return time.perf_counter() - t0, r


def missions_table(paths: list[Path]) -> None:
    print(f"\n{'mission':<22} {'draft [s]':>9} {'sign-off [s]':>12}  {'margin (sign-off)':>18} {'draft - sign-off':>17}"
          f" {'stated error':>12}  model")
    for path in paths:
        m = load_mission(path)
        _timed(m.with_fidelity("draft"))  # warm: operator families and caches
        t_draft, draft = _timed(m.with_fidelity("draft"))
        t_sign, sign = _timed(m)
        for i, (a, b) in enumerate(zip(draft["margins"], sign["margins"])):
            diff = (abs(a["value"] - b["value"]) / b["value"]
                    if a["value"] not in (None, 0) and b["value"] not in (None, 0) else 0.0)
            label = path.stem if i == 0 else ""
            times = f"{t_draft:>9.3f} {t_sign:>12.2f}" if i == 0 else f"{'':>9} {'':>12}"
            value = "n/a" if b["value"] is None else f"{b['value']:.6g}"
            err = "n/a" if b["error"] is None else f"{b['error']:.1e}"
            print(f"{label:<22} {times}  {value:>18} {diff:>17.1e} {err:>12}  {b['name'][:40]} [{b['model']}]")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip the slow rows")
    ap.add_argument("--markdown", type=Path, default=None,
                    help="rewrite the headline table between the bench_headline markers of this file")
    ap.add_argument("--missions", default=None,
                    help="comma-separated mission files for the draft/sign-off table (default: missions/*.toml; "
                    "SET with --quick)")
    ap.add_argument("--no-missions", action="store_true", help="skip the draft/sign-off table")
    args = ap.parse_args()
    measured = headline(args.quick)
    if args.markdown is not None:
        write_markdown(args.markdown, measured)
    if not args.no_missions:
        paths = ([Path(p) for p in args.missions.split(",")] if args.missions
                 else [SET] if args.quick else sorted((ROOT / "missions").glob("*.toml")))
        missions_table(paths)


if __name__ == "__main__":
    main()
