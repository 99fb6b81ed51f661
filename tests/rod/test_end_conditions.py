"""Pinned and swivel ends (etcheck/rod/core/ends.py) through rungs 0 and 1, against independent routes.

Rung 0's closed forms against a high-precision shooting (mpmath's matrix exponential of the complex
first-order system, roots by the secant method in the complex plane); the collocation spectrum and its
static pencils against the exact determinant, with spin, tension and damping; an independent BVP solver
(scipy's solve_bvp) on a tensioned scene; the string limit under strong tension; the unperturbed
frequencies; the end swap. The values the issue quotes (R = 21/38, no tension: pinned-pinned 0.36 of the
welded load, one of each 0.63) are checked to the digits quoted and to all digits against the shooting.
"""

from __future__ import annotations

import json
import math
import pickle
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import ClassVar

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import solve_bvp

from etcheck.rod.core import ends as ends_module
from etcheck.rod.core import linear
from etcheck.rod.core.ends import ALL_PINNED, ALL_WELDED, Ends
from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.rod.core.spectrum import spectrum
from etcheck.rod.straight import analytic
from etcheck.rod.straight.collocation.damped_critical import damped_critical
from etcheck.rod.straight.collocation.spectral import static_points
from etcheck.rod.straight.exact import determinant as det
from etcheck.rod.straight.exact.roots import exact_critical, exact_root, string_limit_load
from etcheck.rod.straight.exact.undamped import undamped_critical

MIXED = Ends(("welded", "pinned"))
SWAPPED = Ends(("pinned", "welded"))
R_SET = 21 / 38


def shooting_beta(ends, guess: float) -> mp.mpf:
    """The buckling beta of w'''' + i beta^3 w' = 0 with the ends' conditions, by shooting: the 4 x 4
    fundamental matrix expm(A) at 40 digits, the 2 x 2 determinant of the conditions at s = 1 on the
    solutions that meet those at s = 0, its root by the secant method in complex beta (it must come out real)."""
    mp.mp.dps = 40
    rows = {"welded": (0, 1), "pinned": (0, 2), "swivel": (0, 2)}

    def d(beta):
        A = mp.matrix(4, 4)
        A[0, 1] = A[1, 2] = A[2, 3] = 1
        A[3, 1] = -1j * beta**3
        Phi = mp.expm(A)
        free = [i for i in range(4) if i not in rows[ends[0]]]
        held = rows[ends[1]]
        return mp.det(mp.matrix([[Phi[r, c] for c in free] for r in held]))

    root = mp.findroot(d, mp.mpf(guess))
    assert abs(mp.im(root)) < mp.mpf(10) ** -25
    return mp.re(root)


@pytest.mark.parametrize("ends", [ALL_PINNED, MIXED, SWAPPED, ("swivel", "pinned")])
def test_closed_form_static_roots_against_shooting(ends):
    roots = analytic.static_roots(ends, 3)
    for r in roots:
        ref = shooting_beta(ends, r.beta * 1.01)
        assert r.beta == pytest.approx(float(ref), rel=2e-15)
        assert r.kernel_dimension == 2  # w and i w: a double pitchfork, as with welded ends
        assert r.curvature > 0 and r.residual < 1e-28


