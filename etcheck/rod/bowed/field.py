"""The magnetic field's direction relative to the chord and the Lorentz load it puts on the tether (dimensionless).

The field is B0 b with the unit vector, in the e-frame (e3 along the chord, from the sliding end s = 0 to the
fixed end s = 1; e1, e2 along the stiff and weak axes d1, d2 of the undeformed tether)::

    b = (sin(alpha) cos(phi), sin(alpha) sin(phi), cos(alpha))

alpha: the angle between the field and the chord (alpha = 0 is the paper's field, B0 along e3); phi: the angle of
the cross component from the stiff axis d1 towards d2. The Lorentz force per unit length on the tether carrying
the current i(s) I along its tangent d3 is, in the f-scaling of eq. (36),

    n(s) = B i(s) d3 x b,

which for b = e3 is the load of eqs. (49)-(51). i(s) = 1 for one current; a profile i(s) (a bare tether that
collects its current, :class:`etcheck.rod.core.profile.Profile` of one smooth piece, largest value 1) makes the load circulatory
(docs/model.md, section 10). On the straight tether the load B i (e3 x b) = B i sin(alpha) (-sin(phi), cos(phi), 0)
points along :attr:`CrossField.in_plane`: that lateral direction and e3 span the plane of the bow; the other
lateral direction, :attr:`CrossField.out_of_plane` (along the cross component of b), is the direction of coiling.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from etcheck.rod.core.linear import skew
from etcheck.rod.core.profile import Profile

__all__ = ["CrossField", "lorentz_block"]


@dataclass(frozen=True)
class CrossField:
    """The field's direction (angles ``alpha``, ``phi`` in radians) and the current profile (None: one current,
    i = 1). Dimensionless; hashable."""

    alpha: float
    phi: float = 0.0
    current: Profile | None = None

    def __post_init__(self) -> None:
        for name in ("alpha", "phi"):
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"field angle {name} must be finite, got {getattr(self, name)!r}")
        if self.current is not None and len(self.current.coefficients) > 1:
            raise ValueError("the bowed tether takes a smooth current profile (one piece): one Chebyshev domain "
                             "converges only algebraically across a kink")

    @property
    def direction(self) -> np.ndarray:
        """The unit vector b (e-frame components)."""
        sa = math.sin(self.alpha)
        return np.array([sa * math.cos(self.phi), sa * math.sin(self.phi), math.cos(self.alpha)])

    @property
    def in_plane(self) -> np.ndarray:
        """Unit lateral direction of the load on the straight tether, e3 x b / |e3 x b| (defined by phi alone, also
        at alpha = 0)."""
        return np.array([-math.sin(self.phi), math.cos(self.phi), 0.0])

    @property
    def out_of_plane(self) -> np.ndarray:
        """Unit lateral direction of the field's cross component (cos(phi), sin(phi), 0): out of the plane of the
        bow."""
        return np.array([math.cos(self.phi), math.sin(self.phi), 0.0])

    @property
    def uniform(self) -> bool:
        """One current along the whole tether (the load has a potential)."""
        return self.current is None or self.current.uniform_value == 1.0

    def current_at(self, s) -> np.ndarray:
        """i(s) at the points s (ones for one current)."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        return np.ones_like(s) if self.current is None else self.current(s)


def lorentz_block(B: float, field: CrossField, t: np.ndarray, d3: np.ndarray, P: np.ndarray) -> np.ndarray:
    """The derivative of the collocated load B i(t_k) d3(t_k) x b with respect to the rotations a_j of the nodes
    (d3_j -> d3_j + a_j x d3_j), as the block [a, k, b, j] of the force rows (phi) and rotation columns (a).

    d(d3 x b) = (a x d3) x b = [b]x [d3]x a, so the block is B i(t_k) [b]x [d3]x P[k, j], with d3 taken at the
    node j (``d3`` of shape (N+1, 3): the exact derivative of the discrete residual) or at the point t_k
    (shape (N, 3): the linearisation's coefficient, eq. (71) with e3 -> b). ``t`` (N,) are the first-kind points,
    ``P`` (N, N+1) the resampling matrix.
    """
    n, n1 = P.shape
    i_t = field.current_at(t)
    C = skew(field.direction) @ skew(np.asarray(d3, dtype=float))  # (N or N+1, 3, 3)
    if C.shape[0] == n1:
        out = C.transpose(1, 2, 0)[:, None, :, :] * P[None, :, None, :]
    else:
        out = C.transpose(1, 0, 2)[:, :, :, None] * P[None, :, None, :]
    return B * i_t[None, :, None, None] * out
