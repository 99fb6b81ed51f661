"""What the models assume and how far they are validated: the text of the report's validity list."""

from __future__ import annotations

from etcheck.checks.attachment import alternative_ends
from etcheck.checks.plan import EXACT, PROFILES, Plan
from etcheck.checks.sections import PostbucklingSection
from etcheck.input.mission import Mission
from etcheck.rod.core.ends import describe, is_welded
from etcheck.scaling import Scaled


def _after_buckling(post: PostbucklingSection | None, ends) -> str:
    if not is_welded(ends):
        return ("Linear stability of the straight tether: margins say where it first buckles or whirls. The buckled "
                "tether (rungs 2-3) is computed for welded ends only and is not analysed for these ends.")
    if post and post.get("computed"):
        return ("Past (or near) the first critical load the first post-buckling branch b1 is followed as nonlinear "
                "whirling equilibria (rung 2, Chebyshev collocation, Newton with the exact Jacobian, pseudo-arclength "
                "continuation) and each state's stability from its linearisation (rung 3); other branches (b2, b12, "
                "...) are in `etcheck diagram`. Every measure is checked at a second resolution.")
    return ("Linear stability of the straight tether: margins say where it first buckles or whirls; when the operating "
            "point is within the required margin of that load, the buckled tether is analysed too (rungs 2-3).")


def _model(ends) -> str:
    held = "welded (clamped) at both ends" if is_welded(ends) else describe(ends)
    return (f"Model: inextensible, unshearable, intrinsically straight Kirchhoff rod, {held}, "
            "uniform field along the undeformed axis (Valverde & van der Heijden, arXiv:0810.3668).")


def _attachment(ends) -> str:
    """What the attachment means for the answers, and the other attachment beside each margin."""
    if is_welded(ends):
        held = ("Welded ends, as in the paper: the end bodies hold the tether's position, direction and twist. A "
                "tether on a gimbal, a hinge or an exit guide passes no bending moment (pinned) and buckles much "
                "sooner; each margin is shown beside the same margin with both ends pinned.")
    else:
        held = ("The paper welds both ends; a pinned end holds the position but passes no bending moment "
                "(u = u'' = v = v'' = 0 on the straight tether; docs/model.md), which lowers the critical loads; "
                "torsion decouples from bending on the straight tether, so the twist condition (gimbal or swivel) "
                f"changes only the torsional frequencies. Each margin is shown beside the same margin {_others(ends)}; "
                "the buckled tether (rungs 2-3) is computed for welded ends only and is not computed here.")
    return held + (" The alternatives are computed on the same rung with the critical values only (no spectrum).")


def _others(ends) -> str:
    alts = alternative_ends(ends)
    if len(alts) == 2:
        return "with both ends welded and with both pinned, which bound it"
    return f"with both ends {alts[0][0]}"


