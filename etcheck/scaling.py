"""Mission <-> dimensionless problem: the scalings of arXiv:0810.3668 eq. (36).

``scene(mission)`` reduces a mission to one worst-case operating point in SI
floats; ``scale(scene)`` gives the dimensionless :class:`RodParameters` plus the
:class:`Scales` needed to go back; ``unscale`` inverts it exactly (to rounding).
This is the one unit boundary: the scene carries every operating value a check
needs (current, field, tension, stiffnesses ... in SI floats) and the scales turn
dimensionless answers back into SI (:meth:`Scales.line_load`, :meth:`Scales.current`,
:meth:`Scales.rpm` ...); nothing past this module handles units.

    omega_c = sqrt(f EI1 / (rho A L^4))   [rad/s]
    B       = I B0 L^3 / (f EI1)          T̄ = T L^2 / (f EI1)
    ω̄       = omega / omega_c             gamma = gamma_v omega_c
    P       = I1 / (A L^2)                R = EI2 / EI1     Gamma = 2 GJ / (EI1 + EI2)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import astropy.units as u

from etcheck.input.gravity_gradient import GravityGradient
from etcheck.input.mission import DEFAULT_GAMMA, Mission
from etcheck.rod.core.ends import ALL_WELDED
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.profile import Profile

if TYPE_CHECKING:  # rung 1v (scipy.sparse) is imported only for a mission with profiles
    from etcheck.rod.straight.varying.profiles import Tether

#: rad/s -> revolutions per minute
RPM = 60.0 / (2.0 * math.pi)


@dataclass(frozen=True)
class MagneticField:
    """The worst-case magnetic field at the tether [T]: ``axial`` along the undeformed tether (|B0| of the
    paper's load I B0) and ``cross`` across it (the bow under the Lorentz load: stated, the largest over the
    orbit, else taken equal to the axial field). A direction of the cross field (an angle about the tether) is
    one more field of this record."""

    axial: float
    cross: float


@dataclass(frozen=True)
class Scene:
    """One operating point in SI floats (the unit edge has been crossed).

    length [m], EI1, EI2, GJ [N m^2], mass_per_length [kg/m], P [-],
    load = |I B0| [N/m], spin_rate [rad/s], tension [N] (positive pulls),
    damping_time gamma_v [s], f [-]; current = |I| [A] and field [T], the
    worst case whose product is ``load`` (None in a scene scaled back from
    dimensionless parameters, which know only the product); axial_stiffness
    E A [N] (None where the mission gives no youngs_modulus and cross-section).
    """

    length: float
    EI1: float
    EI2: float
    GJ: float
    mass_per_length: float
    P: float
    load: float
    spin_rate: float
    tension: float
    damping_time: float
    f: float
    ends: tuple[str, str] = ALL_WELDED  # (lower, upper): how the tether is attached (etcheck.rod.core.ends)
    # along the tether (dimensionless shapes of s, the fraction of the length from the lower end): I(s)/I_max of
    # operation.current_profile (None: one current) and the gravity-gradient tension of tether.end_masses (None:
    # one end tension); ``tension`` is then its smallest value along the tether, a bound
    current_profile: Profile | None = None
    gravity_gradient: GravityGradient | None = None
    current: float | None = None
    field: MagneticField | None = None
    axial_stiffness: float | None = None

    @property
    def profiles(self) -> bool:
        """Whether current or tension varies along the tether (rung 1v)."""
        return self.current_profile is not None or self.gravity_gradient is not None

    @property
    def spin_rpm(self) -> float:
        """The spin rate in revolutions per minute."""
        return self.spin_rate * RPM

    @property
    def largest_tension(self) -> float:
        """The largest tension along the tether [N]: the gravity gradient's at the centre of mass, else the end
        tension."""
        return self.gravity_gradient.maximum if self.gravity_gradient is not None else self.tension


@dataclass(frozen=True)
class Scales:
    """What turns dimensionless numbers back into SI (arXiv:0810.3668 eq. (36)); ``current`` [A] and ``field``
    [T]: the scene's worst case (None where unknown), which split a load I B0 into a current or a field."""

    length: float  # L [m]
    EI1: float  # [N m^2]
    mass_per_length: float  # rho A [kg/m]
    f: float  # [-]
    worst_current: float | None = None  # |I| [A]
    worst_field: float | None = None  # |B0| [T]

    @property
    def frequency(self) -> float:
        """omega_c = sqrt(f EI1 / (rho A L^4)) [rad/s]."""
        return math.sqrt(self.f * self.EI1 / (self.mass_per_length * self.length**4))

    @property
    def force(self) -> float:
        """Force scale f EI1 / L^2 [N] (end tension, internal force)."""
        return self.f * self.EI1 / self.length**2

    @property
    def load(self) -> float:
        """Distributed-load scale f EI1 / L^3 [N/m]: I B0 = B * load."""
        return self.f * self.EI1 / self.length**3

    @property
    def spin_rpm(self) -> float:
        """omega_c in revolutions per minute: the rpm of a dimensionless spin rate of 1."""
        return self.frequency * RPM

    def line_load(self, B):
        """Load per length I B0 = B f EI1 / L^3 [N/m] of a dimensionless load B (a float or an array)."""
        return B * self.load

    def current(self, B: float) -> float:
        """The current [A] whose load I B0 at the worst field is the dimensionless load B."""
        return self.line_load(B) / self.worst_field

    def tension(self, T):
        """Force T f EI1 / L^2 [N] of a dimensionless force T (end tension, internal force)."""
        return T * self.force

    def moment(self, M):
        """Moment M f EI1 / L [N m] of a dimensionless moment M."""
        return M * (self.force * self.length)

    def distance(self, x):
        """Length x L [m] of a dimensionless length x."""
        return x * self.length

    def rad_s(self, w):
        """Angular rate w omega_c [rad/s] of a dimensionless rate (spin, frequency, growth rate)."""
        return w * self.frequency

    def damping_time(self, gamma: float) -> float:
        """Kelvin-Voigt damping time gamma_v = gamma / omega_c [s] of a dimensionless damping gamma."""
        return gamma / self.frequency

    def hz(self, w):
        """Frequency w omega_c / (2 pi) [Hz] of a dimensionless angular frequency w."""
        return self.rad_s(w) / (2.0 * math.pi)

    def rpm(self, w):
        """Spin rate [rpm] of a dimensionless spin rate w."""
        return w * self.frequency * RPM


