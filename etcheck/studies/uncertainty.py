"""Which input a margin hinges on: elasticities, tolerance swings and the
probability of falling below the required margin.

Everything here works on SI floats and the dimensionless parameters of
:mod:`etcheck.scaling`; units are crossed only by the mission parser.

**Margins.** The margins of the check, re-evaluated at perturbed inputs by the
fastest exact route of the nominal point:

* rung 0 (omega = T = 0): margin = B_1(R) / B = beta_1^3 sqrt(EI1 EI2) / (|I B0| L^3),
  closed form, vectorised with numpy;
* damped rung 1 (or any rod without spin): first roots of the static pencils
  (:func:`etcheck.rod.straight.damped_critical.first_root`): load margin B_c(omega, T) / B,
  spin margin omega_c(B, T) / omega. The static pencil (lambda = 0) does not
  contain the damping gamma, so every pencil is evaluated at the nominal gamma
  (which also lets samples share the assembled operators);
* undamped and spinning: the spectral scans of rung 1 (seconds per point;
  elasticities only, no probability).

**Elasticities** d ln margin / d ln input are exact where the model is a power
law (rung 0: EI1 1/2, EI2 1/2, L -3, I -1, B0 -1, the rest 0; pencils: the load
margin is B_c / B so I and B0 are exactly -1, the spin margin is omega_c / omega
so the spin rate is exactly -1, and damping is exactly 0). Elsewhere they are
central differences of ln margin in ln R, ln Gamma, ln P, ln omega, ln B, ln T
with relative step ``STEP`` = 1e-3 at a fixed Chebyshev resolution (truncation
error ~ STEP^2, round-off ~ 1e-13 / STEP), carried to the physical inputs by
the exact Jacobian of the scalings (omega_c = sqrt(f EI1 / (rho A L^4)),
B = |I B0| L^3 / (f EI1), T = T L^2 / (f EI1), P ~ L^-2, R = EI2/EI1,
Gamma = 2 GJ / (EI1 + EI2)).

**Probability of falling short**: randomised quasi-Monte Carlo with
conditioning. For each margin the input that moves it most (largest
|elasticity| x log-spread) is integrated exactly: given the other inputs the
margin is monotone in it, so P(margin < required | others) is that input's
distribution function at the value where margin = required (closed form for
the exact power laws, Brent's method otherwise). The remaining inputs are
sampled with scrambled Sobol points (scipy.stats.qmc), ``replicates``
independent scramblings giving a Student-t confidence interval. Why: plain
Monte Carlo at P ~ 1e-3 needs ~4e5 evaluations for +-10 % (1.96^2 (1-P)/(0.1^2 P));
the conditional integrand is smooth and bounded, and QMC on a smooth integrand
converges close to 1/n, so tens to hundreds of samples reach the target.
The number of points doubles until every probability meets the relative
half-width target or the sample budget is spent.
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field, replace
from typing import Any, cast

import numpy as np

from etcheck.checks.orbit_field import with_orbit_field
from etcheck.checks.plan import plan
from etcheck.checks.sections import CheckResults, MarginSensitivityRecord, ProbabilityRecord, UncertaintySection
from etcheck.input.echo import UncertaintyInputs
from etcheck.input.mission import Mission
from etcheck.input.uncertainty import Distribution, Uncertainty
from etcheck.numerics.blas import one_blas_thread, single_blas_thread
from etcheck.rod.core.ends import ALL_WELDED
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.analytic import static_roots
from etcheck.rod.straight.damped_critical import LADDER, first_root
from etcheck.scaling import RPM, scene

#: Relative step (in ln of the dimensionless parameter) of the central differences.
STEP = 1e-3
#: Physical inputs, their SI unit and label.
PHYSICAL = {
    "EI1": ("N m²", "EI1 (stiff-axis bending stiffness)"),
    "EI2": ("N m²", "EI2 (weak-axis bending stiffness)"),
    "torsional_stiffness": ("N m²", "GJ (torsional stiffness)"),
    "mass_per_length": ("kg/m", "mass per length"),
    "length": ("m", "length L"),
    "current": ("A", "current |I| (worst case)"),
    "axial_field": ("T", "axial field |B0| (worst case)"),
    "spin_rate": ("rad/s", "spin rate"),
    "end_tension": ("N", "end tension T"),
    "damping_time": ("s", "damping time"),
}
#: Rows of the elasticity table: the physical inputs and both stiffnesses together.
ROWS = ("bending_stiffness", *PHYSICAL)
LABELS = {"bending_stiffness": "EI1 and EI2 together (one factor)"} | {k: v[1] for k, v in PHYSICAL.items()}
LOAD0, LOAD, SPIN = "load0", "load", "spin"
NAMES = {LOAD0: "magnetic load |I B0|", LOAD: "magnetic load |I B0| at the operating spin and tension",
         SPIN: "spin rate at the operating load"}
_DIMS = ("R", "Gamma", "P", "omega", "B", "T")


# --------------------------------------------------------------------------- the margin model


@dataclass(frozen=True)
class MarginModel:
    """The margins of one mission as functions of its physical inputs (SI floats).

    ``nominal``: physical inputs (keys of PHYSICAL, SI); ``P0``, ``L0``: rotary
    inertia ratio at the mission length (P ~ L^-2); ``gj_ratio``: GJ / (EI1 +
    EI2) when GJ follows from poisson_ratio (None: GJ is its own input);
    ``kinds``: the margins (LOAD0, LOAD, SPIN); ``route``: which model answers;
    ``gamma0``: the nominal dimensionless damping (used for every pencil);
    ``ends``: the attachment of the tether (:mod:`etcheck.rod.core.ends`).
    """

    nominal: dict[str, float]
    P0: float
    L0: float
    f: float
    gj_ratio: float | None
    kinds: tuple[str, ...]
    route: str
    required: float
    gamma0: float
    tol: float = 1e-8
    ladder: tuple[int, ...] = LADDER
    ends: tuple[str, str] = ALL_WELDED

    def values(self, changes: dict[str, float] | None = None) -> dict[str, float]:
        """Physical inputs with ``changes`` applied; "bending_stiffness" is a factor on EI1 and EI2."""
        v = dict(self.nominal)
        for k, x in (changes or {}).items():
            if k == "bending_stiffness":
                v["EI1"] *= x
                v["EI2"] *= x
            else:
                v[k] = x
        if self.gj_ratio is not None:
            v["torsional_stiffness"] = self.gj_ratio * (v["EI1"] + v["EI2"])
        return v

    def params(self, v: dict[str, float]) -> RodParameters:
        """Dimensionless parameters (eq. (36)) of physical inputs; the stiff axis is the larger EI."""
        EI1, EI2 = max(v["EI1"], v["EI2"]), min(v["EI1"], v["EI2"])
        L, m = v["length"], v["mass_per_length"]
        wc = math.sqrt(self.f * EI1 / (m * L**4))
        return RodParameters(P=self.P0 * (self.L0 / L) ** 2, R=EI2 / EI1, Gamma=2 * v["torsional_stiffness"] / (EI1 + EI2),
                             f=self.f, B=v["current"] * v["axial_field"] * L**3 / (self.f * EI1),
                             omega=v["spin_rate"] / wc, T=v["end_tension"] * L**2 / (self.f * EI1),
                             gamma=v["damping_time"] * wc, ends=self.ends)

    def margins(self, v: dict[str, float], kinds: tuple[str, ...] | None = None) -> dict[str, float]:
        """Margins (critical / operating) at physical inputs v; 0 where the tether is already unstable."""
        kinds = kinds or self.kinds
        if self.route == ROUTE_CLOSED:
            return {k: float(closed_form_margin({n: np.asarray(x) for n, x in v.items()}, self.ends)) for k in kinds}
        return dimensionless_margins(self.params(v), kinds, self)

    def margins_at(self, p: RodParameters) -> dict[str, float]:
        """Margins at dimensionless parameters (elasticities are differentiated here)."""
        return dimensionless_margins(p, self.kinds, self)


ROUTE_CLOSED = "rung 0 closed form B_1 = beta_1^3 sqrt(R)/f, vectorised over the samples (numpy)"
ROUTE_PENCIL = "first roots of the static pencils per sample (rung 1, exact with damping; BLAS one thread)"
ROUTE_UNDAMPED = "rung 1 spectral scans (undamped: flutter possible)"
NOT_ANSWERED_UNDAMPED = "not answered (undamped: flutter possible; no fast exact route)"
#: Quantile cut of the conditioning input's range in the root find (absolute error <= 1e-10 in P).
_CUT = 1e-10


def closed_form_margin(v: dict[str, np.ndarray], ends: tuple[str, str] = ALL_WELDED) -> np.ndarray:
    """Rung-0 load margin beta_1^3 sqrt(EI1 EI2) / (|I| |B0| L^3), vectorised (SI arrays in, dimensionless out);
    beta_1 of the ends (the first zero of chi for welded ends, eq. (91))."""
    beta1_cubed = static_roots(ends, 1)[0].beta ** 3
    with np.errstate(divide="ignore"):
        return beta1_cubed * np.sqrt(v["EI1"] * v["EI2"]) / (v["current"] * v["axial_field"] * v["length"] ** 3)


def dimensionless_margins(p: RodParameters, kinds: tuple[str, ...], model: MarginModel) -> dict[str, float]:
    """Load margin B_c(omega, T)/B and spin margin omega_c(B, T)/omega from first pencil roots.

    Exact for a damped rod (Kelvin-Tait-Chetaev) and for any rod without spin.
    The pencil does not contain gamma: it is evaluated at the model's nominal gamma.
    """
    if model.route == ROUTE_UNDAMPED:
        return _undamped_margins(p, kinds)
    p = p.with_(gamma=model.gamma0)
    tol, ladder = model.tol, model.ladder
    if p.T < 0:
        comp = first_root(p.with_(B=0.0, omega=0.0), "T", tol, sign=-1.0, ladder=ladder)
        if p.T <= comp.value:
            return {k: 0.0 for k in kinds}
    static = first_root(p.with_(omega=0.0), "B", tol, ladder=ladder).value
    rest = first_root(p.with_(B=0.0), "omega", tol, ladder=ladder).value if p.omega > 0 or SPIN in kinds else math.inf
    out = {}
    for k in kinds:
        if k in (LOAD0, LOAD):
            if p.omega == 0:
                crit = static
            elif p.omega >= rest:
                crit = 0.0
            else:
                crit = first_root(p, "B", tol, ladder=ladder, floor=1e-2 * static).value
            out[k] = crit / p.B if p.B > 0 else math.inf
        else:
            crit = 0.0 if p.B >= static else first_root(p, "omega", tol, ladder=ladder, floor=1e-2 * rest).value
            out[k] = crit / p.omega if p.omega > 0 else math.inf
    return out


def _undamped_margins(p: RodParameters, kinds: tuple[str, ...]) -> dict[str, float]:
    from etcheck.studies.sweep import solve_point

    r = solve_point(p, 1e-10)
    if r["status"] != "ok":
        return {k: math.nan for k in kinds}
    return {k: (r["B_c"] / p.B if k != SPIN else r["omega_c"] / p.omega) for k in kinds}


def margin_model(mission: Mission, tol: float = 1e-8) -> MarginModel:
    """The margin model of a mission at its worst-case operating point (as the check uses)."""
    from etcheck.scaling import scale

    mission = with_orbit_field(mission)
    sc = scene(mission)
    scaled = scale(sc)
    p = scaled.params
    chosen = plan(p, mission.fidelity if mission.fidelity in ("analytic", "linear") else "auto")
    if chosen.rung == 0 and chosen.complete:
        kinds = (LOAD0,)
    elif chosen.rung == 1:
        kinds = (LOAD, SPIN) if p.omega > 0 else (LOAD,)
    else:
        kinds = ()
    if chosen.rung == 0 and chosen.complete:
        route = ROUTE_CLOSED
    elif p.gamma > 0 or p.omega == 0:
        route = ROUTE_PENCIL
    else:
        route = ROUTE_UNDAMPED
    nominal = {"EI1": sc.EI1, "EI2": sc.EI2, "torsional_stiffness": sc.GJ, "mass_per_length": sc.mass_per_length,
               "length": sc.length, "current": float(mission.worst_current.to_value("A")),
               "axial_field": float(mission.worst_field.to_value("T")), "spin_rate": sc.spin_rate,
               "end_tension": sc.tension, "damping_time": sc.damping_time}
    gj_ratio = sc.GJ / (sc.EI1 + sc.EI2) if mission.poisson_ratio is not None else None
    return MarginModel(nominal, sc.P, sc.length, sc.f, gj_ratio, kinds, route, mission.required_margin, p.gamma, tol,
                       ends=p.ends)


def _fixed_resolution(model: MarginModel) -> MarginModel:
    """The model with its Chebyshev resolution frozen at the one the nominal point needed
    (so that differences do not jump between resolutions)."""
    if model.route != ROUTE_PENCIL:
        return model
    p = model.params(model.values()).with_(gamma=model.gamma0)
    Ns = [first_root(p.with_(omega=0.0), "B", model.tol).N]
    if p.omega > 0 or SPIN in model.kinds:
        Ns.append(first_root(p.with_(B=0.0), "omega", model.tol).N)
    if p.omega > 0:
        Ns.append(first_root(p, "B", model.tol).N)
    if SPIN in model.kinds:
        Ns.append(first_root(p, "omega", model.tol).N)
    N = max([n for n in Ns if n] or [LADDER[0]])
    return replace(model, ladder=(N,))


# --------------------------------------------------------------------------- elasticities


@dataclass(frozen=True)
class Elasticity:
    """d ln margin / d ln input at the operating point (dimensionless); ``method`` says how."""

    input: str
    value: float | None
    method: str


@dataclass(frozen=True)
class Swing:
    """The margin with one input at the ends of its tolerance range, the others nominal."""

    input: str
    low: float  # input value (SI, or factor) at the low end
    high: float
    margin_low: float
    margin_high: float


@dataclass(frozen=True)
class MarginSensitivity:
    """Elasticities of one margin to every input, and its tolerance swings."""

    margin: str
    nominal: float
    elasticities: tuple[Elasticity, ...]
    swings: tuple[Swing, ...] = ()


def _jacobian(v: dict[str, float], gj_follows: bool) -> dict[str, dict[str, float]]:
    """d ln q / d ln input for q in R, Gamma, P, omega, B, T (exact, from the scalings)."""
    EI1, EI2 = v["EI1"], v["EI2"]
    s1, s2 = EI1 / (EI1 + EI2), EI2 / (EI1 + EI2)
    J = {q: dict.fromkeys(PHYSICAL, 0.0) for q in _DIMS}
    J["R"] |= {"EI2": 1.0, "EI1": -1.0}
    if not gj_follows:
        J["Gamma"] |= {"torsional_stiffness": 1.0, "EI1": -s1, "EI2": -s2}
    J["P"] |= {"length": -2.0}
    J["omega"] |= {"spin_rate": 1.0, "EI1": -0.5, "mass_per_length": 0.5, "length": 2.0}
    J["B"] |= {"current": 1.0, "axial_field": 1.0, "length": 3.0, "EI1": -1.0}
    J["T"] |= {"end_tension": 1.0, "length": 2.0, "EI1": -1.0}
    if EI2 > EI1:  # axes swapped by the sample: R = EI1/EI2
        J["R"] |= {"EI1": 1.0, "EI2": -1.0}
        J["omega"]["EI1"], J["omega"]["EI2"] = 0.0, -0.5
    return J


@single_blas_thread
def sensitivities(model: MarginModel, step: float = STEP) -> tuple[MarginSensitivity, ...]:
    """Elasticities of every margin of the model to every physical input (and both stiffnesses together).

    Exact where the model is a power law; central differences of relative
    step ``step`` in the dimensionless parameters otherwise (see the module
    docstring), at the nominal point's Chebyshev resolution.
    """
    v = model.values()
    if model.route == ROUTE_CLOSED:
        exp = {"EI1": 0.5, "EI2": 0.5, "length": -3.0, "current": -1.0, "axial_field": -1.0}
        m0 = model.margins(v)[LOAD0]
        els = [Elasticity(k, exp.get(k, 0.0) if k != "bending_stiffness" else 1.0,
                          "exact (closed form: margin ∝ sqrt(EI1 EI2) L^-3 / |I B0|)") for k in ROWS]
        return (MarginSensitivity(NAMES[LOAD0], m0, tuple(els)),)
    fixed = _fixed_resolution(model)
    p0 = fixed.params(v)
    m0 = fixed.margins_at(p0)
    J = _jacobian(v, model.gj_ratio is not None)
    return tuple(_margin_sensitivity(fixed, kind, p0, m0[kind], J, v, step) for kind in model.kinds)


def _margin_sensitivity(fixed: MarginModel, kind: str, p0: RodParameters, base: float,
                        J: dict[str, dict[str, float]], v: dict[str, float], step: float) -> MarginSensitivity:
    """One margin's elasticities: in the dimensionless parameters (exact or central differences), then to the
    physical inputs through the scalings (``J``), and to both stiffnesses together."""
    name = NAMES[kind]
    if not (base > 0 and math.isfinite(base)):
        els = tuple(Elasticity(k, None, "margin is zero or unbounded at the operating point") for k in ROWS)
        return MarginSensitivity(name, base, els)
    d, how = _dimensionless_elasticities(fixed, kind, p0, step)
    els = [_physical_elasticity(fixed, kind, k, J, d, how, v, step) for k in PHYSICAL]
    common, els = _both_stiffnesses(fixed, kind, els, step)
    return MarginSensitivity(name, base, (common, *els))


def _dimensionless_elasticities(fixed: MarginModel, kind: str, p0: RodParameters,
                                step: float) -> tuple[dict[str, float], dict[str, str]]:
    """d ln margin / d ln q for q in R, Gamma, P, omega, B, T, and how each was found: "exact" (the margin is
    inversely proportional to B or omega), zero parameters, "symmetric" (R = 1: not differentiable) or "fd"."""
    exact_dir = "B" if kind in (LOAD0, LOAD) else "omega"
    d = {q: 0.0 for q in _DIMS} | {exact_dir: -1.0}
    how = {exact_dir: "exact"}
    for q in _DIMS:
        if q == exact_dir:
            continue
        x = getattr(p0, q)
        if x == 0:
            how[q] = "exact (the parameter is zero)"
        elif q == "R" and p0.R * math.exp(step) > 1.0:
            how[q] = "symmetric"
        else:
            up = fixed.margins_at(p0.with_(**{q: x * math.exp(step)}))[kind]
            dn = fixed.margins_at(p0.with_(**{q: x * math.exp(-step)}))[kind]
            d[q] = (math.log(up) - math.log(dn)) / (2 * step) if up > 0 and dn > 0 else math.nan
            how[q] = "fd"
    return d, how


def _physical_elasticity(fixed: MarginModel, kind: str, k: str, J: dict[str, dict[str, float]],
                         d: dict[str, float], how: dict[str, str], v: dict[str, float], step: float) -> Elasticity:
    """The elasticity to physical input ``k``: sum over q of d ln q / d ln k * d ln margin / d ln q."""
    if k == "damping_time":
        return Elasticity(k, 0.0, "exact (the static pencil does not contain damping)")
    if (k in ("current", "axial_field") and kind != SPIN) or (k == "spin_rate" and kind == SPIN):
        return Elasticity(k, -1.0, "exact (margin ∝ 1/input)")
    used = {how.get(q, "") for q in _DIMS if J[q][k] != 0}
    if k in ("EI1", "EI2") and "symmetric" in used:
        return Elasticity(k, None, "isotropic: see both together")
    val = sum(J[q][k] * d[q] for q in _DIMS)
    if k == "end_tension" and v["end_tension"] == 0:
        method = "exact: 0 at zero tension (see the tolerance swing for an absolute tolerance)"
    elif "fd" in used:
        method = f"central difference, relative step {step:g} in the dimensionless parameters"
    elif k == "torsional_stiffness" and fixed.gj_ratio is not None:
        method = "GJ follows from poisson_ratio: counted in EI1 and EI2"
    else:
        method = "exact (the margin does not depend on it)" if val == 0 else "exact (from the scalings)"
    return Elasticity(k, val, method)


def _both_stiffnesses(fixed: MarginModel, kind: str, els: list[Elasticity],
                      step: float) -> tuple[Elasticity, list[Elasticity]]:
    """The elasticity to EI1 and EI2 together (one factor), and the per-axis ones (halves of it when the rod
    is isotropic, where each alone is not differentiable)."""
    ei1, ei2 = next(e for e in els if e.input == "EI1"), next(e for e in els if e.input == "EI2")
    gj = next(e for e in els if e.input == "torsional_stiffness")
    if ei1.value is not None:
        tot = ei1.value + ei2.value + (gj.value if fixed.gj_ratio is not None else 0.0)
        return Elasticity("bending_stiffness", tot, "sum of EI1 and EI2" +
                          (" (GJ follows from poisson_ratio)" if fixed.gj_ratio is not None else "")), els
    up = fixed.margins(fixed.values({"bending_stiffness": math.exp(step)}))[kind]
    dn = fixed.margins(fixed.values({"bending_stiffness": math.exp(-step)}))[kind]
    tot = (math.log(up) - math.log(dn)) / (2 * step)
    els = [replace(e, value=0.5 * tot, method="half of both together (isotropic, by symmetry)")
           if e.input in ("EI1", "EI2") else e for e in els]
    return Elasticity("bending_stiffness", tot, f"central difference, relative step {step:g}"), els


@single_blas_thread
def swings(model: MarginModel, unc: Uncertainty) -> dict[str, tuple[Swing, ...]]:
    """Margins at the ends of every uncertain input's tolerance range (one at a time), per margin name."""
    rows: dict[str, list[Swing]] = {NAMES[k]: [] for k in model.kinds}
    for d in unc.inputs:
        lo, hi = d.interval()
        ends = []
        for x in (lo, hi):
            ends.append(model.margins(model.values({d.input: _value(model, d, x)})))
        for k in model.kinds:
            rows[NAMES[k]].append(Swing(d.input, lo, hi, ends[0][k], ends[1][k]))
    return {k: tuple(v) for k, v in rows.items()}


