"""Special points of the generic continuation: a branch point that is a fold is reported as that fold, and its
location is not refined past the point where that is known."""

from __future__ import annotations

import numpy as np
import pytest

from etcheck.numerics import continuation as cont
from etcheck.numerics import corrector
from etcheck.numerics import special_points as sp


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
    locate = sp.locate

    def counted(problem, a, b, name, W, opts, settled=None):
        return locate(problem, a, b, name, W, opts, settled=settled if settle else None)

    trial = sp.trial_point

    def counted_trial(problem, br, s_a, sig, name, W, opts):
        trials.append(name)
        return trial(problem, br, s_a, sig, name, W, opts)

    monkeypatch.setattr(sp, "locate", counted)
    monkeypatch.setattr(sp, "trial_point", counted_trial)
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


class _Circle:
    """F(u, p) = |u|^2 + p^2 - 1 and u_2 = sin(u_1) p on R^2: a regular branch on which Newton converges
    quadratically from any nearby predictor."""

    def residual(self, u, p):
        return np.array([u @ u + p * p - 1.0, u[1] - np.sin(u[0]) * p])

    def jacobian(self, u, p):
        return (np.array([[2 * u[0], 2 * u[1]], [-np.cos(u[0]) * p, 1.0]]),
                np.array([2 * p, -np.sin(u[0])]))

    def retract(self, u, du):
        return u + du


@pytest.fixture
def solves(monkeypatch) -> list:
    """The Newton solves of the continuation module, one entry each (cleared by the test as it goes)."""
    done = []
    solve = np.linalg.solve

    def counted(A, b):
        done.append(1)
        return solve(A, b)

    monkeypatch.setattr(cont.np.linalg, "solve", counted)
    return done


@pytest.mark.parametrize("ds", [0.02, 0.1, 0.3])
def test_corrector_stops_when_quadratic_convergence_makes_the_next_update_negligible(ds, solves, monkeypatch):
    """The corrector's result lies within the tolerance of the point on the branch it converges to (reached with
    the tolerance 1e-15), with the residual below the tolerance, after one Newton solve fewer than the plain
    test (update below the tolerance) needs, and it reports the plain test's count to the step control."""
    problem, tol = _Circle(), 1e-10
    u0, p0 = np.array([0.6, np.sin(0.6) * 0.5]), 0.5
    for _ in range(50):  # a point on the branch: p fixed, Newton in u
        Ju, _ = problem.jacobian(u0, p0)
        u0 = u0 - np.linalg.solve(Ju, problem.residual(u0, p0))
    Ju, Jp = problem.jacobian(u0, p0)
    tau = np.linalg.solve(np.vstack([np.c_[Ju, Jp], [0.0, 0.0, 1.0]]), [0.0, 0.0, 1.0])
    tau /= np.linalg.norm(tau)
    W = np.ones(3)
    solves.clear()
    u, p, rn, it, ok = cont.correct(problem, u0, p0, tau, ds, W, tol, 40)
    quick = len(solves)
    monkeypatch.setattr(corrector, "QUADRATIC", 0.0)  # the plain test only
    u_ref, p_ref, _, _, ok_ref = cont.correct(problem, u0, p0, tau, ds, W, 1e-15, 40)
    solves.clear()
    _, _, _, it_plain, _ = cont.correct(problem, u0, p0, tau, ds, W, tol, 40)
    plain = len(solves)
    assert ok and ok_ref and rn < tol
    assert np.max(np.abs(np.r_[u - u_ref, p - p_ref])) < tol
    assert quick == plain - 1 and it == it_plain == plain


def test_newton_at_a_fixed_parameter_has_the_same_quadratic_exit(solves, monkeypatch):
    problem, tol, p = _Circle(), 1e-10, 0.5
    start = np.array([0.75, 0.2])
    u, _, rn, it, ok = cont.correct_at(problem, start, p, tol, 20)
    quick = len(solves)
    u_ref, _, _, _, _ = cont.correct_at(problem, start, p, 1e-15, 20)
    monkeypatch.setattr(corrector, "QUADRATIC", 0.0)
    solves.clear()
    _, _, _, it_plain, _ = cont.correct_at(problem, start, p, tol, 20)
    assert ok and rn < tol and np.max(np.abs(u - u_ref)) < tol
    assert quick == len(solves) - 1 and it == it_plain


