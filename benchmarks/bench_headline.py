"""The headline: time and margins of the draft and the sign-off check of every shipped mission.

    python benchmarks/bench_headline.py [--missions missions/set.toml,...] [--no-cli]

For each mission: the check in this process (draft warm, sign-off), the margins of both and their
largest relative difference against the sign-off's stated errors; then the cold CLI runs the
issue's targets name (`etcheck missions/set.toml` with HTML + PDF + JSON, `--format json`,
`--draft --format json`) with the ratio to each target. One BLAS thread. A measurement, not a test.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from etcheck.checks.pipeline import check  # noqa: E402
from etcheck.input.mission import load_mission  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
#: (command, target wall time [s]) from issue 10
CLI_TARGETS = ((["missions/set.toml"], 4.0), (["missions/set.toml", "--format", "json"], 1.5),
               (["missions/set.toml", "--draft", "--format", "json"], 1.0))


def _timed(mission):
    t0 = time.perf_counter()
    r = check(mission).results
    return time.perf_counter() - t0, r


def missions_table(paths: list[Path]) -> None:
    print(f"{'mission':<22} {'draft [s]':>9} {'sign-off [s]':>12}  {'margin (sign-off)':>18} {'draft - sign-off':>17}"
          f" {'stated error':>12}  model")
    for path in paths:
        m = load_mission(path)
        _timed(replace(m, fidelity="draft"))  # warm: operator families and caches
        t_draft, draft = _timed(replace(m, fidelity="draft"))
        t_sign, sign = _timed(m)
        for i, (a, b) in enumerate(zip(draft["margins"], sign["margins"])):
            diff = (abs(a["value"] - b["value"]) / b["value"]
                    if a["value"] not in (None, 0) and b["value"] not in (None, 0) else 0.0)
            label = path.stem if i == 0 else ""
            times = f"{t_draft:>9.3f} {t_sign:>12.2f}" if i == 0 else f"{'':>9} {'':>12}"
            value = "n/a" if b["value"] is None else f"{b['value']:.6g}"
            err = "n/a" if b["error"] is None else f"{b['error']:.1e}"
            print(f"{label:<22} {times}  {value:>18} {diff:>17.1e} {err:>12}  {b['name'][:40]} [{b['model']}]")


def cli_table() -> None:
    print("\ncold CLI runs (new process each), against the targets of issue 10")
    for args, target in CLI_TARGETS:
        with tempfile.TemporaryDirectory() as out:
            t0 = time.perf_counter()
            proc = subprocess.run([sys.executable, "-m", "etcheck", *args, "--out", out], cwd=ROOT,
                                  capture_output=True, text=True)
            wall = time.perf_counter() - t0
        print(f"  etcheck {' '.join(args):<48} {wall:6.2f} s  target {target:4.1f} s  ratio {wall / target:5.2f}"
              f"  exit {proc.returncode}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--missions", default=None, help="comma-separated mission files (default: missions/*.toml)")
    ap.add_argument("--no-cli", action="store_true", help="skip the cold CLI runs")
    args = ap.parse_args()
    paths = ([Path(p) for p in args.missions.split(",")] if args.missions
             else sorted((ROOT / "missions").glob("*.toml")))
    missions_table(paths)
    if not args.no_cli:
        cli_table()


if __name__ == "__main__":
    main()