def _value(model: MarginModel, d: Distribution, x: float) -> float:
    """A sampled value of d as the model's input (factors multiply the nominal value)."""
    if d.input == "bending_stiffness":
        return x
    return model.nominal[d.input] * x if d.factor else x


# --------------------------------------------------------------------------- probability of falling short


@dataclass(frozen=True)
class Probability:
    """P(margin < required) with its 95 % confidence interval [low, high] (dimensionless).

    ``samples``: sampled points; ``evaluations``: model evaluations (margins
    computed, including root finding along the conditioning input);
    ``conditioned_on``: the input integrated exactly (None: indicator
    sampling); ``settled``: the target was met; ``note``: what to know.
    """

    margin: str
    required: float
    value: float | None
    low: float | None
    high: float | None
    relative_half_width: float | None
    samples: int
    evaluations: int
    model: str
    method: str
    conditioned_on: str | None
    settled: bool
    note: str = ""


def _dominant(sens: MarginSensitivity, unc: Uncertainty, exact_zero: set[str]) -> str | None:
    best, score = None, 0.0
    e = {x.input: x.value for x in sens.elasticities}
    for d in unc.inputs:
        if d.input in exact_zero:
            continue
        s = abs(e.get(d.input) or 0.0) * d.log_spread()
        if s > score:
            best, score = d.input, s
    return best


