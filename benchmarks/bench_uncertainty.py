"""Uncertainty study timing (a measurement, not a test; issue 15).

1. Sensitivities (elasticities) of every margin of missions/set.toml (target < 1 s).
2. Probability of failure to +-10 % (95 %) for the spinning SET with 15 % stiffness and
   30 % field tolerance (missions/set-tolerances.toml), on every local core (target < 30 s on 2):
   at the mission's required margin 2 (P ~ 1.2e-4), and at the required margin that puts
   P near 1e-3 (2.186: 2.984 x sqrt(1 - 3.09 x 0.15)), the regime the target names.
Run:  python benchmarks/bench_uncertainty.py
"""

from __future__ import annotations

import os
import time
from dataclasses import replace
from pathlib import Path

from etcheck.input.mission import load_mission
from etcheck.studies.uncertainty import failure_probabilities, margin_model, sensitivities, study

MISSIONS = Path(__file__).resolve().parents[1] / "missions"


def main() -> None:
    print(f"cores: {len(os.sched_getaffinity(0))}")
    m = load_mission(MISSIONS / "set.toml")
    t0 = time.perf_counter()
    st = study(m)
    print(f"== sensitivities of every margin of set.toml: {time.perf_counter() - t0:.3f} s (route: {st.route})")
    for s in st.sensitivities:
        print(f"  {s.margin} (nominal {s.nominal:.6g})")
        for e in s.elasticities:
            print(f"    {e.input:20s} {'—' if e.value is None else f'{e.value:+.6f}'}  {e.method}")
    mt = load_mission(MISSIONS / "set-tolerances.toml")
    for req in (mt.required_margin, 2.186):
        mm = replace(mt, required_margin=req)
        model = margin_model(mm)
        t0 = time.perf_counter()
        sens = sensitivities(model)
        probs = failure_probabilities(model, mm.uncertainty, sens, target=0.1)
        dt = time.perf_counter() - t0
        print(f"== set-tolerances.toml, required margin {req:g}: {dt:.2f} s (sensitivities + probabilities)")
        for p in probs:
            print(f"  P({p.margin} < {req:g}) = {p.value:.4g} [{p.low:.4g}, {p.high:.4g}], rel. half-width "
                  f"{p.relative_half_width if p.relative_half_width is None else round(p.relative_half_width, 4)}, "
                  f"{p.samples} samples, {p.evaluations} evaluations, conditioned on {p.conditioned_on}, settled {p.settled}")


if __name__ == "__main__":
    main()
