"""The margins of one mission as functions of its physical inputs, computed by the check's own route.

Everything here works on SI floats and the dimensionless parameters of
:mod:`etcheck.scaling`; units are crossed only by the mission parser. The
uncertainty study (:mod:`etcheck.checks.margins.uncertainty`) asks this model for the
margins at perturbed inputs:

* rung 0 (omega = T = 0, and no spin or tension among the uncertain inputs):
  margin = B_1(R) / B = beta_1^3 sqrt(EI1 EI2) / (|I B0| L^3) (eq. (91)),
  closed form, vectorised with numpy;
* rung 1: the critical load at the operating spin and tension and the critical
  spin at the operating load by :func:`etcheck.checks.rungs.straight.critical_values`,
  the very function whose answers the check's margins are (static pencils or
  exact characteristic determinant with damping, exact undamped determinant
  without), at the check's tolerances, each with its error estimate, and the
  margin by the check's rule (:func:`etcheck.checks.margins.margin.margin_from_critical`);
* rungs 2-3 (the buckled tether's margin to its secondary pitchfork): not
  re-evaluated (seconds per point); only inputs that scale it exactly are
  integrated (see :meth:`MarginModel.powers`: the current and the field; without
  spin and tension also the length and both stiffnesses together).

**Exact structure.** Each margin is critical / operating, and some inputs
enter only the operating value: every margin is an exact power law in them,
margin = M(other inputs) x prod (x_j / x_j0)^a_j, which the probability
integrates in closed form (:meth:`MarginModel.powers`); others provably do not
move it at all (:meth:`MarginModel.inert`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from etcheck.checks.margins.margin import BUCKLED, INCOMPLETE, LOAD_AT_REST, LOAD_AT_SPIN, SPIN, margin_from_critical
from etcheck.checks.plan import EXACT, SPECTRAL, straight_route
from etcheck.checks.rungs.straight import DEFAULT_OPTIONS, WhirlOptions, critical_values
from etcheck.rod.core.ends import ALL_WELDED
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.analytic import static_roots

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
#: The common factor on EI1 and EI2 ("bending_stiffness" of [uncertainty]), and every physical input.
INPUTS = ("bending_stiffness", *PHYSICAL)
LABELS = {"bending_stiffness": "EI1 and EI2 together (one factor)"} | {k: v[1] for k, v in PHYSICAL.items()}

CLOSED = "closed form"
ROUTE_NAMES = {
    CLOSED: "rung 0 closed form beta_1^3 sqrt(EI1 EI2) / (|I B0| L^3) (eq. (91)), vectorised",
    SPECTRAL: "rung 1 as the check: first roots of the static pencils (exact determinant where a pencil root "
              "missed its tolerance)",
    EXACT: "rung 1 as the check: the exact characteristic determinant",
}
UNDAMPED = "rung 1 as the check: the exact undamped determinant (flutter possible)"
#: Exponents of the rung-0 margin beta_1^3 sqrt(EI1 EI2) / (|I B0| L^3) in its inputs.
RUNG0_POWERS = {"EI1": 0.5, "EI2": 0.5, "bending_stiffness": 1.0, "length": -3.0, "current": -1.0,
                "axial_field": -1.0}


@dataclass(frozen=True)
class MarginValue:
    """One margin at one set of inputs: ``value`` (dimensionless; inf where no value destabilises the tether,
    0 where it is unstable without load or spin), its relative ``error``, and why it was not answered (``why``;
    then ``value`` is NaN)."""

    value: float
    error: float = 0.0
    why: str = ""

    @property
    def answered(self) -> bool:
        return not self.why


@dataclass(frozen=True)
class MarginModel:
    """The margins of one mission as functions of its physical inputs (SI floats).

    ``nominal``: the physical inputs (keys of PHYSICAL, SI), the current and
    field at their worst case; ``P0``, ``L0``: rotary inertia ratio at the
    mission length (P ~ L^-2); ``gj_ratio``: GJ / (EI1 + EI2) when GJ follows
    from poisson_ratio (None: GJ is its own input); ``kinds``: the margins
    (names of the check's margins); ``route``: CLOSED, or the check's rung-1
    route (SPECTRAL, EXACT); ``options``: the check's rung-1 tolerances;
    ``at_nominal``: the check's own margin values (for the margins not
    re-evaluated); ``damped``: the mission has damping (``gamma0``, the
    dimensionless damping); ``ends``: the attachment (:mod:`etcheck.rod.core.ends`). Where the uncertain inputs give samples spin or
    tension although the mission has none, rung 1 answers every sample
    (``route`` the one the plan picks for a spinning, taut sample).
    """

    nominal: dict[str, float]
    P0: float
    L0: float
    f: float
    gj_ratio: float | None
    kinds: tuple[str, ...]
    route: str
    required: float
    options: WhirlOptions = DEFAULT_OPTIONS
    at_nominal: dict[str, float] = field(default_factory=dict)
    damped: bool = True
    gamma0: float = 0.0
    ends: tuple[str, str] = ALL_WELDED

    # ------------------------------------------------------------------ inputs

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
        """Dimensionless parameters (eqs. (36), (42)) of physical inputs; the stiff axis is the larger EI. On the
        damped routes gamma is the mission's whatever the inputs: the critical values do not depend on it (see
        :meth:`inert`), and samples then share the operators the check assembled."""
        EI1, EI2 = max(v["EI1"], v["EI2"]), min(v["EI1"], v["EI2"])
        L, m = v["length"], v["mass_per_length"]
        wc = math.sqrt(self.f * EI1 / (m * L**4))
        gamma = self.gamma0 if self.damped and self.route != CLOSED else v["damping_time"] * wc
        return RodParameters(P=self.P0 * (self.L0 / L) ** 2, R=EI2 / EI1, Gamma=2 * v["torsional_stiffness"] / (EI1 + EI2),
                             f=self.f, B=v["current"] * v["axial_field"] * L**3 / (self.f * EI1),
                             omega=v["spin_rate"] / wc, T=v["end_tension"] * L**2 / (self.f * EI1), gamma=gamma,
                             ends=self.ends)

    @property
    def name(self) -> str:
        """What answers the samples, in words."""
        return ROUTE_NAMES[self.route] if self.damped or self.route == CLOSED else UNDAMPED

    # ------------------------------------------------------------------ exact structure

    def powers(self, kind: str) -> dict[str, float]:
        """Inputs in which the margin ``kind`` is an exact power law whatever the other inputs (input -> exponent):
        margin = M(others) (x / x0)^a. Rung 0: every input of eq. (91); rung 1 and the buckled tether: the current
        and the field (they enter only the operating load) for the load margins, the spin rate for the spin margin
        (it enters only the operating spin)."""
        if self.route == CLOSED and kind != BUCKLED:
            return dict(RUNG0_POWERS)
        if kind == SPIN:
            return {"spin_rate": -1.0}
        if kind == BUCKLED and self.static:
            return {"current": -1.0, "axial_field": -1.0, "length": -3.0} | (
                {"bending_stiffness": 1.0} if self.gj_ratio is not None else {})
        return {"current": -1.0, "axial_field": -1.0}

    @property
    def static(self) -> bool:
        """No spin and no end tension at the mission's values: the buckled tether's secondary pitchfork is then a
        static bifurcation of the coil, B*(R, Gamma) (Sec. VI), and its margin B* f EI1 / (|I B0| L^3) is a
        power law in the length and (with R and Gamma fixed: GJ from poisson_ratio) in both stiffnesses together."""
        return self.nominal["spin_rate"] == 0 and self.nominal["end_tension"] == 0

    def inert(self, kind: str, uncertain: tuple[str, ...] = ()) -> dict[str, str]:
        """Inputs that provably do not move the margin ``kind`` (input -> why), given the ``uncertain`` inputs
        (for the buckled tether only where it is static: then neither its mass nor its damping enters its
        equilibria or their static bifurcation)."""
        if kind == BUCKLED:
            if not self.static or {"spin_rate", "end_tension"} & set(uncertain):
                return {}
            why = "the coil's equilibria and its static secondary pitchfork (no spin) do not contain it"
            return {"mass_per_length": why, "damping_time": why}
        if self.route == CLOSED:
            return {k: "rung 0: the static load of eq. (91) does not contain it" for k in INPUTS
                    if k not in RUNG0_POWERS}
        out = {"torsional_stiffness": "torsion decouples from bending about the straight tether"}
        if self.damped:
            out["damping_time"] = "with damping the straight tether loses stability where the static operator, " \
                                  "which does not contain damping, is singular (Kelvin-Tait-Chetaev)"
        if self.nominal["spin_rate"] == 0 and "spin_rate" not in uncertain:
            out["mass_per_length"] = "without spin the mass sets only the time scale"
        return out

    def unanswered(self, kind: str, shape: tuple[str, ...]) -> str:
        """Why the margin ``kind`` cannot be re-evaluated at other values of the inputs ``shape`` ("" if it can)."""
        if kind == BUCKLED and shape:
            scaled = ", ".join(self.powers(BUCKLED))
            return (f"the buckled tether's margin takes rungs 2-3 (seconds per point): only the inputs that scale it "
                    f"exactly ({scaled}) are integrated, not {', '.join(shape)}")
        if not self.damped and "damping_time" in shape:
            return "a damping tolerance on an undamped mission changes its model (give a damping time)"
        return ""

    # ------------------------------------------------------------------ evaluation

    def evaluate(self, v: dict[str, float], kinds: tuple[str, ...] | None = None) -> dict[str, MarginValue]:
        """The margins ``kinds`` (default all) at physical inputs v."""
        kinds = kinds or self.kinds
        out = {}
        if BUCKLED in kinds:
            out[BUCKLED] = MarginValue(self.at_nominal[BUCKLED] * self._buckled_scale(v))
        straight = tuple(k for k in kinds if k != BUCKLED)
        if straight and self.route == CLOSED:
            m = float(closed_form_margin({k: np.asarray(x) for k, x in v.items()}, self.ends))
            return out | {k: MarginValue(m, 3.0 * static_roots(self.ends, 1)[0].error) for k in straight}
        return out | (self.at_params(self.params(v), straight) if straight else {})

    def _buckled_scale(self, v: dict[str, float]) -> float:
        """The buckled tether's margin at ``v`` over the check's: the product of its powers (:meth:`powers`; the
        stiffnesses' common factor read as their geometric mean)."""
        scale = 1.0
        for k, a in self.powers(BUCKLED).items():
            if k == "bending_stiffness":
                x = math.sqrt(v["EI1"] * v["EI2"] / (self.nominal["EI1"] * self.nominal["EI2"]))
            else:
                x = v[k] / self.nominal[k]
            scale *= x**a
        return scale

    def at_params(self, p: RodParameters, kinds: tuple[str, ...]) -> dict[str, MarginValue]:
        """The straight tether's margins ``kinds`` at dimensionless parameters p (rung 1; the elasticities
        are differentiated here)."""
        load, spin = critical_values(p, self.options, self.route, spin=SPIN in kinds)
        return {k: _ratio(spin, p.omega, self.required) if k == SPIN else _ratio(load, p.B, self.required)
                for k in kinds}

    def margin(self, v: dict[str, float], kind: str) -> MarginValue:
        """One margin at physical inputs v."""
        return self.evaluate(v, (kind,))[kind]


def _ratio(point, operating: float, required: float) -> MarginValue:
    """critical / operating of a rung-1 critical point by the check's rule (dimensionless)."""
    m = margin_from_critical("", "", point, point.value, operating, 1.0, required, "", "")
    if m.verdict == INCOMPLETE:
        return MarginValue(math.nan, math.nan, m.why or "the critical value was not located")
    return MarginValue(math.inf if m.value is None else m.value, m.error or 0.0)


def closed_form_margin(v: dict[str, np.ndarray], ends: tuple[str, str] = ALL_WELDED) -> np.ndarray:
    """Rung-0 load margin beta_1^3 sqrt(EI1 EI2) / (|I| |B0| L^3), vectorised (SI arrays in, dimensionless out);
    beta_1 of the ends (the first double zero of chi for welded ends, eq. (91))."""
    beta1_cubed = static_roots(ends, 1)[0].beta ** 3
    with np.errstate(divide="ignore"):
        return beta1_cubed * np.sqrt(v["EI1"] * v["EI2"]) / (v["current"] * v["axial_field"] * v["length"] ** 3)


def margin_model(mission, scene, scaled, chosen, margins, options: WhirlOptions = DEFAULT_OPTIONS) -> MarginModel:
    """The margin model of a checked mission: its scene (SI), scaled parameters, plan, the check's margins
    (:class:`~etcheck.checks.margins.margin.Margin`) and rung-1 options, at the worst-case operating point."""
    p = scaled.params
    unc = mission.studies.uncertainty
    moving = unc is not None and any(unc.get(k) is not None for k in ("spin_rate", "end_tension"))
    closed = chosen.rung == 0 and chosen.complete and not moving
    if closed:
        route = CLOSED
    elif chosen.rung == 1 and chosen.route:
        route = chosen.route
    else:  # rung 0 with spin or tension among the uncertain inputs: the rung-1 route of a spinning, taut sample
        route = straight_route(p.with_(omega=max(p.omega, 1e-3), T=max(p.T, 1e-3)))
    known = (LOAD_AT_REST, LOAD_AT_SPIN, SPIN, BUCKLED)
    kinds = tuple(m.name for m in margins if m.name in known)
    nominal = {"EI1": scene.EI1, "EI2": scene.EI2, "torsional_stiffness": scene.GJ,
               "mass_per_length": scene.mass_per_length, "length": scene.length,
               "current": scene.current, "axial_field": scene.field.axial, "spin_rate": scene.spin_rate,
               "end_tension": scene.tension, "damping_time": scene.damping_time}
    gj_ratio = scene.GJ / (scene.EI1 + scene.EI2) if mission.tether.poisson_ratio is not None else None
    at_nominal = {m.name: (math.inf if m.value is None else m.value) for m in margins}
    return MarginModel(nominal, scene.P, scene.length, scene.f, gj_ratio, kinds, route, mission.check.required_margin,
                       options, at_nominal, p.gamma > 0, p.gamma, p.ends)
