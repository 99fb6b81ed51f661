"""Tethers as they fly (issue 16): strong tension and tapes go to the exact determinant, in milliseconds.

The planner hands scenes whose end boundary layers are thinner than collocation resolves (or whose
weak axis is nearly a string) to :mod:`etcheck.rod.straight.exact.roots`; where both routes apply they agree.
"""

from __future__ import annotations

import math
import time

import pytest
from helpers import set_like

from etcheck import check, mission_from_dict
from etcheck.checks.plan import EXACT, LAYER_MIN, SPECTRAL, boundary_layer, plan, straight_route
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.damped_critical import damped_critical
from etcheck.rod.straight.exact.roots import exact_critical, string_limit_load
from etcheck.scaling import scale, scene

SET = dict(P=1e-3, R=21 / 38, Gamma=1 / 1.3, gamma=0.04375)

#: the issue's tape: 500 m aluminium, EI1 = 3.65 N m2, EI2 = 9.3e-6 N m2, 2.7 g/m, 1 A in 30 uT, 0.18 N
TAPE = dict(length="500 m", bending_stiffness=["3.65 N m2", "9.3e-6 N m2"], mass_per_length="2.7 g/m",
            rotary_inertia_ratio=1e-9, current="1 A", axial_field="30 uT", end_tension="0.18 N")


def test_planner_routes_by_boundary_layer_width():
    assert straight_route(RodParameters(**SET, T=1.0)) == SPECTRAL
    assert boundary_layer(RodParameters(**SET, T=1e4)) < LAYER_MIN
    assert straight_route(RodParameters(**SET, T=1e4)) == EXACT
    assert straight_route(RodParameters(P=1e-9, R=2.5e-6, Gamma=0.75, gamma=0.01)) == EXACT  # string-like weak axis
    assert boundary_layer(RodParameters(**SET)) == math.inf


@pytest.mark.parametrize("T,omega", [(2.0, 0.0), (5.0, 0.3), (0.5, 0.5)])
def test_both_routes_agree_where_both_apply(T, omega):
    p = RodParameters(**SET, T=T, omega=omega, B=0.2)
    a, b = damped_critical(p), exact_critical(p)
    assert a.converged and b.converged
    for x, y in ((a.critical_load, b.critical_load), (a.critical_spin, b.critical_spin)):
        assert y.value == pytest.approx(x.value, rel=1e-9)


def test_the_issue_tape_is_answered_by_the_exact_rung_fast():
    t0 = time.perf_counter()
    r = check(set_like(name="tape", check={"fidelity": "draft"}, **TAPE)).results
    elapsed = time.perf_counter() - t0
    assert r["plan"]["route"] == EXACT and r["verdict"] == "pass"
    margin = r["margins"][0]
    assert "exact characteristic determinant" in margin["model"]
    # the string limit with its boundary-layer corrections: I B0 = B f EI1 / L^3, B -> 2 pi T (1 + ...)
    p = RodParameters(**{k: r["scaled"][k] for k in ("P", "R", "Gamma", "f", "T", "gamma")})
    critical = string_limit_load(p, order=2) * r["scales"]["load_N_per_m"]
    assert margin["critical"] == pytest.approx(critical, rel=1e-5)
    assert margin["critical"] == pytest.approx(2 * math.pi * 0.18 / 500, rel=2e-3)  # 2 pi T / L
    assert margin["error"] < 1e-8
    assert elapsed < 30  # minutes before (no answer); generous bound on a loaded machine, not a benchmark


def test_undamped_thin_layers_go_to_the_exact_undamped_determinant():
    """Without damping flutter is possible; the exact undamped determinant locates it (no longer incomplete)."""
    p = RodParameters(P=1e-9, R=2.5e-6, Gamma=0.75, T=1e3, omega=0.1)
    chosen = plan(p)
    assert chosen.complete and chosen.route == EXACT and "undamped" in chosen.reason


def test_buckled_tape_is_beyond_rungs_2_3_and_says_why():
    """Past its first critical load a tape's coil has boundary layers rung 2 cannot resolve: said, not attempted."""
    r = check(set_like(name="tape", **(TAPE | {"current": "200 A"}))).results
    post = r["postbuckling"]
    assert "fail" in [m["verdict"] for m in r["margins"]] and post is not None and post["computed"] is False
    assert r["verdict"] == "outside"  # 200 A across the tether bows it far past the model's limit
    assert "beyond rungs 2-3" in post["reason"]


def test_exact_map_rows_shared_with_a_helper_are_the_rows_one_by_one(monkeypatch, forks_allowed):
    """The damped map's rows on the exact route (one first determinant root per spin) are independent: on two
    cores a forked helper takes half of them; the same rows, in order, as one by one."""
    from dataclasses import replace

    import etcheck.checks.rungs.straight as straight
    from etcheck.checks.rungs.straight import DEFAULT_OPTIONS, linear_stability
    from etcheck.runtime.parallel import serial, split_map

    shared_out = []

    def counted(fn, items):
        shared_out.append(len(items))
        return split_map(fn, items)

    monkeypatch.setattr(straight, "split_map", counted)
    scaled = scale(scene(mission_from_dict(set_like(name="tape", **TAPE))))
    options = replace(DEFAULT_OPTIONS, row_points=9)
    shared = linear_stability(scaled, options, EXACT).stability_map.stable_rows
    with serial():
        alone = linear_stability(scaled, options, EXACT).stability_map.stable_rows
    assert shared == alone and shared_out == [9, 9]  # every row goes through the shared map
    rest = exact_critical(scaled.params).spin_at_rest.value  # the unloaded tether's critical spin: empty past it
    assert [len(r.IB0_N_per_m) for r in shared] == [int(r.omega < rest) for r in shared]
    loads = [r.IB0_N_per_m[0][1] for r in shared if r.IB0_N_per_m]
    assert len(loads) >= 4 and all(0 < b for b in loads)
    assert loads == sorted(loads, reverse=True)  # spin lowers the critical load


def test_exact_map_rows_agree_with_the_critical_spin_at_the_operating_load():
    """The shipped tape with one current and its smallest tension (the exact route): every spin row of its map below
    the critical spin at the operating load holds the operating load in its stable interval, and no row above it
    does (near the unloaded critical spin the rows' roots carry ~1e-8 from their two formulations: held to the
    margins' 1e-10 they were left empty, drawn unstable)."""
    from helpers import tape

    lin = check(tape(current_profile=False, end_masses=False)).results["linear"]
    critical, load = lin["critical_spin"]["rpm"], lin["operating"]["IB0_N_per_m"]
    rows = lin["stability_map"]["stable_rows"]
    assert sum(row["spin_rpm"] < critical for row in rows) >= 30
    for row in rows:
        holds = any(a <= load < b for a, b in row["IB0_N_per_m"])
        assert holds == (row["spin_rpm"] < critical), row