@dataclass(frozen=True)
class Scaled:
    """The dimensionless problem and its scales; ``tether``: the problem with its profiles along the tether
    (rung 1v: current b(s), tension T tau(s) with T the largest tension), None where both are uniform. ``params``
    has the uniform smallest tension (the bound)."""

    params: RodParameters
    scales: Scales
    tether: Tether | None = None


def scene(mission: Mission, field: MagneticField | None = None) -> Scene:
    """The worst-case operating point of a mission, in SI floats.

    Worst case: largest |I| times largest |B0| over the given ranges. A missing
    damping_time means the default dimensionless gamma (DEFAULT_GAMMA) at the
    mission's length, i.e. gamma_v = DEFAULT_GAMMA / omega_c. ``field``: the
    worst field where the mission does not give it (None: ``operation.axial_field``
    and ``operation.cross_field``); a mission with an [orbit] table takes the field
    over its orbit, which the check's orbit stage evaluates and passes
    (:func:`etcheck.checks.orbit_field.resolve`).
    """
    # plain Python floats (not numpy scalars): everything downstream stays JSON-able
    t, op = mission.tether, mission.operation
    EI1, EI2 = (float(q.to_value(u.N * u.m**2)) for q in t.bending_stiffness)
    profile = op.current_profile
    L = float(t.length.to_value(u.m))
    rho_a = float(t.mass_per_length.to_value(u.kg / u.m))
    f = mission.check.scaling_constant
    field = _field(mission) if field is None else field
    current = float(op.worst_current.to_value(u.A))
    if t.damping_time is None:
        damping = DEFAULT_GAMMA / Scales(L, EI1, rho_a, f).frequency
    else:
        damping = float(t.damping_time.to_value(u.s))
    return Scene(
        length=L,
        EI1=EI1,
        EI2=EI2,
        GJ=float(t.torsional_stiffness.to_value(u.N * u.m**2)),
        mass_per_length=rho_a,
        P=t.rotary_inertia_ratio,
        load=current * field.axial,
        spin_rate=float(op.spin_rate.to_value(u.rad / u.s)),
        tension=float(op.end_tension.to_value(u.N)),
        damping_time=damping,
        f=f,
        ends=t.end_conditions,
        current_profile=None if profile is None or profile.uniform else profile.profile,
        gravity_gradient=op.gravity_gradient,
        current=current,
        field=field,
        axial_stiffness=None if t.youngs_modulus is None or t.cross_section_area is None else
        float((t.youngs_modulus * t.cross_section_area).to_value(u.N)),
    )


