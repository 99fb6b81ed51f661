"""Rung 0 for a mission: the static buckling of the straight tether, exact and analytic.

At zero spin and zero end tension the critical loads are B_k = beta_k^3 sqrt(R)/f
with beta_k the double zeros of chi(beta) (arXiv:0810.3668, eq. (91) and Fig. 4),
or of its closed-form analogue for pinned ends (docs/model.md); the natural frequencies are those of the
paper's Sec. VI B for the tether's ends, under the mission's end tension. Dimensionless
answers with their SI counterparts (I·B0 in N/m, frequencies in rad/s and Hz).
"""

from __future__ import annotations

import math

import numpy as np

from etcheck.checks.results.sections_straight import (
    ChiCurve,
    ModeShape,
    NaturalFrequencies,
    NaturalFrequency,
    StaticBuckling,
    StaticCriticalLoad,
    StaticLimits,
    StraightRodSection,
)
from etcheck.jsonable import fields_of
from etcheck.rod.core.ends import describe
from etcheck.rod.straight import analytic
from etcheck.scaling import Scaled, Scales, Scene

#: critical loads listed (and chi zeros located)
N_LOADS = 5


def static_buckling(scaled: Scaled) -> StaticBuckling:
    """Rung 0 answers for the scene: critical loads, frequencies, mode shape.

    All loads are at omega = 0, T = 0 (eq. (91), or its analogue for the
    scene's ends); dimensionless B and I B0 in N/m. The natural frequencies are the tether's under its end
    tension T (no load, no spin).
    """
    p, scales = scaled.params, scaled.scales
    ends = p.ends
    roots = analytic.static_roots(ends, N_LOADS)
    loads: list[StaticCriticalLoad] = []
    for r, B in zip(roots, analytic.critical_loads(p.R, p.f, N_LOADS, ends)):
        B = float(B)
        loads.append(
            StaticCriticalLoad(
                k=r.k,
                beta=r.beta,
                B=B,
                IB0_N_per_m=scales.line_load(B),
                multiplicity=r.kernel_dimension,
                chi_residual=r.residual,
                chi_curvature=r.curvature,
                relative_error=3.0 * r.error,
            )
        )
    s = np.linspace(0.0, 1.0, 101)
    x, y = analytic.buckling_mode(1, p.R, s, ends)
    op_beta = analytic.beta_of_load(p.B, p.R, p.f)
    beta_grid = np.linspace(0.0, min(max(1.25 * roots[2].beta, 1.15 * op_beta), 1.1 * roots[-1].beta), 600)
    # zeros of chi below the operating beta (asymptotically pi/3 + 2 pi n beyond the tabulated ones; other ends:
    # analytic.asymptotic_count)
    exceeded = sum(r.beta <= op_beta for r in roots)
    if op_beta > roots[-1].beta:
        exceeded = analytic.asymptotic_count(op_beta, ends)
    return StaticBuckling(
        model="rung 0 (analytic)",
        critical_loads=tuple(loads),
        operating_beta=op_beta,
        loads_exceeded=exceeded,
        operating_B=p.B,
        first_mode=ModeShape(s=tuple(s.tolist()), x=tuple(x.tolist()), y=tuple(y.tolist())),
        chi_curve=ChiCurve(beta=tuple(beta_grid.tolist()),
                           chi_scaled=tuple(analytic.characteristic_scaled(beta_grid, ends).tolist())),
        natural_frequencies=_natural_frequencies(p, scales),
    )


def _natural_frequencies(p, scales) -> NaturalFrequencies:
    """The frequencies of the straight tether under its end tension (no load, no spin); a compressive end force
    is left out (under it the frequencies are lower, and the first reaches zero at the Euler load), and said."""
    T = max(p.T, 0.0)
    model = (f"exact: the Rayleigh beam {describe(p.ends)} under the end tension, each axis (arXiv:0810.3668 "
             "Sec. VI B with T); torsion does not feel the tension")
    if p.T < 0:
        model += "; the end force is compressive: these are the frequencies without it (under it they are lower)"
    ends = p.ends
    return NaturalFrequencies(
        model=model, tension_N=scales.tension(T),
        bending_weak=_frequencies(analytic.bending_frequencies(p.P, p.R, p.f, 5, "weak", ends, T), scales),
        bending_stiff=_frequencies(analytic.bending_frequencies(p.P, p.R, p.f, 5, "stiff", ends, T), scales),
        torsion=_frequencies(analytic.torsion_frequencies(p.P, p.Gamma, p.f, 5, ends), scales))


def _frequencies(mus, scales: Scales) -> tuple[NaturalFrequency, ...]:
    """The finite dimensionless frequencies mu (units of the reference frequency omega_c) in rad/s and Hz."""
    return tuple(NaturalFrequency(mu=float(m), rad_s=float(scales.rad_s(m)), Hz=float(scales.hz(m))) for m in mus
                 if math.isfinite(m))


def static_limits(static: StaticBuckling, sc: Scene, scales: Scales) -> StaticLimits:
    """Critical current at the worst field and critical length at the operating load.

    Static buckling (omega = T = 0): B ∝ L^3 and the static loads do not
    depend on P, so L_c = L (B_1 / B)^(1/3). SI; None where the operating
    value is zero (no limit).
    """
    first = static.critical_loads[0]
    critical = first.IB0_N_per_m
    return StaticLimits(
        critical_IB0_N_per_m=critical,
        critical_current_A=scales.current(first.B) if sc.field.axial else None,
        critical_length_m=sc.length * (critical / sc.load) ** (1 / 3) if sc.load else None,
    )


def straight_rod(scaled: Scaled, sc: Scene) -> StraightRodSection:
    """The ``straight_rod`` section: rung 0's answers (:func:`static_buckling`) with the limits they set
    (:func:`static_limits`)."""
    rung0 = static_buckling(scaled)
    return StraightRodSection(**fields_of(rung0), limits=static_limits(rung0, sc, scaled.scales))