def validity(mission: Mission, scaled: Scaled, chosen: Plan, post: PostbucklingSection | None = None) -> list[str]:
    p = scaled.params
    items = [
        _model(p.ends),
        _after_buckling(post, p.ends),
        _attachment(p.ends),
        "The load is the worst case |I| x |B0| over the given ranges; field components across the tether "
        "(which drive the intended drag) are not part of this check.",
    ]
    if chosen.rung == 0:
        items.append(
            ("Rung 0 roots of chi(beta) are located" if is_welded(p.ends) else
             "Rung 0 roots of the closed-form characteristic function of these ends are located")
            + " to ~1e-15 relative (a-posteriori Newton step); "
            "the static loads do not depend on P, damping or mass per length."
        )
    if chosen.route == PROFILES:
        items += _profiles_items(p, scaled)
    elif chosen.rung == 1 and chosen.route == EXACT:
        items += [
            "The straight tether's linear problem (Sec. V B) has constant coefficients: its characteristic "
            "determinant, with each growing or decaying exponential scaled at the end where it is small, is exact "
            "at any tension and stiffness ratio. Critical values are its first roots (bracketed, then Brent's "
            "method); each error estimate is the root's distance to that of a second, independent formulation.",
            "With damping the straight tether loses stability only where its static operator is singular "
            "(Kelvin-Tait-Chetaev), so those roots are the whole stability boundary; the map's stable rows run from "
            "zero load to the first root at each spin. Frequencies (Campbell diagram, operating eigenvalues) are not "
            "computed on this route." if p.gamma > 0 else
            "Without damping the determinant is a real function of mu = -lambda^2 whose real roots are the "
            "vibration frequencies (for an isotropic tether, R = 1, one complex scalar problem per direction of "
            "whirl): divergence and flutter points, and the edges of stable spin windows, are located as its "
            "roots and folds, not sampled. No map, Campbell diagram or operating eigenvalues on this route.",
        ]
    elif chosen.rung == 1:
        items += [
            "Rung 1 linearises the full O(delta) equations (Sec. V B) about the straight tether and solves the "
            "damped gyroscopic eigenproblem by Chebyshev collocation; every eigenvalue and critical value is "
            "computed at two resolutions and their agreement is its error estimate (table below).",
            "Stability is judged on the lowest 12 eigenvalue pairs (Re lambda > 1e-9 counts as growing); higher "
            "modes are stiffened by bending. With damping, the straight tether can only lose stability where "
            "its static operator is singular (divergence, Kelvin-Tait-Chetaev); without damping, gyroscopic "
            "windows above the critical spin may appear and are lost with any damping.",
            "The stability map is exact with damping (each spin row cut at its static points) and sampled on a "
            "grid without (boundaries interpolated between grid points); the margins and critical values in the "
            "tables are located to 1e-10.",
        ]
        if p.gamma > 0:
            items.append(
                f"Eigenvalues left of -1/gamma = {-1 / p.gamma:.4g} on the real axis (the Kelvin-Voigt "
                "accumulation of heavily damped high modes) are not listed: they decay faster than the material "
                "relaxation rate."
            )
    gg = mission.gravity_gradient
    if gg is not None:
        items.append(
            f"Tension from the gravity gradient (tether.end_masses, {gg.rate_source}): the tension varies along "
            f"the tether from {gg.minimum:.4g} N at the {gg.minimum_at} to {gg.maximum:.4g} N at the centre of mass, "
            "and the check uses that profile (rung 1v); the smallest tension held constant along the tether is "
            "reported beside it as a bound (tension stabilises). The axial pull of the gradient is taken along the "
            "undeformed tether; the lateral forces of the orbital frame on a displaced element (Hill's equations) "
            "are left out. Tether on the local vertical of a circular orbit, no libration (at the extremes of a "
            "libration swing the tension is lower, by about cos² of the angle)."
        )
    if p.P > 1e-2:
        items.append(f"P = {p.P:.3g} is large for a slender rod; rod theory assumes P << 1.")
    return items


def _profiles_items(p, scaled: Scaled) -> list[str]:
    """What rung 1v assumes and how it is checked."""
    t = scaled.tether
    items = [
        "Rung 1v linearises about the straight tether with its current and tension along it (docs/model.md "
        "section 9): Chebyshev collocation on subdomains graded towards the welded ends (down to the boundary layers "
        "of the weak axis), stability read from the eigenvalues (Re lambda > 1e-8 |lambda| counts as growing). Every "
        "critical value is located on two meshes; their distance (with the round-off of a slow crossing) is its "
        "error. An independent finite-element discretisation agrees with it in the tests.",
    ]
    if t is not None and t.circulatory:
        items.append(
            "With a current that varies along the tether the magnetic load has no potential (it is circulatory): the "
            "tether can lose stability by flutter, two vibration modes merging into one that grows, and damping can "
            "lower the threshold (Ziegler's paradox), so the threshold is computed undamped and over the damping the "
            "mission allows. A round wire (R = 1) flutters at any load without damping.")
    return items