def _field(mission: Mission) -> MagneticField:
    """The worst field the mission gives along the tether and across it [T] (the cross field, where not given,
    taken equal to the axial one)."""
    if mission.orbit is not None:
        raise ValueError("the field of a mission with an [orbit] table is the worst over its orbit: the check's "
                         "orbit stage evaluates it (etcheck.checks.orbit_field.resolve)")
    axial = float(max(abs(b) for b in mission.operation.axial_field).to_value(u.T))
    cross = mission.operation.worst_cross_field
    return MagneticField(axial, axial if cross is None else float(cross.to_value(u.T)))


def scale(s: Scene) -> Scaled:
    """Scene (SI) -> dimensionless parameters (arXiv:0810.3668 eq. (36)) and scales."""
    scales = Scales(length=s.length, EI1=s.EI1, mass_per_length=s.mass_per_length, f=s.f, worst_current=s.current,
                    worst_field=None if s.field is None else s.field.axial)
    wc = scales.frequency
    params = RodParameters(
        P=s.P,
        R=s.EI2 / s.EI1,
        Gamma=2.0 * s.GJ / (s.EI1 + s.EI2),
        f=s.f,
        B=s.load / scales.load,
        omega=s.spin_rate / wc,
        T=s.tension / scales.force,
        gamma=s.damping_time * wc,
        ends=s.ends,
    )
    return Scaled(params=params, scales=scales, tether=_tether(s, params, scales))


def _tether(s: Scene, params: RodParameters, scales: Scales) -> Tether | None:
    """The problem with its profiles (T the largest tension, tau = T(s) / T_max), None without any."""
    if not s.profiles:
        return None
    from etcheck.rod.straight.varying.profiles import Tether

    current = s.current_profile or Profile.uniform()
    gg = s.gravity_gradient
    if gg is None:
        return Tether(params, current)
    return Tether(params.with_(T=gg.maximum / scales.force), current, gg.shape())


def unscale(scaled: Scaled) -> Scene:
    """Dimensionless parameters and scales -> the SI scene (inverse of scale; the profiles along the tether are
    not carried back: the scene of the uniform bound)."""
    p, sc = scaled.params, scaled.scales
    wc = sc.frequency
    EI2 = p.R * sc.EI1
    return Scene(
        length=sc.length,
        EI1=sc.EI1,
        EI2=EI2,
        GJ=p.Gamma * (sc.EI1 + EI2) / 2.0,
        mass_per_length=sc.mass_per_length,
        P=p.P,
        load=p.B * sc.load,
        spin_rate=p.omega * wc,
        tension=p.T * sc.force,
        damping_time=p.gamma / wc,
        f=p.f,
        ends=p.ends,
    )


def with_length(s: Scene, length: float) -> Scene:
    """The same tether at another length [m] (what-if): P scales as L^-2.

    Stiffnesses, mass per length, load per length, spin, end tension and damping
    time are physical properties and stay; the dimensionless B ∝ L^3,
    P ∝ L^-2, T̄ ∝ L^2, ω̄ ∝ L^2, gamma ∝ L^-2 follow from :func:`scale`. A
    gravity-gradient tension (end masses) is recomputed at the new length: it
    grows with it (the end bodies sit farther from the centre of mass, and the
    tether's own mass grows).
    """
    from dataclasses import replace

    gg = s.gravity_gradient
    if gg is None:
        return replace(s, length=length, P=s.P * (s.length / length) ** 2)
    gg = replace(gg, length=length)  # the end bodies and the tether's own mass pull harder on a longer tether
    return replace(s, length=length, P=s.P * (s.length / length) ** 2, tension=gg.minimum, gravity_gradient=gg)
