"""Rung 3 benchmark: stability of buckled, whirling SET tethers (dimensionless).

First the targets of issue 10 for rungs 2-3, each with its wall time, its
largest stated error and the ratio of the time to the target (b1 from its
pitchfork to 4 B1 with the stability of every state and B* located; B*(omega)
at 10 spins; the bifurcation diagram at spin 0.25 with 3 branches and the
damping map at their defaults, in-process: the CLI adds its imports and the
report). Then, per curve, the wall time (one core, BLAS pinned to one thread
with threadpoolctl) and the estimated numerical error (two resolutions of the
operator and of the base state). Not a test: nothing here is asserted; on a
shared machine, repeat it.

    python benchmarks/bench_rung3.py [--quick] [--targets-only]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from etcheck.rod.buckled import branches as br  # noqa: E402
from etcheck.rod.buckled import damping_map, hopf, secondary, spectra, structure  # noqa: E402
from etcheck.rod.buckled import equilibria as eq  # noqa: E402
from etcheck.rod.core.parameters import RodParameters  # noqa: E402

SET = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3)  # Gamma = 1/(1 + nu), nu = 0.3, as the missions
#: B* of b1 at omega = 0 from an independent solver (README, docs/validation.md)
B_STAR_INDEPENDENT = 1.94246251
MISSION = os.path.join(os.path.dirname(__file__), "..", "missions", "set.toml")


def _row(what: str, target: float, wall: float, error: float | None, note: str = "") -> None:
    err = "      -" if error is None else f"{error:7.1e}"
    print(f"  {what:<58s} {wall:7.2f} s  target {target:5.1f} s  ratio {wall / target:5.2f}  error {err}  {note}")


def targets(quick: bool) -> None:
    """The rung 2-3 targets of issue 10: time, largest stated error, ratio to the target."""
    print("[0] targets (wall time, time / target, largest stated error: relative for B*, absolute for "
          "Re lambda and the measures)")
    t = time.perf_counter()
    start = br.primary_branches(SET, 1, 32)[0]
    b1 = br.continue_branch(SET, start, stop=(0.0, 4.0 * start.load))
    sp = spectra.branch_spectra(b1, 0.04375, k=6)
    pf = secondary.secondary_pitchfork(SET, 0.0, N=32, N_check=48, branch=b1)
    wall = time.perf_counter() - t
    _row("b1 pitchfork -> 4 B1, stability of every state, B*", 3.0, wall,
         max(pf.error / pf.B, float(np.nanmax(sp.max_real_error))),
         f"B* = {pf.B:.10f} (stated {pf.error:.1e}, independent {B_STAR_INDEPENDENT}: "
         f"{abs(pf.B - B_STAR_INDEPENDENT):.1e}), {len(b1.states)} states")
    t = time.perf_counter()
    c = secondary.secondary_pitchfork_curve(SET, np.linspace(0.0, 1.0, 10), N=32, N_check=48)
    _row("B*(omega) at 10 spins (0 ... 1, N = 32 and 48)", 5.0, time.perf_counter() - t,
         max(p.error / p.B for p in c.points), f"B*(0) = {c.points[0].B:.10f}, B*(1) = {c.points[-1].B:.8f}")
    if quick:
        return
    from etcheck.input.mission import load_mission
    from etcheck.studies.damping_map import damping_results
    from etcheck.studies.diagram import diagram_study

    m = load_mission(MISSION)
    t = time.perf_counter()
    d = diagram_study(m, omega=0.25)
    errs = [b.get(k) for b in d["diagram"]["branches"] for k in ("measure1_error", "deflection_error")]
    _row("diagram at spin 0.25, 3 branches (in-process)", 10.0, time.perf_counter() - t,
         max((e for e in errs if e is not None), default=None),
         ", ".join(f"{b['label']} {b['points']}" for b in d["diagram"]["branches"]))
    t = time.perf_counter()
    r = damping_results(m)
    _row("damping map at its defaults (in-process)", 60.0, time.perf_counter() - t, r["study"]["largest_error"],
         f"{r['study']['timing']['points']} b1 states, curve {r['study']['curve_time_s']:.1f} s")


def pitchfork_curve(omegas, N, N_check):
    t = time.perf_counter()
    c = secondary.secondary_pitchfork_curve(SET, omegas, N=N, N_check=N_check)
    print(f"\n[1] secondary pitchfork B*(omega) of b1, N = {N} vs {N_check}: {time.perf_counter() - t:.1f} s")
    print("    omega      B*(N)          B*(N_check)     |error|   measure1")
    for p in c.points:
        print(f"    {p.omega:5.2f}  {p.B:.9f}  {p.B_check:.9f}  {p.error:.1e}  {p.measure1:.4f}")
    return c


def b1_static(N):
    t = time.perf_counter()
    start = br.primary_branches(SET, 1, N)[0]
    b1 = br.continue_branch(SET, start, stop=(0.0, 2.5))
    t_b = time.perf_counter() - t
    sp = spectra.branch_spectra(b1, 0.04375, k=6, state_stride=4)
    change = np.nonzero(np.diff(sp.stable.astype(int)))[0]
    print(f"\n[2] b1 at omega = 0, gamma = 0.04375, N = {N}: branch {t_b:.1f} s, spectra {sp.time:.1f} s "
          f"({len(b1.states)} points); operator error {np.max(sp.errors[1:]):.1e}, "
          f"state error {np.nanmax(sp.state_errors):.1e}")
    for i in change:
        print(f"    stability changes between B = {sp.values[i]:.4f} and {sp.values[i + 1]:.4f} "
              f"({'stable->unstable' if sp.stable[i] else 'unstable->stable'})")
    print(f"    path crossings flagged: {len(sp.crossings)}")
    return b1


def spun_b1(Ns, omega_max, gammas):
    print(f"\n[3] b1 at B = 1.2 continued in omega to {omega_max}: Hopf search")
    res = {}
    for N in Ns:
        t = time.perf_counter()
        bw = secondary.b1_spin_branch(SET, 1.2, omega_max, N)
        t_b = time.perf_counter() - t
        for g in gammas:
            sp = spectra.branch_spectra(bw, g, k=6, state_stride=4)
            scan = hopf.find_hopf(bw, g, k=6)
            i = int(np.nanargmax(sp.max_real))
            res[(N, g)] = sp
            print(f"    N = {N} (check {sp.N_check}), gamma = {g}: branch {t_b:.1f} s, spectra {sp.time:.1f} s, "
                  f"hopf scan {scan.time:.1f} s; stable everywhere: {bool(np.all(sp.stable))}; "
                  f"max Re lambda = {sp.max_real[i]:.4e} at omega = {sp.values[i]:.3f} "
                  f"(op. error {sp.max_real_error[i]:.1e}); complex modes max Re {np.nanmax(scan.max_real_complex):.4e}"
                  f" (error {np.nanmax(scan.error):.1e}); Hopf points: {len(scan.points)}; "
                  f"base-state error {np.nanmax(sp.state_errors):.1e}")
    for g in gammas:
        a, b = res[(Ns[0], g)], res[(Ns[-1], g)]
        w = np.linspace(0.0, omega_max, 27)
        da = np.interp(w, a.values, a.max_real)
        db = np.interp(w, b.values, b.max_real)
        print(f"    gamma = {g}: max Re lambda on a common omega grid, N = {Ns[0]} vs {Ns[-1]} base states: "
              f"max difference {np.max(np.abs(da - db)):.1e} (interpolation included)")
    a = res[(Ns[-1], gammas[0])]
    print(f"    omega   least-damped modes (gamma = {gammas[0]:g}, N = {Ns[-1]}), labels")
    for i in range(0, len(a.values), 4):
        lam = a.eigenvalues[i, :3]
        print(f"    {a.values[i]:5.2f}  " + "  ".join(f"{z.real:+.4e}{z.imag:+.4f}j" for z in lam)
              + "  " + ",".join(a.labels[i, :3]))
    for om in (0.0, 1.5, 2.2, 4.0, 6.0):
        st = secondary.b1_state(SET, 1.2, om, N=Ns[-1])
        c = structure.structure_check(st, gammas=(0.01, 0.04375))
        print(f"    structure at omega = {om}: index(K) = {c.index}, unstable(gamma) = {c.unstable_damped}, "
              f"Hamiltonian defect {c.hamiltonian_defect:.1e}, K asymmetry {c.stiffness_asymmetry:.1e}, "
              f"max |Re| undamped {c.max_real_undamped:.1e}")


def b2_check():
    print("\n[4] b2 at omega = 0 (paper: unstable)")
    for N in (24, 32):
        start = br.primary_branches(SET, 1, N)[1]
        b2 = br.continue_branch(SET, start, stop=(0.0, 2.5))
        for B in (0.7, 1.2, 2.0):
            st = br.locate(b2, lambda s: s.params.B, B)[1]
            for n_op in (N, N + 16):
                c = structure.structure_check(st, N=n_op, gammas=(0.01, 0.04375))
                lam = spectra.operator_eigenvalues(spectra.damped_operator(st.params, st, n_op), 0.0, 8, False)
                print(f"    base N = {N}, operator N = {n_op}, B = {B}: measure1 {eq.measure1(st):.4f}, "
                      f"index(K) = {c.index}, unstable(gamma) = {c.unstable_damped}, "
                      f"max|Re| undamped {c.max_real_undamped:.1e}, lowest |lambda| {np.min(np.abs(lam)):.6f}")


def damping(B_grid, omega_grid, N):
    t = time.perf_counter()
    dm = damping_map.damping_map(SET, B_grid, omega_grid, gammas=damping_map.HOPF_GAMMAS, N=N)
    wall = time.perf_counter() - t
    print(f"\n[5] damping map, {len(omega_grid)} x {len(B_grid)} grid, gammas {damping_map.HOPF_GAMMAS}, N = {N} vs "
          f"{dm.N_check}: {wall:.1f} s ({dm.timing['points']} b1 points; equilibria "
          f"{dm.timing['equilibria_s']:.1f} s, spectra {dm.timing['spectra_s']:.1f} s for all gammas)")
    print(f"    max two-resolution error of max Re lambda: {np.nanmax(dm.error):.1e}")
    print(f"    max Re lambda over the stable region, all gammas: {np.nanmax(dm.max_real):.3e} "
          f"(> 0 would be a Hopf/instability inside)")
    print("    secondary pitchfork B* at the grid omegas:", np.round(dm.curve_B, 4).tolist())
    print("    primary pitchfork of b1 (-inf: lifted off):", np.round(dm.primary_B, 4).tolist())
    for w, B in ((0.0, 1.2), (0.5, 1.2), (1.0, 2.0), (2.0, 1.2), (2.0, 4.0), (3.0, 6.0)):
        iw = int(np.argmin(np.abs(dm.omega - w)))
        ib = int(np.argmin(np.abs(dm.B - B)))
        if not dm.inside[iw, ib]:
            continue
        row = ", ".join(f"g={g}: decay {dm.decay[k, iw, ib]:.2e} zeta {dm.zeta[k, iw, ib]:.2e} "
                        f"logdec {dm.log_decrement[k, iw, ib]:.3f}" for k, g in enumerate(dm.gammas))
        print(f"    omega={dm.omega[iw]:.2f} B={dm.B[ib]:.2f}: {row}")
    return dm


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--targets-only", action="store_true")
    ap.add_argument("--json", default=None, help="write the damping map and curve here")
    a = ap.parse_args()
    with threadpool_limits(limits=1):
        t0 = time.perf_counter()
        targets(a.quick)
        if a.targets_only:
            return
        omegas = [0.0, 0.25, 0.5, 1.0] if a.quick else [0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0]
        curve = pitchfork_curve(omegas, 32, 40)
        if not a.quick:  # high spin: the coiled states at B* ~ 6..16 need more points
            pitchfork_curve([2.0, 3.0, 4.0], 48, 64)
        b1_static(32)
        spun_b1((24, 32), 4.0 if a.quick else 6.5, (0.01, 0.04375))
        b2_check()
        Bg = np.arange(0.25, 6.01, 0.25) if not a.quick else np.arange(0.5, 3.01, 0.5)
        wg = np.array([0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0]) if not a.quick else np.array([0.0, 0.5, 1.0])
        dm = damping(Bg, wg, 24)
        print(f"\ntotal {time.perf_counter() - t0:.1f} s")
        if a.json:
            with open(a.json, "w") as fh:
                json.dump({"curve": curve.as_dict(), "damping_map": dm.as_dict()}, fh)


if __name__ == "__main__":
    main()