def _power(model: MarginModel, kind: str, name: str) -> float | None:
    """Exponent a when margin ∝ input^a exactly (closed-form threshold), else None."""
    if model.route == ROUTE_CLOSED:
        return {"EI1": 0.5, "EI2": 0.5, "bending_stiffness": 1.0, "length": -3.0, "current": -1.0,
                "axial_field": -1.0}.get(name)
    if kind in (LOAD, LOAD0) and name in ("current", "axial_field"):
        return -1.0
    if kind == SPIN and name == "spin_rate":
        return -1.0
    return None


def conditional_probability(model: MarginModel, kind: str, v: dict[str, float], d: Distribution | None) -> tuple[float, int]:
    """P(margin < required | the other inputs at v), integrating input d exactly; (probability, evaluations).

    d None: the indicator of margin < required. Otherwise the margin is taken
    monotone in d's input over its range: closed form for exact power laws,
    Brent's method on ln(input) otherwise.
    """
    req = model.required
    if d is None:
        return float(model.margins(v, (kind,))[kind] < req), 1
    name = d.input
    a = _power(model, kind, name)
    if a is not None:
        m = model.margins(v, (kind,))[kind]
        xv = v[name] if name != "bending_stiffness" else v.get("_bs", 1.0)
        if m == 0:
            return 1.0, 1
        x_star = xv * (req / m) ** (1.0 / a)
        sample_x = x_star / model.nominal[name] if d.factor and name != "bending_stiffness" else x_star
        return float(d.sf(sample_x) if a < 0 else d.cdf(sample_x)), 1
    # the range searched: the 1e-10 and 1 - 1e-10 quantiles (an absolute error below 1e-10 in P)
    lo, hi = (float(x) for x in d.ppf([_CUT, 1.0 - _CUT]))
    if lo <= 0:
        lo = float(d.ppf(0.5)) * 1e-6
    count = [0]

    def g(lnx: float) -> float:
        count[0] += 1
        w = _with(model, v, d, math.exp(lnx))
        return model.margins(w, (kind,))[kind] - req

    f_lo, f_hi = g(math.log(lo)), g(math.log(hi))
    if f_lo >= 0 and f_hi >= 0:
        return 0.0, count[0]
    if f_lo < 0 and f_hi < 0:
        return 1.0, count[0]
    from scipy.optimize import brentq

    root = math.exp(brentq(g, math.log(lo), math.log(hi), xtol=1e-9, rtol=1e-12))
    return float(d.cdf(root) if f_lo < 0 else d.sf(root)), count[0]


