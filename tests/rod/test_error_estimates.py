"""Stated errors of the primary pitchforks against the true error (issue 11).

The pitchfork loads of the straight rod (:func:`etcheck.rod.buckled.branches.pitchfork_loads`)
and the lift-off spins (:func:`etcheck.rod.buckled.branches.liftoff_estimate`) report the
value at the finer of two resolutions and, as its error, the change of the
coarser value. Over scenes away from the SET defaults (other R, P, tension,
compression, spin) the true error of the reported value, measured against a
much finer resolution, must not exceed the estimate; and the estimate must not
exceed twice the coarse value's true error (plus the rounding floor): it is
not looser than the discretisation error it describes. (Against the finer
value the estimate is conservative by the ratio of the two resolutions'
errors, which for a spectrally converging collocation can be large: that is
the price of a bound from two resolutions.)
"""

from __future__ import annotations

import numpy as np
import pytest

from etcheck.rod.buckled import pitchforks, symmetry
from etcheck.rod.core.parameters import RodParameters

#: the estimates use N = 16 and 24; the reference values N = 44
N_EST, N_REF = 16, 44

SCENES = {
    "SET": RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3),
    "spun, tensioned": RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, omega=0.3, T=0.5),
    "R 0.1, compressed, heavy rotary inertia": RodParameters(P=0.05, R=0.1, Gamma=1 / 1.3, omega=0.2, T=-0.3),
    "R 0.9, strong tension": RodParameters(P=1e-6, R=0.9, Gamma=0.7, omega=0.5, T=3.0),
}


def _check(value: np.ndarray, error: np.ndarray, coarse_error: np.ndarray, ref: np.ndarray) -> None:
    true = np.abs(value - ref)
    floor = pitchforks.ROUNDING * np.abs(ref)
    assert np.all(true <= error), (true, error)
    assert np.all(error <= 2.0 * coarse_error + floor), (error, coarse_error)


@pytest.mark.parametrize("scene", list(SCENES))
def test_pitchfork_load_errors_bound_the_true_error(scene):
    p = SCENES[scene]
    for which in ("S1", "S2"):
        ref = pitchforks.class_loads(p, which, N_REF, 2)
        est = pitchforks.pitchfork_loads(p, which, N_EST, 2)
        coarse = pitchforks.class_loads(p, which, N_EST, 2)
        _check(est.loads, est.errors, np.abs(coarse - ref), ref)


def test_liftoff_spin_errors_bound_the_true_error():
    checked = 0
    for name in ("SET", "spun, tensioned"):
        p = SCENES[name]
        for which in ("b1", "b2"):
            est = pitchforks.liftoff_estimate(p, which, 1, N=N_EST)
            if not np.isfinite(est.omega):
                continue
            roots = pitchforks.pitchfork_spins(p, symmetry.BRANCH_CLASS[which], N_REF)
            ref = roots[np.argmin(np.abs(roots - est.omega))]
            _check(np.array([est.omega]), np.array([est.error]), np.array([abs(est.omega_coarse - ref)]), np.array([ref]))
            checked += 1
    assert checked >= 4


#: damped critical values next to the end of their line, where they vanish like a square root: the load
#: root just below the unloaded rod's critical spin, the spin root just below the static load
NEAR_END = [
    ("load near the critical spin, R = 1", RodParameters(P=1e-6, R=1.0, Gamma=0.76923, gamma=0.1, omega=0.99999), "B"),
    ("load near the critical spin, SET", RodParameters(P=1e-3, R=21 / 38, Gamma=0.76923, gamma=0.1,
                                                       omega=0.74338), "B"),
    ("spin near the static load, SET", RodParameters(P=1e-3, R=21 / 38, Gamma=0.76923, gamma=0.1, B=0.58539), "omega"),
]


@pytest.mark.parametrize("name, params, axis", NEAR_END, ids=[n for n, _, _ in NEAR_END])
def test_damped_critical_estimate_bounds_round_off_near_the_end_of_a_line(name, params, axis):
    """Two resolutions each at round-off can agree far better than either is right where a root falls like
    a square root: the stated error must still bound the distance to the exact determinant."""
    from etcheck.rod.straight.collocation.damped_critical import damped_critical
    from etcheck.rod.straight.exact.roots import first_exact_root

    d = damped_critical(params, tol=1e-10)
    r = d.critical_load if axis == "B" else d.critical_spin
    end = d.spin_at_rest.value if axis == "B" else first_exact_root(params.with_(B=0.0, omega=0.0), "B").value
    assert 0 < r.value < 0.3 * (end if axis == "omega" else 1.0)  # close to the end: the root is small
    exact = first_exact_root(params, axis, 1e-12)
    true = abs(r.value - exact.value) / exact.value  # both errors are relative to the value
    assert true <= r.error + exact.error, f"{name}: stated {r.error:.1e}, true {true:.1e}"
