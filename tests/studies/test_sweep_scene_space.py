"""Property test (issue 11): every sweep point over the scene space is answered, failed with a reason, or
outside the validated range — never an exception and never a non-finite number in the data."""

from __future__ import annotations

import json
import math

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.studies.sweep import STATUS_FAILED, STATUS_OK, STATUS_OUTSIDE, solve_point

params = st.builds(
    RodParameters,
    P=st.sampled_from([1e-9, 1e-5, 1e-3, 0.05, 0.5]),
    R=st.sampled_from([1.0, 0.5526, 0.1, 0.01, 1e-4, 2.5e-6]),
    Gamma=st.just(1 / 1.3),
    f=st.just(F_CLAMPED),
    B=st.floats(0.0, 1e4),
    omega=st.sampled_from([0.0, 0.01, 0.3, 1.0, 5.0]),
    T=st.sampled_from([0.0, 1.0, 1e2, 1e4, 1e7]),
    gamma=st.sampled_from([1e-9, 0.04375, 1.0]),
)


@settings(max_examples=30, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(params)
def test_every_damped_sweep_point_is_answered_or_says_why(p):
    r = solve_point(p, 1e-8)
    json.dumps(r.as_dict(), allow_nan=False)
    assert r.status in (STATUS_OK, STATUS_FAILED, STATUS_OUTSIDE)
    if r.status != STATUS_OK:
        assert r.reason and r.stable is None
        return
    assert r.model
    for v in (r.B_c, r.omega_c, r.omega_rest):
        assert v is None or (v >= 0 and (math.isfinite(v) or v == math.inf))
    assert isinstance(r.stable, bool)
    if r.B_c is not None and math.isfinite(r.B_c) and r.B_c > 0:
        # the operating point is stable exactly when it lies below the critical load at its spin
        assert r.stable == (p.B < r.B_c and (r.omega_rest is None or p.omega < r.omega_rest))