@pytest.mark.parametrize("seed", range(5))
def test_branch_point_test_from_the_tangents_factors_is_the_bordered_determinant_test(seed):
    """The branch-point test of an accepted point, made from the LU of the tangent's bordered matrix (last row
    W tau0) by a rank-one update, is :func:`signed_smallness` of [[Ju, Jp], [tau]] factored on its own: same sign,
    same value to round-off."""
    rng = np.random.default_rng(seed)
    m = 12
    Ju, Jp = rng.standard_normal((m, m)), rng.standard_normal(m)

    class Linear:
        def jacobian(self, u, p):
            return Ju, Jp

    W = rng.uniform(0.5, 2.0, m + 1) / (m + 1)
    tau0 = rng.standard_normal(m + 1)
    tau, _, _, bp = corrector.tangent(Linear(), None, 0.0, tau0, W)
    direct = cont.signed_smallness(corrector.bordered(Ju, Jp, tau))
    assert np.sign(bp) == np.sign(direct) and bp == pytest.approx(direct, rel=1e-9)
    # the tangent itself: in the kernel of [Ju, Jp], unit in the W-norm, oriented like tau0
    assert np.max(np.abs(np.c_[Ju, Jp] @ tau)) < 1e-12 and np.sum(W * tau * tau) == pytest.approx(1.0)
    assert np.sum(W * tau * tau0) > 0


def test_step_control_grows_on_nearly_straight_branches_and_rejects_slow_steps(monkeypatch):
    """The step grows after three Newton solves, after four only where the tangent turned by less than a sixth of
    the largest accepted turn, is kept after five, halved after six; a step that took seven is rejected (it may
    have landed on a neighbouring branch: the SET b34 at rest did, tests/rod/test_equilibria.py), and its retry at
    half the length is accepted however many it takes (next to a branch point every step may be slow)."""
    opts = cont.ContinuationOptions(ds=0.1, ds_max=0.5, max_angle=0.3)
    grown, kept, halved = 0.15, 0.1, 0.05
    assert cont.next_step(0.1, 3, 0.29, opts) == pytest.approx(grown)
    assert cont.next_step(0.1, 4, 0.049, opts) == pytest.approx(grown)
    assert cont.next_step(0.1, 4, 0.051, opts) == kept
    assert cont.next_step(0.1, 5, 0.0, opts) == kept
    assert cont.next_step(0.1, 6, 0.0, opts) == pytest.approx(halved)
    assert cont.next_step(0.4, 3, 0.0, opts) == 0.5  # at most ds_max

    problem = _Circle()
    u0, p0 = np.array([0.6, np.sin(0.6) * 0.5]), 0.5
    for _ in range(50):
        Ju, _ = problem.jacobian(u0, p0)
        u0 = u0 - np.linalg.solve(Ju, problem.residual(u0, p0))
    W = cont.weights(2, opts)
    a = corrector.make_point(problem, u0, p0, np.array([1.0, 0.0, 0.0]), W, 0.0, 0.0, 0, opts)
    correct = cont.correct
    for solves, retry, accepted in ((6, False, True), (7, False, False), (8, True, True)):
        def slow(*args, _n=solves, **kw):
            u, p, rn, _, ok = correct(*args, **kw)
            return u, p, rn, _n, ok

        monkeypatch.setattr(cont, "correct", slow)
        b, it, _ = cont.advance(problem, a, 0.05, W, opts, slow_ok=retry)
        assert it == solves and (b is not None) is accepted


@pytest.mark.parametrize("offset", [1e-6, -1e-6])
def test_branch_point_next_to_a_fold_is_bracketed_from_the_fold(offset, monkeypatch):
    """A branch-point test that changes sign 1e-6 from a located fold (beyond the fold's final bracket) is bracketed
    by points stepped out from the fold: the same point as from the whole step's bracket, in fewer trials."""
    with monkeypatch.context() as m:
        near, near_trials = _run(offset, True, m)
    with monkeypatch.context() as m:
        m.setattr(sp, "beside_fold", lambda problem, a, b, folds, W, opts: (a, b))
        whole, whole_trials = _run(offset, True, m)
    (bp,) = [q for q in near.special if q.kind == "bp"]
    (ref,) = [q for q in whole.special if q.kind == "bp"]
    assert bp.converged and ref.converged
    assert bp.p == pytest.approx(ref.p, abs=1e-13) and bp.p == pytest.approx(offset**2, abs=2e-12)  # p = u_1^2
    assert near_trials < whole_trials