def _with(model: MarginModel, v: dict[str, float], d: Distribution, x: float) -> dict[str, float]:
    """v with d's input set to the sample x (a factor or an SI value)."""
    if d.input == "bending_stiffness":
        w = dict(v)
        w["EI1"], w["EI2"] = v["EI1"] * x / v.get("_bs", 1.0), v["EI2"] * x / v.get("_bs", 1.0)
        w["_bs"] = x
        if model.gj_ratio is not None:
            w["torsional_stiffness"] = model.gj_ratio * (w["EI1"] + w["EI2"])
        return w
    w = dict(v)
    w[d.input] = model.nominal[d.input] * x if d.factor else x
    if model.gj_ratio is not None:
        w["torsional_stiffness"] = model.gj_ratio * (w["EI1"] + w["EI2"])
    return w


def _sample_values(model: MarginModel, dists: list[Distribution], u: np.ndarray) -> list[dict[str, float]]:
    """Physical inputs at each row of u (columns in the order of dists)."""
    cols = [d.ppf(u[:, j]) for j, d in enumerate(dists)]
    out = []
    for i in range(u.shape[0]):
        w = {k: x for k, x in model.nominal.items()}
        w["_bs"] = 1.0
        for j, d in enumerate(dists):
            w = _with(model, w, d, float(cols[j][i]))
        out.append(w)
    return out


