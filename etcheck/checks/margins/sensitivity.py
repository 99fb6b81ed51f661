"""Which input a margin hinges on: elasticities d ln margin / d ln input and tolerance swings.

Dimensionless elasticities of every margin of a :class:`~etcheck.checks.margins.margin_model.MarginModel`.
Exact where the model is a power law (rung 0: EI1 1/2, EI2 1/2, L -3, I -1,
B0 -1, the rest 0; rung 1: the load margin is B_c / B so I and B0 are exactly
-1, the spin margin is omega_c / omega so the spin rate is exactly -1; the
inputs of :meth:`~etcheck.checks.margins.margin_model.MarginModel.inert` exactly 0).
Elsewhere they are central differences of ln margin in ln R, ln Gamma, ln P,
ln omega, ln B, ln T with relative step ``STEP`` = 1e-3 on the check's route
(truncation error ~ STEP^2, the margins' own error / STEP: 1e-7 at the
check's 1e-10), carried to the physical inputs by the exact Jacobian of the
scalings (omega_c = sqrt(f EI1 / (rho A L^4)), B = |I B0| L^3 / (f EI1),
T = T L^2 / (f EI1), P ~ L^-2, R = EI2/EI1, Gamma = 2 GJ / (EI1 + EI2)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from etcheck.checks.margins.margin import BUCKLED, SPIN
from etcheck.checks.margins.margin_model import CLOSED, INPUTS, PHYSICAL, RUNG0_POWERS, MarginModel
from etcheck.input.uncertainty import Distribution, Uncertainty
from etcheck.rod.core.parameters import RodParameters
from etcheck.runtime.blas import single_blas_thread

#: Relative step (in ln of the dimensionless parameter) of the central differences.
STEP = 1e-3
_DIMS = ("R", "Gamma", "P", "omega", "B", "T")


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

    def of(self, name: str) -> float | None:
        """The elasticity to one input (None where not differentiable)."""
        return next(e.value for e in self.elasticities if e.input == name)


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
    if EI2 > EI1:  # axes swapped: R = EI1/EI2
        J["R"] |= {"EI1": 1.0, "EI2": -1.0}
        J["omega"]["EI1"], J["omega"]["EI2"] = 0.0, -0.5
    return J


@single_blas_thread
def sensitivities(model: MarginModel, step: float = STEP) -> tuple[MarginSensitivity, ...]:
    """Elasticities of every margin of the model to every physical input (and both stiffnesses together).

    Exact where the model is a power law; central differences of relative
    step ``step`` in the dimensionless parameters otherwise (module docstring).
    """
    v = model.values()
    if model.route == CLOSED:
        how = "exact (closed form: margin ∝ sqrt(EI1 EI2) L^-3 / |I B0|)"
        return tuple(_buckled(model) if kind == BUCKLED else
                     MarginSensitivity(kind, model.margin(v, kind).value,
                                       tuple(Elasticity(k, RUNG0_POWERS.get(k, 0.0), how) for k in INPUTS))
                     for kind in model.kinds)
    straight = tuple(k for k in model.kinds if k != BUCKLED)
    p0 = model.params(v)
    m0 = model.at_params(p0, straight) if straight else {}
    J = _jacobian(v, model.gj_ratio is not None)
    return tuple(_buckled(model) if kind == BUCKLED else
                 _margin_sensitivity(model, kind, p0, m0[kind].value, J, v, step) for kind in model.kinds)


def _buckled(model: MarginModel) -> MarginSensitivity:
    """The buckled tether's margin: exact in the inputs that scale it (:meth:`MarginModel.powers`) or do not move
    it (:meth:`MarginModel.inert`), not differentiated otherwise."""
    powers, inert = model.powers(BUCKLED), model.inert(BUCKLED)

    def one(k: str) -> Elasticity:
        if k in powers:
            return Elasticity(k, powers[k], "exact (a power law: B* f EI1 / (|I B0| L^3))")
        if k in inert:
            return Elasticity(k, 0.0, f"exact ({inert[k]})")
        return Elasticity(k, None, "not differentiated (rungs 2-3, seconds per point)")

    return MarginSensitivity(BUCKLED, model.at_nominal[BUCKLED], tuple(one(k) for k in INPUTS))


def _margin_sensitivity(model: MarginModel, kind: str, p0: RodParameters, base: float,
                        J: dict[str, dict[str, float]], v: dict[str, float], step: float) -> MarginSensitivity:
    """One margin's elasticities: in the dimensionless parameters (exact or central differences), then to the
    physical inputs through the scalings (``J``), and to both stiffnesses together."""
    if not (base > 0 and math.isfinite(base)):
        els = tuple(Elasticity(k, None, "margin is zero or unbounded at the operating point") for k in INPUTS)
        return MarginSensitivity(kind, base, els)
    d, how = _dimensionless_elasticities(model, kind, p0, step)
    inert = model.inert(kind)
    els = [_physical_elasticity(model, kind, k, J, d, how, v, step, inert) for k in PHYSICAL]
    common, els = _both_stiffnesses(model, kind, els, step)
    return MarginSensitivity(kind, base, (common, *els))


def _dimensionless_elasticities(model: MarginModel, kind: str, p0: RodParameters,
                                step: float) -> tuple[dict[str, float], dict[str, str]]:
    """d ln margin / d ln q for q in R, Gamma, P, omega, B, T, and how each was found: "exact" (the margin is
    inversely proportional to B or omega), zero parameters, "symmetric" (R = 1: not differentiable) or "fd"."""
    exact_dir = "omega" if kind == SPIN else "B"
    d = {q: 0.0 for q in _DIMS} | {exact_dir: -1.0}
    how = {exact_dir: "exact"}
    for q in _DIMS:
        if q == exact_dir:
            continue
        x = getattr(p0, q)
        if x == 0 or q == "Gamma":  # torsion decouples: Gamma does not enter (MarginModel.inert)
            how[q] = "exact (the parameter is zero)" if x == 0 else "exact"
        elif q == "R" and p0.R * math.exp(step) > 1.0:
            how[q] = "symmetric"
        else:
            up = model.at_params(p0.with_(**{q: x * math.exp(step)}), (kind,))[kind].value
            dn = model.at_params(p0.with_(**{q: x * math.exp(-step)}), (kind,))[kind].value
            d[q] = (math.log(up) - math.log(dn)) / (2 * step) if up > 0 and dn > 0 else math.nan
            how[q] = "fd"
    return d, how


def _physical_elasticity(model: MarginModel, kind: str, k: str, J: dict[str, dict[str, float]],
                         d: dict[str, float], how: dict[str, str], v: dict[str, float], step: float,
                         inert: dict[str, str]) -> Elasticity:
    """The elasticity to physical input ``k``: sum over q of d ln q / d ln k * d ln margin / d ln q."""
    if k in inert:
        return Elasticity(k, 0.0, f"exact ({inert[k]})")
    if model.powers(kind).get(k) is not None:
        return Elasticity(k, model.powers(kind)[k], "exact (margin ∝ 1/input)")
    used = {how.get(q, "") for q in _DIMS if J[q][k] != 0}
    if k in ("EI1", "EI2") and "symmetric" in used:
        return Elasticity(k, None, "isotropic: see both together")
    val = sum(J[q][k] * d[q] for q in _DIMS)
    if k == "end_tension" and v["end_tension"] == 0:
        method = "exact: 0 at zero tension (see the tolerance swing for an absolute tolerance)"
    elif "fd" in used:
        method = f"central difference, relative step {step:g} in the dimensionless parameters"
    else:
        method = "exact (the margin does not depend on it)" if val == 0 else "exact (from the scalings)"
    return Elasticity(k, val, method)


def _both_stiffnesses(model: MarginModel, kind: str, els: list[Elasticity],
                      step: float) -> tuple[Elasticity, list[Elasticity]]:
    """The elasticity to EI1 and EI2 together (one factor), and the per-axis ones (halves of it when the rod
    is isotropic, where each alone is not differentiable)."""
    ei1, ei2 = next(e for e in els if e.input == "EI1"), next(e for e in els if e.input == "EI2")
    gj = next(e for e in els if e.input == "torsional_stiffness")
    if ei1.value is not None:
        tot = ei1.value + ei2.value + (gj.value if model.gj_ratio is not None else 0.0)
        return Elasticity("bending_stiffness", tot, "sum of EI1 and EI2" +
                          (" (GJ follows from poisson_ratio)" if model.gj_ratio is not None else "")), els
    up = model.margin(model.values({"bending_stiffness": math.exp(step)}), kind).value
    dn = model.margin(model.values({"bending_stiffness": math.exp(-step)}), kind).value
    tot = (math.log(up) - math.log(dn)) / (2 * step) if up > 0 and dn > 0 else math.nan  # a margin of 0 nearby
    els = [replace(e, value=0.5 * tot, method="half of both together (isotropic, by symmetry)")
           if e.input in ("EI1", "EI2") else e for e in els]
    return Elasticity("bending_stiffness", tot, f"central difference, relative step {step:g}"), els


@single_blas_thread
def swings(model: MarginModel, unc: Uncertainty) -> dict[str, tuple[Swing, ...]]:
    """Margins at the ends of every uncertain input's tolerance range (one at a time), per margin name; NaN where
    a margin is not re-evaluated (the buckled tether's, for inputs other than the current and the field)."""
    rows: dict[str, list[Swing]] = {k: [] for k in model.kinds}
    for d in unc.inputs:
        lo, hi = d.interval()
        kinds = tuple(k for k in model.kinds if not model.unanswered(k, (d.input,) if d.input not in
                                                                      model.powers(k) else ()))
        ends = [model.evaluate(model.values({d.input: input_value(model, d, x)}), kinds) if kinds else {}
                for x in (lo, hi)]
        for k in model.kinds:
            a, b = (e[k].value if k in e else math.nan for e in ends)
            rows[k].append(Swing(d.input, lo, hi, a, b))
    return {k: tuple(v) for k, v in rows.items()}


def input_value(model: MarginModel, d: Distribution, x: float) -> float:
    """A value of d as the model's input (SI; factors multiply the nominal value; bending_stiffness stays a
    factor)."""
    if d.input == "bending_stiffness":
        return x
    return model.nominal[d.input] * x if d.factor else x