def test_issue_ratios_and_the_mixed_roots_are_two_pi_k():
    welded = analytic.critical_loads(R_SET, F_CLAMPED, 3)
    pinned = analytic.critical_loads(R_SET, F_CLAMPED, 3, ALL_PINNED)
    mixed = analytic.critical_loads(R_SET, F_CLAMPED, 3, MIXED)
    assert round(pinned[0] / welded[0], 2) == 0.36 and round(mixed[0] / welded[0], 2) == 0.63
    assert pinned[0] / welded[0] == pytest.approx(0.3619152543, rel=1e-9)
    assert [r.beta for r in analytic.static_roots(MIXED, 3)] == pytest.approx([2 * math.pi * k for k in (1, 2, 3)],
                                                                              rel=1e-15)
    # the welded branch is eq. (91) itself: chi e^{-sqrt3 beta} = 2 (reduced g)^2
    b = np.linspace(0.3, 40.0, 57)
    assert analytic.chi_scaled(b) == pytest.approx(2 * analytic.reduced_characteristic(b, ALL_WELDED) ** 2,
                                                   rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("R", [R_SET, 0.07, 1.0])
@pytest.mark.parametrize("ends", [ALL_PINNED, MIXED, ("pinned", "swivel")])
def test_collocation_static_loads_match_the_closed_form(ends, R):
    p = RodParameters(P=1e-3, R=R, Gamma=0.77, ends=ends)
    values, errors = static_points(p, "B", hi=3 * analytic.critical_loads(R, p.f, 2, ends)[1], N=32)
    closed = analytic.critical_loads(R, p.f, 2, ends)
    assert values[0] == pytest.approx(closed[0], rel=1e-10)
    assert values[1] == pytest.approx(closed[0], rel=1e-6)  # double
    assert np.any(np.isclose(values, closed[1], rtol=1e-9))


SCENES = [
    dict(P=1e-3, R=0.3, Gamma=0.7, T=3.0, omega=0.4, gamma=0.01),
    dict(P=5e-4, R=0.8, Gamma=1.1, T=0.5, omega=0.9, gamma=0.05),
    dict(P=2e-3, R=R_SET, Gamma=0.77, T=-0.005, omega=0.2, gamma=0.02),
]


@pytest.mark.parametrize("scene", SCENES, ids=["taut-spun", "near-round-fast", "compressed"])
@pytest.mark.parametrize("ends", [ALL_PINNED, MIXED])
def test_exact_determinant_and_static_pencils_agree(ends, scene):
    """Two discretisations of rung 1 for a damped tether: the exact characteristic determinant (the ends'
    rows of the scaled state) and the static pencils of the Chebyshev collocation (the ends' moment rows)."""
    p = RodParameters(**scene, ends=ends)
    a, b = exact_critical(p, tol=1e-9), damped_critical(p, tol=1e-9)
    assert a.converged and b.converged
    for x, y in ((a.critical_load, b.critical_load), (a.critical_spin, b.critical_spin),
                 (a.spin_at_rest, b.spin_at_rest)):
        assert x.value == pytest.approx(y.value, rel=1e-8, abs=1e-12)
    welded = exact_critical(p.with_(ends=ALL_WELDED), tol=1e-9)
    assert a.critical_load.value < welded.critical_load.value  # a pin holds the tether less than a weld


@pytest.mark.parametrize("ends", [ALL_WELDED, ALL_PINNED, MIXED])
def test_compressive_limit_is_the_euler_load_of_the_weak_axis(ends):
    p = RodParameters(P=1e-3, R=R_SET, Gamma=0.77, ends=ends)
    limit = exact_root(p, "T", sign=-1.0).value
    assert limit == pytest.approx(-ends.euler_load * p.R / p.f, rel=1e-11)


def test_end_swap_gives_the_same_answers():
    """s -> 1 - s with v -> -v maps the straight problem with (welded, pinned) onto (pinned, welded)."""
    p = RodParameters(**SCENES[0], ends=MIXED)
    q = p.with_(ends=SWAPPED)
    assert exact_root(p, "B").value == pytest.approx(exact_root(q, "B").value, rel=1e-13)
    assert damped_critical(p).critical_spin.value == pytest.approx(damped_critical(q).critical_spin.value, rel=1e-9)


def test_independent_bvp_solver_on_a_tensioned_pinned_tether():
    """scipy's solve_bvp (4th-order collocation, adaptive mesh) with B as the unknown, u'(0) = 1 fixing the
    mode: the first two loads of a tensioned, anisotropic tether with both ends pinned (simple roots 4 % apart,
    the pair that tension splits), each from a guess 1 % off, against the exact determinant's roots."""
    p = RodParameters(P=0.0, R=0.3, Gamma=0.7, T=0.2, ends=ALL_PINNED)
    first = exact_root(p, "B").value
    values, _ = static_points(p, "B", hi=3 * first, N=48)
    second = values[1]
    assert values[0] == pytest.approx(first, rel=1e-10) and second > 1.03 * first
    R, f, T = p.R, p.f, p.T

    def rhs(s, y, q):
        B = q[0]
        u, v = y[:4], y[4:]
        du = np.vstack([u[1], u[2], u[3], f / R * (T * u[2] + B * v[1])])
        dv = np.vstack([v[1], v[2], v[3], f * (T * v[2] - B * u[1])])
        return np.vstack([du, dv])

    def bc(ya, yb, q):
        return np.array([ya[0], ya[2], ya[4], ya[6], yb[0], yb[2], yb[4], yb[6], ya[1] - 1.0])

    s = np.linspace(0.0, 1.0, 201)
    k = 2 * math.pi  # the string's helix u + i v ~ (sin ks + i (1 - cos ks)) / k, and a half sine in u alone
    helix = np.array([np.sin(k * s) / k, np.cos(k * s), -k * np.sin(k * s), -k**2 * np.cos(k * s),
                      (1 - np.cos(k * s)) / k, np.sin(k * s), k * np.cos(k * s), -k**2 * np.sin(k * s)])
    k = math.pi
    sine = np.array([np.sin(k * s) / k, np.cos(k * s), -k * np.sin(k * s), -k**2 * np.cos(k * s),
                     *np.zeros((4, s.size))])
    for ref, y, guess in ((first, helix, 0.97 * first), (second, sine, 1.01 * second)):
        sol = solve_bvp(rhs, bc, s, y, p=[guess], tol=1e-6, max_nodes=20000)
        assert sol.success
        assert sol.p[0] == pytest.approx(ref, rel=1e-6)


@pytest.mark.parametrize("ends", [ALL_WELDED, ALL_PINNED, MIXED])
def test_string_limit_under_strong_tension(ends):
    """Welded and pinned converge to B = 2 pi T; the order-2 formula of each is good to O((f T)^-3/2)."""
    errs = []
    for T in (1e2, 1e3, 1e4):
        p = RodParameters(P=1e-4, R=0.5, Gamma=0.7, T=T, omega=0.3, ends=ends)
        root = exact_root(p, "B").value
        assert abs(root / (2 * math.pi * T) - 1) < 3.0 / math.sqrt(p.f * T)
        errs.append(abs(string_limit_load(p, 2) - root) / root)
    assert errs[2] < 3e-8
    assert 10**1.5 / 2 < errs[1] / errs[2] < 10**1.5 * 2  # the error falls like (f T)^-3/2
    if ends == ALL_PINNED:  # no first-order layer term: a pinned end meets the string's w = 0 at every order
        assert string_limit_load(p, 1) == string_limit_load(p, 0)


def test_welded_and_pinned_loads_meet_under_tension():
    gaps = []
    for T in (1e1, 1e3, 1e5):
        w, pn = (exact_root(RodParameters(P=1e-4, R=0.5, Gamma=0.7, T=T, ends=e), "B").value
                 for e in (ALL_WELDED, ALL_PINNED))
        gaps.append((w - pn) / pn)
    assert gaps[0] > gaps[1] > gaps[2] > 0 and gaps[2] < 2e-3


@pytest.mark.parametrize("ends", [ALL_PINNED, MIXED, ("swivel", "welded")])
def test_unperturbed_frequencies_against_the_collocation_spectrum(ends):
    P, R, G = 1e-3, 0.55, 0.77
    p = RodParameters(P=P, R=R, Gamma=G, ends=ends)
    mus = np.sort(np.concatenate([analytic.bending_frequencies(P, R, p.f, 4, "weak", ends),
                                  analytic.bending_frequencies(P, R, p.f, 4, "stiff", ends),
                                  analytic.torsion_frequencies(P, G, p.f, 4, ends)]))
    got = np.sort(np.abs(spectrum(p, k=8).eigenvalues.imag))
    assert got[:6] == pytest.approx(mus[:6], rel=1e-9)


def test_determinant_is_real_for_every_attachment():
    for ends in (ALL_PINNED, MIXED, SWAPPED):
        for B in (3.0, 17.0, 40.0):
            p = RodParameters(P=1e-3, R=0.3, Gamma=0.7, B=B, T=3.0, omega=0.4, ends=ends)
            a, b = det.evaluate(p), det.evaluate(p, "schur")
            assert a.imaginary < 1e-13 and b.imaginary < 1e-13
            assert a.value == pytest.approx(b.value, rel=1e-10)  # two routes, the same rows


def test_undamped_pinned_tether_against_the_pencil():
    """The exact undamped route: its divergence load at the operating spin is the static pencil's first root."""
    p = RodParameters(P=1e-3, R=R_SET, Gamma=1 / 1.3, omega=0.25, B=0.1, ends=MIXED)
    u = undamped_critical(p, tol=1e-10, windows=False)
    values, _ = static_points(p, "B", hi=1.0, N=32)
    assert u.critical_load.value == pytest.approx(values[0], rel=1e-10)
    op = spectrum(p, k=8)
    assert u.stable == op.stable


def test_bounds_of_the_ends():
    assert ALL_WELDED.first_bending_root ** 4 == pytest.approx(F_CLAMPED, rel=1e-15)
    assert math.tan(MIXED.first_bending_root) == pytest.approx(math.tanh(MIXED.first_bending_root), rel=1e-13)
    k = math.sqrt(MIXED.euler_load)
    assert math.tan(k) == pytest.approx(k, rel=1e-12)
    with pytest.raises(ValueError, match="swivel at both ends"):
        Ends(("swivel", "swivel"))
    with pytest.raises(ValueError, match="ends must be"):
        RodParameters(P=0.0, R=1.0, Gamma=1.0, ends=("welded", "glued"))
    assert RodParameters(P=0.0, R=1.0, Gamma=1.0, ends=["pinned", "welded"]).ends == SWAPPED  # hashable pair


# --- the kinds and the pair as objects (etcheck/rod/core/ends.py) ----------------------------------------------


def test_registry_names_and_what_each_kind_holds():
    assert ends_module.KINDS == ("welded", "pinned", "swivel")
    kinds = {name: ends_module.REGISTRY[name] for name in ends_module.KINDS}
    assert all(k.name == name for name, k in kinds.items())
    assert [k.holds_slope for k in kinds.values()] == [True, False, False]
    assert [k.holds_twist for k in kinds.values()] == [True, True, False]
    assert [k.bending for k in kinds.values()] == [ends_module.CLAMPED, ends_module.HINGED, ends_module.HINGED]
    assert [k.free_moments for k in kinds.values()] == [(), (0, 1), (0, 1, 2)]
    e = Ends.of(["swivel", "welded"])
    assert (e.lower, e.upper) == (kinds["swivel"], kinds["welded"]) and Ends.of(e) is e
    with pytest.raises(ValueError, match="registered already"):
        ends_module.register(ends_module.Pinned)


def test_the_results_schema_names_the_kinds():
    """Every enum of end names in docs/results.schema.json is the registry's (a new kind adds its name there)."""
    schema = json.loads((Path(__file__).resolve().parents[2] / "docs" / "results.schema.json").read_text())

    def enums(node):
        if isinstance(node, dict):
            if "swivel" in node.get("enum", ()):
                yield node["enum"]
            for value in node.values():
                yield from enums(value)
        elif isinstance(node, list):
            for value in node:
                yield from enums(value)

    found = list(enums(schema))
    assert found and all(e == list(ends_module.KINDS) for e in found)


def test_the_pair_is_its_names_in_results_and_caches():
    """Ends is the tuple of names: JSON, asdict, repr (the sweep cache's key), pickling and hashing are the names'."""
    p = RodParameters(P=1e-3, R=0.5, Gamma=0.7, ends=("welded", "swivel"))
    assert json.dumps(asdict(p)["ends"]) == '["welded", "swivel"]' and repr(p.ends) == "('welded', 'swivel')"
    assert RodParameters(**asdict(p)) == p and pickle.loads(pickle.dumps(p)).ends.upper.name == "swivel"
    assert hash(p.ends) == hash(("welded", "swivel")) and isinstance(p.ends, Ends)


@pytest.mark.parametrize("names, said", [
    (("welded", "welded"), "welded at both ends"),
    (("pinned", "pinned"), "pinned at both ends (no bending moment, twist held)"),
    (("welded", "pinned"), "lower end welded, upper end pinned (no bending moment, twist held)"),
    (("pinned", "swivel"), "lower end pinned, upper end on a swivel (pinned: no bending moment, twist held; "
                           "on a swivel: no moment, free to twist)"),
])
def test_describe(names, said):
    assert Ends(names).describe() == said == ends_module.describe(list(names))


@pytest.mark.parametrize("names, root, equation", [
    (("welded", "welded"), 4.730040744862704, lambda b: mp.cos(b) * mp.cosh(b) - 1),
    (("welded", "pinned"), 3.926602312047919, lambda b: mp.tan(b) - mp.tanh(b)),
    (("swivel", "welded"), 3.926602312047919, lambda b: mp.tan(b) - mp.tanh(b)),
    (("pinned", "swivel"), math.pi, mp.sin),
])
def test_beam_roots_against_their_equations(names, root, equation):
    ends = Ends(names)
    assert ends.first_bending_root == root and ends.beam is Ends(names[::-1]).beam  # either way round
    with mp.workdps(30):
        assert float(mp.findroot(equation, root)) == pytest.approx(root, rel=1e-15)


def _slope_quotient(beta: float, clamped: int) -> float:
    """int phi'^2 / int phi^2 of the first beam mode (clamped at s = 0 unless ``clamped`` is 0) by quadrature."""
    b = mp.mpf(beta)
    if clamped:
        sigma = (mp.cosh(b) - mp.cos(b)) / (mp.sinh(b) - mp.sin(b))
        phi = lambda s: mp.cosh(b * s) - mp.cos(b * s) - sigma * (mp.sinh(b * s) - mp.sin(b * s))  # noqa: E731
    else:
        phi = lambda s: mp.sin(b * s)  # noqa: E731
    with mp.workdps(20):
        return float(mp.quad(lambda s: mp.diff(phi, s) ** 2, [0, 1]) / mp.quad(lambda s: phi(s) ** 2, [0, 1]))


@pytest.mark.parametrize("names, euler, clamped", [
    (("welded", "welded"), 4 * math.pi**2, 2), (("welded", "pinned"), 20.190728556426630, 1),
    (("pinned", "pinned"), math.pi**2, 0)])
def test_euler_loads_and_slope_quotients(names, euler, clamped):
    """The Euler loads of a column, T L^2 / EI (f = 1; the check divides by f as the exact route's limit above
    shows): 4 pi^2, 20.19 (tan k = k), pi^2; and int phi'^2 / int phi^2 of the first beam mode to 4 digits."""
    ends = Ends(names)
    assert ends.euler_load == pytest.approx(euler, rel=1e-15)
    if clamped == 1:
        with mp.workdps(30):
            k = float(mp.findroot(lambda x: mp.tan(x) - x, 4.49))
        assert ends.euler_load == pytest.approx(k * k, rel=1e-15)
    assert ends.beam.slope_quotient == pytest.approx(_slope_quotient(ends.first_bending_root, clamped), rel=5e-4)


@pytest.mark.parametrize("kind", ["welded", "pinned", "swivel"])
def test_determinant_rows_are_the_scaled_state_at_the_rows_held(kind):
    """Each kind's held values of a basis solution (u, v) e^{k s} are its rows of that solution's scaled state
    (u, u'/ku, u''/ku^2, u'''/ku^3, v, ..), and the same for the complex state (w, w'/kap, ..)."""
    end = ends_module.REGISTRY[kind]
    rng = np.random.default_rng(3)
    u, v, k = (rng.normal(size=(2, 5)) + 1j * rng.normal(size=(2, 5)) for _ in range(3))
    ku, kv = np.array([1.5, 3.0]), np.array([2.0, 0.7])
    state = np.stack([u * (k / ku[:, None]) ** j for j in range(4)] + [v * (k / kv[:, None]) ** j for j in range(4)],
                     axis=1)
    assert end.real_values(u, v, k, ku, kv) == pytest.approx(state[:, end.real_rows()], rel=1e-14)
    ms = k / ku[:, None]
    assert end.complex_values(ms) == pytest.approx(np.stack([ms**j for j in range(4)], axis=1)[:, end.complex_rows()],
                                                   rel=1e-14)
    assert list(end.real_rows()) == [0, end.bending_order, 4, 4 + end.bending_order]


def _rotation(seed: int) -> np.ndarray:
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    return q * np.sign(np.diag(r)) * np.linalg.det(q * np.sign(np.diag(r)))


@pytest.mark.parametrize("names", [("welded", "pinned"), ("swivel", "welded"), ("pinned", "swivel")])
def test_collocation_rows_are_the_linearised_conditions(names):
    """The boundary rows on a turned frame D and a base moment M0 at each end, applied to any (a, m) at the end
    nodes: welded (a x d3) . e1, (a x d3) . e2, (a x d1) . e2 (eqs. (76)-(81)); pinned (m + M0 x a) . d1,
    (m + M0 x a) . d2 and the twist; swivel (m + M0 x a) . d_j for j = 1, 2, 3."""
    N = 4
    D = np.stack([_rotation(1), _rotation(2)])
    M = np.array([[0.3, -1.1, 0.7], [2.0, 0.4, -0.5]])
    rows = linear.end_rows(D, N, Ends(names), M).reshape(12, linear.NFIELDS, N + 1)
    rng = np.random.default_rng(5)
    Y = rng.normal(size=(linear.NFIELDS, N + 1))
    e1, e2 = np.eye(3)[0], np.eye(3)[1]
    for end, (first, node) in enumerate(((3, 0), (9, N))):
        a, m, d = Y[3:6, node], Y[9:12, node], D[end]
        moment = m + np.cross(M[end], a)
        held = {"welded": [np.cross(a, d[:, 2]) @ e1, np.cross(a, d[:, 2]) @ e2, np.cross(a, d[:, 0]) @ e2],
                "pinned": [moment @ d[:, 0], moment @ d[:, 1], np.cross(a, d[:, 0]) @ e2],
                "swivel": [moment @ d[:, 0], moment @ d[:, 1], moment @ d[:, 2]]}[names[end]]
        got = [np.sum(rows[first + j] * Y) for j in range(3)]
        assert got == pytest.approx(held, rel=1e-13, abs=1e-13)


# --- a new kind is one class ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Bearing(ends_module.Welded):
    """A toy kind: the slope held, free to twist (a clamp on a bearing)."""

    name: ClassVar[str] = "bearing"
    words: ClassVar[str] = "in a bearing"
    meaning: ClassVar[str] = "slope held, free to twist"
    holds_twist: ClassVar[bool] = False


@dataclass(frozen=True)
class Sleeve(ends_module.EndCondition):
    """A toy kind that bends in a way no pair table knows."""

    name: ClassVar[str] = "sleeve"
    words: ClassVar[str] = "in a sleeve"
    meaning: ClassVar[str] = "a new bending behaviour"
    bending: ClassVar[str] = "sleeve"
    bending_order: ClassVar[int] = 1
    holds_twist: ClassVar[bool] = True


@pytest.fixture
def toy_kinds(monkeypatch):
    monkeypatch.setattr(ends_module, "REGISTRY", dict(ends_module.REGISTRY))
    ends_module.register(Bearing)
    ends_module.register(Sleeve)


def test_a_new_kind_that_bends_as_a_weld_is_one_class(toy_kinds):
    """The toy bearing reaches every rung-0/1 route through the registry alone: the pair tables by its bending,
    its collocation rows (no moment about d3: the torsional frequencies of one free end, (n - 1/2) pi ...), the
    exact determinant (the weld's rows: its loads are the welded tether's)."""
    ends = Ends(("bearing", "welded"))
    assert ends.bending == ("clamped", "clamped") and ends.euler_load == ALL_WELDED.euler_load
    assert ends.describe() == "lower end in a bearing, upper end welded (slope held, free to twist)"
    assert not ends.is_welded and not ends.holds_twist and ends.lower.free_moments == (2,)
    P, R, G = 1e-3, 0.55, 0.77
    p = RodParameters(P=P, R=R, Gamma=G, ends=ends)
    mus = np.sort(np.concatenate([analytic.bending_frequencies(P, R, p.f, 4, axis, ends) for axis in ("weak", "stiff")]
                                 + [analytic.torsion_frequencies(P, G, p.f, 4, ends)]))
    assert analytic.torsion_frequencies(P, G, p.f, 1, ends)[0] == pytest.approx(
        0.5 * analytic.torsion_frequencies(P, G, p.f, 1)[0], rel=1e-15)
    got = np.sort(np.abs(spectrum(p, k=8).eigenvalues.imag))
    assert got[:6] == pytest.approx(mus[:6], rel=1e-9)
    q = RodParameters(**SCENES[0], ends=ends)
    assert exact_root(q, "B").value == pytest.approx(exact_root(q.with_(ends=ALL_WELDED), "B").value, rel=1e-12)
    with pytest.raises(ValueError, match="a bearing and a swivel leaves the tether free to turn"):
        Ends(("bearing", "swivel"))


def test_a_new_bending_behaviour_is_refused_where_no_table_knows_it(toy_kinds):
    ends = Ends(("sleeve", "welded"))
    with pytest.raises(ValueError, match=r"no beam mode for the ends sleeve, welded: .* \('clamped', 'sleeve'\)"):
        _ = ends.euler_load
    with pytest.raises(ValueError, match="no closed-form static buckling"):
        analytic.critical_loads(0.5, F_CLAMPED, 1, ends)
    with pytest.raises(ValueError, match="Sleeve gives no rows for the exact determinant"):
        det.evaluate(RodParameters(P=1e-3, R=0.3, Gamma=0.7, B=3.0, ends=ends))
