"""Special points of the generic continuation: a branch point that is a fold is reported as that fold, and its
location is not refined past the point where that is known."""

from __future__ import annotations

import numpy as np
import pytest

from etcheck.numerics import continuation as cont


class _Parabola:
    """F(u, p) = p - u^2 on R^2 (u_2 = p u_1 keeps the Jacobian regular): a fold at u_1 = 0, p = 0, and a
    "bp" test that changes sign at u_1 = ``offset``, nearly a step there (as a determinant test next to a branch
    point, where the corrector lands on either branch)."""

    def __init__(self, offset: float):
        self.offset = offset

    def residual(self, u, p):
        return np.array([p - u[0] ** 2, u[1] - p * u[0]])

    def jacobian(self, u, p):
        return np.array([[-2.0 * u[0], 0.0], [-p, 1.0]]), np.array([1.0, -u[0]])

    def retract(self, u, du):
        return u + du

    def tests(self, u, p, Ju):
        d = float(u[0] - self.offset)
        return {"bp": float(np.sign(d)) * (1e-3 + abs(d))}


def _run(offset: float, settle: bool, monkeypatch) -> tuple[cont.ContinuationResult, int]:
    trials = []
    locate = cont._locate

    def counted(problem, a, b, name, W, opts, settled=None):
        return locate(problem, a, b, name, W, opts, settled=settled if settle else None)

    trial = cont._trial_point

    def counted_trial(problem, br, s_a, sig, name, W, opts):
        trials.append(name)
        return trial(problem, br, s_a, sig, name, W, opts)

    monkeypatch.setattr(cont, "_locate", counted)
    monkeypatch.setattr(cont, "_trial_point", counted_trial)
    opts = cont.ContinuationOptions(ds=0.13, ds_max=0.13, p_max=0.5, detect_bp=False)
    # from u_1 = -1/2 (p = 1/4, u_2 = u_1^3) towards the fold, then up the other arm to p = 1/2
    res = cont.continuation(_Parabola(offset), np.array([-0.5, -0.125]), 0.25, np.array([1.0, 0.75, -1.0]), opts)
    return res, trials.count("bp")


@pytest.mark.parametrize("offset", [3e-9, -2e-9])
def test_branch_point_at_a_fold_is_the_fold_and_stops_refining(offset, monkeypatch):
    with monkeypatch.context() as m:
        full, full_trials = _run(offset, False, m)
    with monkeypatch.context() as m:
        quick, quick_trials = _run(offset, True, m)
    kinds = [(q.kind, q.value) for q in quick.special]
    assert [k for k, _ in kinds] == ["fold", "bp"]
    fold, bp = quick.special
    assert abs(fold.p) < 1e-12 and bp.p == fold.p and bp.bracket == fold.bracket  # the bp is the fold
    assert [(q.kind, q.p, q.bracket) for q in quick.special] == [(q.kind, q.p, q.bracket) for q in full.special]
    assert 0 < quick_trials < full_trials


def test_branch_point_off_the_fold_is_located_in_full(monkeypatch):
    res, _ = _run(0.3, True, monkeypatch)  # u_1 = 0.3 is past the fold, on the upper arm: its own point
    bp = [q for q in res.special if q.kind == "bp"]
    assert len(bp) == 1 and bp[0].converged
    assert abs(bp[0].p - 0.09) < 1e-9  # p = u_1^2
