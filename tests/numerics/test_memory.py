"""The memory budget: sizes read, routes stop at what fits and say so, memos bounded, stated sizes are upper bounds."""

import math
import tracemalloc

import numpy as np
import pytest

from etcheck.numerics.eigen import QZ_MATRICES, qep_dense
from etcheck.rod.core.base_state import straight
from etcheck.rod.core.linear import linear_operator
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import lowest_eigenvalues, prefers_dense, solve_bytes, spectrum
from etcheck.rod.straight.collocation.damped_critical import first_root
from etcheck.rod.straight.collocation.spectral import StraightFamily, family_bytes
from etcheck.rod.straight.exact.roots import exact_critical, pencil_or_exact
from etcheck.runtime import memory
from etcheck.runtime.memory import BASELINE, Memo, OverBudget, matrix_bytes, parse, require

#: SET at its operating point (Sec. VII B), damped
SET = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, B=0.3, omega=0.25, T=0.0, gamma=0.04375)


@pytest.fixture
def budget(monkeypatch):
    """Set this process's budget for one test (and empty the memos before and after)."""

    def set_to(text: str) -> None:
        memory.release()
        monkeypatch.setenv(memory.VARIABLE, text)

    yield set_to
    memory.release()


@pytest.mark.parametrize(("text", "value"), [("1 GB", 10**9), ("512 MB", 512 * 10**6), ("1.5GiB", 3 * 2**29),
                                              ("2e9", 2 * 10**9), (" 300 mb ", 3 * 10**8)])
def test_sizes_are_read_in_decimal_and_binary_units(text, value):
    assert parse(text) == value


@pytest.mark.parametrize("text", ["lots", "1 GQ", "-1 GB", "", "100 MB"])
def test_a_size_that_cannot_be_a_budget_is_refused_with_the_expected_form(text):
    with pytest.raises(ValueError, match="memory size|below"):
        parse(text)


def test_the_default_budget_is_one_gigabyte(monkeypatch):
    monkeypatch.delenv(memory.VARIABLE, raising=False)
    assert memory.budget() == 10**9


def test_a_route_past_the_budget_is_not_answered_and_says_what_it_would_need(budget):
    budget("300 MB")
    require("a small matrix", 50e6)  # fits beside the baseline
    with pytest.raises(OverBudget) as exc:
        require("the operators at N = 999", 2.3e9)
    text = str(exc.value)
    assert exc.value.exit_code == 1
    assert text.startswith("not answered: the operators at N = 999 would need 2.5 GB of memory")
    assert "past the budget of 300 MB" in text and "--memory-budget" in text


def test_a_memo_keeps_what_the_budget_allows_and_the_latest_always(budget):
    budget("1 GB")
    built = []
    memo = Memo(lambda n: built.append(n) or n, lambda n: n * 1e6)  # entry n states n MB
    for n in (100, 100, 120, 90):
        memo(n)
    assert built == [100, 120, 90] and len(memo) == 2  # 100 + 120 + 90 MB > 25 % of 1 GB: the oldest went
    assert memo.nbytes <= memory.MEMO_SHARE * memory.budget()
    memo(400)  # more than the share alone: kept, as the latest
    assert len(memo) == 1 and memo(400) == 400 and built[-1] == 400
    require("something large", 700e6)  # fits only once the memo is released: it is
    assert len(memo) == 0


def _peak(fn) -> float:
    """Bytes allocated at the peak of fn() above what was held before it (tracemalloc)."""
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        fn()
        return tracemalloc.get_traced_memory()[1] - before
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("N", [16, 32])
def test_a_family_needs_less_than_it_states(N):
    """Built with every block, its reduced forms and its parts, and used by a pencil: within family_bytes(N)."""

    def build():
        fam = StraightFamily(SET, N)
        fam.pencil_roots("B", 0.0, SET.omega, 0.0)
        fam.eigenvalues(SET.B, SET.omega, 0.0, 28)

    peak = _peak(build)
    assert 0.5 * family_bytes(N) < peak <= family_bytes(N)  # an upper bound, and not a loose one


