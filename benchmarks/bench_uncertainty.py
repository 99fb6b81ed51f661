"""Uncertainty study timing (a measurement, not a test).

One row per case: the check without the study, then the probability of each
margin falling short: method, value (or bound) and stated error or interval,
margin evaluations by the check's route, points of the integrand, seconds,
and the process's peak resident memory so far (MB). Cases:

* the static SET with EI normal 15 % and B0 lognormal 30 % at nominal margins
  2.5, 3, 4, 8 and 22 (rung 0, closed form: quadrature), and with four inputs
  (sampling of a closed form);
* missions/set-tolerances.toml (spinning SET, static pencils) and the same
  with four inputs (sampling on the pencils);
* missions/tape-tether.toml (exact determinant) with its length normal 10 %
  (one input) and with EI normal 15 % and B0 lognormal 30 % (two inputs).

Run:  python benchmarks/bench_uncertainty.py   (BLAS pinned to one thread; both cores used for margins)
"""

from __future__ import annotations

import os
import resource
import time
import tomllib
from dataclasses import replace
from pathlib import Path

from etcheck.checks.pipeline import check
from etcheck.checks.rungs.straight import DEFAULT_OPTIONS
from etcheck.input.mission import mission_from_dict

MISSIONS = Path(__file__).resolve().parents[1] / "missions"
EI_FIELD = {"bending_stiffness": {"distribution": "normal", "sigma": "15 %"},
            "axial_field": {"distribution": "lognormal", "sigma": "30 %"}}
FOUR = EI_FIELD | {"length": "±3 %", "current": "±10 %"}


def mission(base: str, uncertainty: dict | None, **operation) -> dict:
    data = tomllib.loads((MISSIONS / base).read_text())
    data["operation"] |= operation
    if uncertainty is not None:
        data["uncertainty"] = uncertainty
    else:
        data.pop("uncertainty", None)
    return data


CASES = [(f"static SET, margin {m:g}, EI + B0", mission("set-static.toml", EI_FIELD, current=f"{159.0720448 / m} A"))
         for m in (2.5, 3.0, 4.0, 8.0, 22.0)] + [
    ("static SET, margin 3, four inputs", mission("set-static.toml", FOUR, current=f"{159.0720448 / 3} A")),
    ("set-tolerances (pencils), EI + B0", mission("set-tolerances.toml", EI_FIELD)),
    ("set-tolerances (pencils), four inputs", mission("set-tolerances.toml", FOUR)),
    ("tape tether (exact determinant), length", mission("tape-tether.toml", {"length": {"distribution": "normal",
                                                                                         "sigma": "10 %"}})),
    ("tape tether (exact determinant), EI + B0", mission("tape-tether.toml", EI_FIELD)),
]


def peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main() -> None:
    print(f"cores: {len(os.sched_getaffinity(0))}")
    options = replace(DEFAULT_OPTIONS, accuracy_N=())
    for name, data in CASES:
        plain = mission_from_dict(mission_base(data))
        t0 = time.perf_counter()
        check(plain, options)
        t_check = time.perf_counter() - t0
        t0 = time.perf_counter()
        r = check(mission_from_dict(data), options).results
        t_total = time.perf_counter() - t0
        u = r["uncertainty"]
        print(f"== {name}: check {t_check:.2f} s, with the study {t_total:.2f} s (study {u['elapsed_s']:.2f} s, "
              f"elasticities and swings {u['sensitivity_time_s']:.2f} s); peak memory {peak_mb():.0f} MB")
        for p in u["probabilities"]:
            if p["value"] is None:
                value = f"< {p['bound']:.2g}" if p["bound"] is not None else "not answered"
            elif p["method"] == "sampling":
                value = f"{p['value']:.6g} [{p['low']:.6g}, {p['high']:.6g}] (95 %)"
            else:
                value = f"{p['value']:.10g} (error {p['error']:.1e} relative)" if p["error"] else f"{p['value']:.10g}"
            cross = p["cross_check"]
            extra = f"; FORM {cross['form']:.4g}, SORM {cross['sorm']}" if cross else ""
            print(f"  P({p['margin']} < {p['required']:g}) = {value}: {p['method']}, {p['evaluations']} margin "
                  f"evaluations, {p['points']} points, {p['elapsed_s']:.2f} s{extra}")


def mission_base(data: dict) -> dict:
    """The same mission without its [uncertainty] table."""
    return {k: v for k, v in data.items() if k != "uncertainty"}


if __name__ == "__main__":
    main()
