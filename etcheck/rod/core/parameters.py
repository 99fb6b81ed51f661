"""The dimensionless parameters of the whirling rod (eqs. (36), (42) of arXiv:0810.3668) and how its ends are held."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from etcheck.rod.core.ends import ALL_WELDED, Ends

#: First clamped-clamped bending root to the fourth power, 4.730040744862704**4:
#: the paper's reference-frequency constant f (eq. (36)).
F_CLAMPED = 4.730040744862704**4


@dataclass(frozen=True)
class RodParameters:
    """Dimensionless parameters of the rod problem (all floats, dimensionless).

    P      rotary inertia I1/(A L^2)
    R      anisotropy EI2/EI1 (0 < R <= 1, d1 is the stiff axis)
    Gamma  torsion/bending 2G/E = 2 GJ/(EI1 + EI2)
    f      scaling constant of eq. (36) (the paper's Sec. VI uses f = 1)
    B      magnetic load B0 I L^3/(f EI1)
    omega  spin rate omega/omega_c
    T      end tension T L^2/(f EI1), positive in tension
    gamma  Kelvin-Voigt damping gamma_v omega_c
    ends   attachment at s = 0 and s = 1 (:class:`etcheck.rod.core.ends.Ends`; the paper's is welded at both)

    The scaling constant f stays the clamped beam's (eq. (36)) whatever the ends: it is only a scale.
    """

    P: float
    R: float
    Gamma: float
    f: float = F_CLAMPED
    B: float = 0.0
    omega: float = 0.0
    T: float = 0.0
    gamma: float = 0.0
    ends: Ends = ALL_WELDED

    def __post_init__(self) -> None:
        object.__setattr__(self, "ends", Ends.of(self.ends))  # names (a list from JSON, a tuple) become the typed pair
        for name in ("P", "R", "Gamma", "f", "B", "omega", "T", "gamma"):
            value = getattr(self, name)
            if not math.isfinite(value):
                raise ValueError(f"rod parameter {name} must be finite, got {value!r}")
        if self.P < 0:
            raise ValueError(f"rod parameter P must be >= 0, got {self.P!r}")
        if not 0 < self.R <= 1:
            raise ValueError(f"rod parameter R must lie in (0, 1], got {self.R!r}")
        for name in ("Gamma", "f"):
            if getattr(self, name) <= 0:
                raise ValueError(f"rod parameter {name} must be > 0, got {getattr(self, name)!r}")
        if self.gamma < 0:
            raise ValueError(f"rod parameter gamma must be >= 0, got {self.gamma!r}")

    def with_(self, **changes) -> RodParameters:
        """A copy with some parameters changed (e.g. ``p.with_(B=1.0)``)."""
        return replace(self, **changes)