@pytest.mark.parametrize("dense", [True, False])
def test_an_eigenvalue_solve_needs_less_than_it_states(dense):
    N = 24
    p = SET.with_(gamma=0.2) if dense else SET
    assert prefers_dense(p, 28) == dense

    peak = _peak(lambda: lowest_eigenvalues(p, None, N, 28))
    assert peak <= solve_bytes(N, dense)


def test_dense_qz_needs_less_than_it_states():
    A = linear_operator(SET, straight(SET), 16)
    n = A[0].shape[0]
    peak = _peak(lambda: qep_dense(*A))
    assert peak <= matrix_bytes(2 * n, count=QZ_MATRICES) + memory.WORKSPACE


def test_a_pencil_ladder_stops_at_the_finest_rung_within_the_budget(budget):
    p = SET.with_(T=1.0, R=0.1)  # end layers under tension: the ladder climbs to N = 48 to meet 1e-13
    full = first_root(p, "B", tol=1e-13)
    assert full.N == 48 and full.converged
    # room beside the baseline for the families at N = 24 (checked at 36), not at 32 (checked at 48)
    budget(f"{BASELINE + family_bytes(40):.0f}")
    short = first_root(p.with_(P=0.0010001), "B", tol=1e-13)  # (not the memoised root)
    assert short.N == 24 and not short.converged
    assert "N = 24 is the finest resolution within the memory budget" in short.model
    assert math.isclose(short.value, full.value, rel_tol=max(10 * short.error, 1e-6))


def test_damped_critical_values_fall_back_to_the_exact_determinant_when_no_pencil_fits(budget):
    budget(f"{BASELINE + family_bytes(16):.0f}")  # not even the first rung (16 checked at 24)
    p = SET.with_(P=0.00123)  # not memoised by another test
    with pytest.raises(OverBudget):
        first_root(p, "B")
    got = pencil_or_exact(p, tol=1e-10)
    assert got == exact_critical(p, tol=1e-10)
    assert got.converged


def test_a_spectrum_ladder_stops_within_the_budget_and_says_so(budget):
    full = spectrum(SET, k=4, tol=1e-14)
    budget(f"{BASELINE + solve_bytes(24, prefers_dense(SET, 16)):.0f}")
    short = spectrum(SET, k=4, tol=1e-14)
    assert short.N == 24 < full.N
    assert "would need" in short.message and "past the budget" in short.message
    np.testing.assert_allclose(short.eigenvalues[:2], full.eigenvalues[:2], rtol=1e-6)


def test_a_spectrum_whose_first_pair_does_not_fit_is_not_answered(budget):
    budget(f"{BASELINE + 1e6:.0f}")
    with pytest.raises(OverBudget, match=r"the spectrum at N = 24 would need"):
        spectrum(SET, k=4)


def test_the_families_of_a_memo_stay_within_its_share(budget):
    """Many parameter sets at a fine resolution (as an uncertainty study's samples): the memo holds what the
    budget's share allows (it held 32 families whatever their size: 2.5 GB at N = 128)."""
    from etcheck.rod.straight.collocation.spectral import straight_family

    budget("400 MB")
    for i in range(6):
        straight_family(SET.with_(P=0.001 * (1 + i / 10)), 48)
    share = memory.MEMO_SHARE * memory.budget()
    assert memory.held() <= max(share, family_bytes(48, peak=False))


def test_the_exact_determinant_is_evaluated_in_blocks_that_fit_the_budget(budget):
    """The same values (to round-off: numpy's vectorised logarithms and exponentials differ in the last bit with
    the position in a block) in blocks of a tenth of a small budget, and a peak within it (one block of 1e5
    points held 530 MB)."""
    from etcheck.rod.straight.exact.undamped_kernel import characteristic_counted

    p = SET.with_(gamma=0.0)
    mu = np.linspace(0.1, 1e3, 20_000)
    whole, _ = characteristic_counted(p, mu, omega=0.5)
    budget("300 MB")
    assert memory.items_within(6e3, 0.1) < mu.size
    blocks, _ = characteristic_counted(p, mu, omega=0.5)
    np.testing.assert_allclose(blocks, whole, rtol=1e-12, atol=1e-12 * np.max(np.abs(whole)))
    peak = _peak(lambda: characteristic_counted(p, np.linspace(0.1, 1e3, 100_000), omega=0.5))
    assert peak < 60e6