def _closed_form_batch(model: MarginModel, dists: list[Distribution], u: np.ndarray, cond: Distribution | None) -> np.ndarray:
    """Rung 0: the conditional probabilities of all rows at once (numpy)."""
    v = {k: np.full(u.shape[0], x) for k, x in model.nominal.items()}
    for j, d in enumerate(dists):
        x = d.ppf(u[:, j])
        if d.input == "bending_stiffness":
            v["EI1"], v["EI2"] = v["EI1"] * x, v["EI2"] * x
        else:
            v[d.input] = model.nominal[d.input] * x if d.factor else x
    m = closed_form_margin(v, model.ends)
    if cond is None:
        return (m < model.required).astype(float)
    a = _power(model, LOAD0, cond.input)
    xv = v[cond.input] if cond.input != "bending_stiffness" else np.ones(u.shape[0])
    with np.errstate(divide="ignore"):
        x_star = xv * (model.required / m) ** (1.0 / a)
    if cond.factor and cond.input != "bending_stiffness":
        x_star = x_star / model.nominal[cond.input]
    return cond.sf(x_star) if a < 0 else cond.cdf(x_star)


def _chunk_worker(args) -> list[tuple[float, int]]:
    model, kind, rows, cond = args
    with one_blas_thread():
        return [conditional_probability(model, kind, v, cond) for v in rows]


