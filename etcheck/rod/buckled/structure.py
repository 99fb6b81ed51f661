"""Rung 3: the structure of the linearisation about a buckled state, checked rather than
assumed (dimensionless).

**Structure (checked, not assumed; :func:`structure_check`).** In the
rotating frame the discretised linearisation is
A0 + lambda A1 + lambda^2 A2 with A1 = G + gamma D: every term linear in
lambda is either gyroscopic (Coriolis, rotary-inertia gyroscopic coupling) or
Kelvin-Voigt damping (the factor (1 + gamma lambda) of eq. (74)),
so A1 is affine in gamma, and dropping A1 leaves the non-gyroscopic undamped
problem K q + M q'' = 0 whose eigenvalues mu = lambda^2 are real when K is
symmetric (M > 0). Then (Kelvin-Tait-Chetaev, complete damping) the number of
eigenvalues with Re lambda > 0 for every gamma > 0 equals the number of
negative eigenvalues of K, i.e. the number of mu > 0; stability of an
equilibrium can only change where A0 is singular (a static bifurcation: the
primary and secondary pitchforks), never in a Hopf bifurcation. The solver
checks this independently (:func:`etcheck.rod.buckled.hopf.find_hopf` bisects on the complex modes).

"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from etcheck.rod.buckled.spectra import damped_operator, operator_eigenvalues, real_positive_count, static_problem
from etcheck.rod.core.spectrum import (
    ERROR_FLOOR,
)
from etcheck.rod.straight.collocation.spectral import THRESHOLD
from etcheck.runtime.blas import single_blas_thread

__all__ = ["StructureCheck", "structure_check"]


# --- structure ------------------------------------------------------------------------------


@dataclass(frozen=True)
class StructureCheck:
    """Structural checks of the linearisation about one equilibrium (dimensionless).

    ``hamiltonian_defect``: at gamma = 0, max over the inner half of the
    computed eigenvalues of the distance from -lambda to the nearest computed
    eigenvalue, relative (absolute below 0.1): 0 up to discretisation error
    when the undamped spectrum is Hamiltonian (lambda, -lambda, conj);
    ``max_real_undamped``: max |Re lambda| of those when none is real-unstable
    (0: purely imaginary); ``stiffness_asymmetry``: max |Im mu| / |mu| over
    the lowest mu = lambda^2 of A0 + mu A2 (A1 = 0: no gyroscopic, no damping
    terms) -- real mu (to discretisation error) means K symmetric relative to
    M; ``index``: number of mu > 0 (negative eigenvalues of K);
    ``unstable_damped``: number of eigenvalues with Re lambda > 0 for each
    gamma in ``gammas`` (Kelvin-Tait-Chetaev: equal to ``index``);
    ``A0_smallest_singular``: smallest singular value of A0 / largest.
    """

    N: int
    hamiltonian_defect: float
    max_real_undamped: float
    stiffness_asymmetry: float
    index: int
    gammas: tuple
    unstable_damped: tuple
    A0_smallest_singular: float

    @property
    def kelvin_tait_chetaev(self) -> bool:
        return all(u == self.index for u in self.unstable_damped)


@single_blas_thread
def structure_check(state, N: int | None = None, k: int = 8, gammas=(0.01, 0.04375)) -> StructureCheck:
    """Check the structure M q'' + (G + gamma D) q' + K q = 0 of the linearisation
    about ``state`` (eqs. (71)-(75)): see :class:`StructureCheck`.
    Dimensionless."""
    N0 = state.N if N is None else int(N)
    op = damped_operator(state.params, state, N0)
    nev = 2 * k + 8
    lam = operator_eigenvalues(op, 0.0, nev, False)
    order = np.argsort(np.abs(lam))
    inner = lam[order[: max(2, lam.size // 2)]]
    d = np.abs(-inner[:, None] - lam[None, :]).min(axis=1) / np.maximum(np.abs(inner), ERROR_FLOOR)
    ham = float(np.max(d))
    mr = float(np.max(np.abs(inner.real)))
    # non-gyroscopic, undamped: (A0 + mu A2) q = 0, mu = lambda^2 -> eigenvalues of the QEP with A1 = 0
    lam0 = static_problem(op, nev)
    mu = lam0**2
    mu_low = mu[np.argsort(np.abs(mu))][: max(2, mu.size // 2)]
    asym = float(np.max(np.abs(mu_low.imag) / np.maximum(np.abs(mu_low), 1e-300)))
    index = real_positive_count(lam0)  # each mu > 0 appears as the pair +-sqrt(mu)
    unstable = []
    for g in gammas:
        lg = operator_eigenvalues(op, g, nev, False)
        unstable.append(int(np.count_nonzero(lg.real > THRESHOLD)))
    sv = np.linalg.svd(op.A0, compute_uv=False)
    return StructureCheck(N0, ham, mr, asym, index, tuple(gammas), tuple(unstable), float(sv[-1] / sv[0]))