@dataclass(frozen=True)
class _Sampling:
    """When the sampling of one probability stops: relative 95 % half-width ``target``, below ``negligible`` with
    its interval, or ``max_samples`` points; ``replicates`` scrambled Sobol sequences of ``first`` points each at
    the start (doubling), seeded from ``seed``; ``workers`` local processes for the pencils."""

    target: float
    max_samples: int
    replicates: int
    first: int
    seed: int
    negligible: float
    workers: int

    def settled(self, mean: float, half: float, n: int) -> bool:
        """The target is met, the probability is negligible, or no sample fell short out of 1024 or more."""
        return (mean > 0 and half <= self.target * mean) or mean + half < self.negligible or (mean == 0 and n >= 1024)


@single_blas_thread
def failure_probabilities(model: MarginModel, unc: Uncertainty, sens: tuple[MarginSensitivity, ...] | None = None,
                          target: float = 0.1, max_samples: int | None = None, replicates: int = 8,
                          first: int = 8, seed: int = 20240615, workers: int | None = None,
                          negligible: float = 1e-9) -> tuple[Probability, ...]:
    """P(margin < required) for every margin of the model, to a relative 95 % half-width ``target``.

    Randomised QMC (``replicates`` scrambled Sobol sequences, ``first`` points
    each at the start, doubling) over the inputs other than each margin's
    conditioning input, which is integrated exactly. Stops when every
    probability has half-width <= target x value, or is below ``negligible``
    with its interval, or ``max_samples`` points (per margin) are spent
    (default 2^20 for the closed form, 4096 for pencils). ``workers``:
    local processes for the pencils (default: every core).
    """
    if model.route == ROUTE_UNDAMPED or _undamped_samples(model, unc):
        return tuple(Probability(NAMES[k], model.required, None, None, None, None, 0, 0, ROUTE_UNDAMPED,
                                 NOT_ANSWERED_UNDAMPED, None, False,
                                 "without damping a spinning tether can flutter; only the spectral scans answer, "
                                 "seconds per sample") for k in model.kinds)
    sens = sens or sensitivities(model)
    if max_samples is None:
        max_samples = 2**20 if model.route == ROUTE_CLOSED else 4096
    sampling = _Sampling(target, max_samples, replicates, first, seed, negligible,
                         workers or len(os.sched_getaffinity(0)))
    if model.route == ROUTE_CLOSED and any(unc.get(k) for k in ("spin_rate", "end_tension")):
        model = replace(model, route=ROUTE_PENCIL, kinds=model.kinds)  # samples leave the rung-0 case
    exact_zero = {"damping_time"} if model.route == ROUTE_PENCIL else set(PHYSICAL) - {
        "EI1", "EI2", "length", "current", "axial_field"}
    # pencils in local processes (started at the first batch large enough to share out)
    pool = ProcessPoolExecutor(max_workers=sampling.workers) if model.route == ROUTE_PENCIL and sampling.workers > 1 \
        else None
    try:
        return tuple(_probability(model, s, unc, exact_zero, sampling, pool) for s in sens)
    finally:
        if pool is not None:
            pool.shutdown()


def _probability(model: MarginModel, s: MarginSensitivity, unc: Uncertainty, exact_zero: set[str],
                 sampling: _Sampling, pool: ProcessPoolExecutor | None) -> Probability:
    """P(margin < required) of one margin: its dominant input integrated exactly, the others sampled."""
    kind = next(k for k in model.kinds if NAMES[k] == s.margin)
    cond_name = _dominant(s, unc, exact_zero)
    cond = unc.get(cond_name) if cond_name else None
    dists = [d for d in unc.inputs if d.input not in exact_zero and d is not cond]
    inert = [d.input for d in unc.inputs if d.input in exact_zero]
    note = f"inputs without influence (exactly): {', '.join(inert)}" if inert else ""
    started = time.perf_counter()
    if not dists:
        v = model.values()
        v["_bs"] = 1.0
        pr, ev = conditional_probability(model, kind, v, cond)
        return Probability(s.margin, model.required, pr, pr, pr, 0.0, 1, ev, model.route,
                           "exact: one input, integrated in closed form" if cond else
                           "exact: no uncertain input moves this margin", cond_name, True, note)
    mean, half, n, evals, settled = _quasi_monte_carlo(model, kind, dists, cond, sampling, pool)
    if mean + half < sampling.negligible and mean > 0:
        note = (note + "; " if note else "") + f"negligible: below {sampling.negligible:g} with its interval"
    if mean == 0:
        low, high, rel = 0.0, 3.0 / n, None
        note = (note + "; " if note else "") + f"no sample fell short: P < {3.0 / n:.2g} (rule of three, 95 %)"
    else:
        low, high, rel = max(0.0, mean - half), min(1.0, mean + half), half / mean
    how = (f"randomised quasi-Monte Carlo: {sampling.replicates} scrambled Sobol sequences (scipy.stats.qmc) over "
           f"{', '.join(d.input for d in dists)}; "
           + (f"{cond_name} integrated exactly (conditional probability)" if cond else "indicator of margin < required")
           + f"; {time.perf_counter() - started:.2f} s")
    return Probability(s.margin, model.required, mean, low, high, rel, n, evals, model.route, how, cond_name,
                       settled, note)


def _quasi_monte_carlo(model: MarginModel, kind: str, dists: list[Distribution], cond: Distribution | None,
                       sampling: _Sampling, pool: ProcessPoolExecutor | None) -> tuple[float, float, int, int, bool]:
    """(mean, 95 % half-width, samples, evaluations, settled) over scrambled Sobol replicates, doubling."""
    from scipy import stats
    from scipy.stats import qmc

    replicates = sampling.replicates
    sobols = [qmc.Sobol(len(dists), scramble=True, seed=sampling.seed + 7919 * r) for r in range(replicates)]
    sums = np.zeros(replicates)
    n_each = evals = 0
    batch = sampling.first
    while True:
        gs, ev = _conditional_batches(model, kind, dists, cond, [sb.random(batch) for sb in sobols], sampling, pool)
        evals += ev
        sums += np.array([float(np.sum(g)) for g in gs])
        n_each += batch
        est = sums / n_each
        mean = float(np.mean(est))
        half = float(stats.t.ppf(0.975, replicates - 1) * np.std(est, ddof=1) / math.sqrt(replicates))
        settled = sampling.settled(mean, half, n_each * replicates)
        if settled or n_each * replicates * 2 > sampling.max_samples:
            return mean, half, n_each * replicates, evals, settled
        batch = n_each  # doubling keeps the Sobol balance (powers of two)


def _conditional_batches(model: MarginModel, kind: str, dists: list[Distribution], cond: Distribution | None,
                         us: list[np.ndarray], sampling: _Sampling,
                         pool: ProcessPoolExecutor | None) -> tuple[list[np.ndarray], int]:
    """The conditional probabilities at every replicate's points ``us``, and the model evaluations spent."""
    batch = us[0].shape[0]
    if model.route == ROUTE_CLOSED:
        return [_closed_form_batch(model, dists, u, cond) for u in us], batch * len(us)
    flat = [w for u in us for w in _sample_values(model, dists, u)]
    if pool is not None and len(flat) >= 16:
        size = max(1, math.ceil(len(flat) / (4 * sampling.workers)))
        chunks = [flat[i:i + size] for i in range(0, len(flat), size)]
        got = [x for part in pool.map(_chunk_worker, [(model, kind, c, cond) for c in chunks]) for x in part]
    else:
        got = _chunk_worker((model, kind, flat, cond))
    g = np.array([x for x, _ in got])
    return [g[r * batch:(r + 1) * batch] for r in range(len(us))], sum(e for _, e in got)


def _undamped_samples(model: MarginModel, unc: Uncertainty) -> bool:
    """Can a sample be a spinning tether without damping (no fast exact route)?"""
    spins = model.nominal["spin_rate"] > 0 or unc.get("spin_rate") is not None
    return spins and model.nominal["damping_time"] == 0 and unc.get("damping_time") is None


# --------------------------------------------------------------------------- the study


@dataclass(frozen=True)
class UncertaintyStudy:
    """Sensitivities of every margin, and (with an [uncertainty] table) the probabilities of falling short."""

    route: str
    sensitivities: tuple[MarginSensitivity, ...]
    probabilities: tuple[Probability, ...] = ()
    inputs: dict[str, Any] = field(default_factory=dict)
    nominal: dict[str, float] = field(default_factory=dict)
    required: float = 2.0
    elapsed_s: float = 0.0
    sensitivity_time_s: float = 0.0

    def as_dict(self) -> UncertaintySection:
        """JSON-able (None where not finite)."""

        def num(x):
            return None if x is None or not math.isfinite(x) else float(x)

        margins: list[MarginSensitivityRecord] = []
        for s in self.sensitivities:
            ranked = sorted((e for e in s.elasticities if e.value is not None), key=lambda e: -abs(e.value))
            margins.append({
                "margin": s.margin, "nominal": num(s.nominal),
                "elasticities": [{"input": e.input, "label": LABELS[e.input], "value": num(e.value), "method": e.method}
                                 for e in s.elasticities],
                "hinges_on": [e.input for e in ranked if abs(e.value) >= 0.1],
                "does_not_matter": [e.input for e in ranked if abs(e.value) < 1e-3],
                "swings": [{"input": w.input, "label": LABELS.get(w.input, w.input), "low": num(w.low),
                            "high": num(w.high), "margin_low": num(w.margin_low), "margin_high": num(w.margin_high)}
                           for w in s.swings],
            })
        return {
            "route": self.route,
            "required_margin": self.required,
            "step": STEP,
            "nominal_inputs_SI": dict(self.nominal),
            "inputs": cast(UncertaintyInputs, self.inputs),
            "margins": margins,
            "probabilities": [cast(ProbabilityRecord, {k: (num(v) if isinstance(v, float) else v)
                                                       for k, v in p.__dict__.items()}) for p in self.probabilities],
            "sensitivity_time_s": self.sensitivity_time_s,
            "elapsed_s": self.elapsed_s,
        }


@single_blas_thread
def study(mission: Mission, target: float = 0.1, max_samples: int | None = None, workers: int | None = None,
          probabilities: bool = True, seed: int = 20240615) -> UncertaintyStudy:
    """Elasticities of every margin; with the mission's [uncertainty] table also the tolerance
    swings and the probability of each margin falling below the required margin."""
    started = time.perf_counter()
    model = margin_model(mission)
    sens = sensitivities(model)
    t_sens = time.perf_counter() - started
    unc = mission.uncertainty
    probs: tuple[Probability, ...] = ()
    if unc is not None:
        sw = swings(model, unc)
        sens = tuple(replace(s, swings=sw.get(s.margin, ())) for s in sens)
        if probabilities:
            probs = failure_probabilities(model, unc, sens, target=target, max_samples=max_samples,
                                          workers=workers, seed=seed)
    return UncertaintyStudy(model.route, sens, probs, unc.as_dict() if unc else {}, dict(model.nominal),
                            model.required, time.perf_counter() - started, t_sens)


def spin_rpm(rad_s: float) -> float:
    """rad/s -> rpm (for labels)."""
    return rad_s * RPM


def attach(results: CheckResults, mission: Mission, **options: Any) -> CheckResults:
    """Add the study to check results under "uncertainty" when the mission has an [uncertainty]
    table (the check's results are otherwise unchanged); returns results."""
    if mission.uncertainty is not None:
        results["uncertainty"] = study(mission, **options).as_dict()
    return results


def summary_lines(results: CheckResults) -> list[str]:
    """Lines for the CLI summary: the probability of each margin falling short."""
    lines = []
    for p in (results.get("uncertainty") or {}).get("probabilities", []):
        if p["value"] is None:
            lines.append(f"  P({p['margin']} < {p['required']:g}): {p['method']}")
            continue
        ci = f"95 % CI {p['low']:.3g} … {p['high']:.3g}"
        lines.append(f"  P({p['margin']} < {p['required']:g}) = {p['value']:.3g} ({ci}; {p['samples']} samples, "
                     f"{p['evaluations']} evaluations{'' if p['settled'] else ', target not met'})")
    return lines
