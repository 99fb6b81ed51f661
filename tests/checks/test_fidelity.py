"""Draft or sign-off (issue 10): a draft answers the same margins, says what it left out, and is marked."""

from __future__ import annotations

from pathlib import Path

import pytest

from etcheck import check, load_mission
from etcheck.checks.fidelity import DRAFT_TOLERANCE, LEFT_OUT
from etcheck.checks.rungs.straight import WhirlOptions
from etcheck.report import render

MISSIONS = Path(__file__).resolve().parents[2] / "missions"
#: a sign-off with the smallest pictures: the margins do not depend on the map or Campbell grids
SMALL = WhirlOptions(map_points=4, row_points=4, campbell_points=4, accuracy_N=())


@pytest.mark.parametrize("name", ["set.toml", "set-static.toml"])
def test_draft_margins_equal_sign_off_within_their_errors(name):
    mission = load_mission(MISSIONS / name)
    sign = check(mission, SMALL).results
    draft = check(mission.with_fidelity("draft")).results
    assert sign["fidelity"] == {"name": "sign-off", "tolerance": mission.check.tolerance, "left_out": []}
    assert draft["fidelity"]["name"] == "draft" and draft["fidelity"]["tolerance"] == DRAFT_TOLERANCE
    assert draft["fidelity"]["left_out"] == list(LEFT_OUT)
    assert draft["verdict"] == sign["verdict"]
    for a, b in zip(draft["margins"], sign["margins"], strict=True):
        assert a["name"] == b["name"] and a["verdict"] == b["verdict"]
        assert a["value"] == pytest.approx(b["value"], rel=DRAFT_TOLERANCE + a["error"] + b["error"])
        assert a["error"] <= DRAFT_TOLERANCE
    if sign["linear"]:  # the trade a damped draft makes: its pencils from N = 12 checked at 20 (sign-off: 16 at
        # 24), with the larger two-resolution error that comes with it, inside the draft's tolerance
        for axis in ("critical_load", "critical_spin"):
            assert draft["linear"][axis]["N"] < sign["linear"][axis]["N"]
            assert sign["linear"][axis]["error"] <= draft["linear"][axis]["error"] <= DRAFT_TOLERANCE


def test_draft_leaves_out_the_pictures_and_says_so():
    draft = check(load_mission(MISSIONS / "set.toml").with_fidelity("draft")).results
    lin = draft["linear"]
    assert lin["campbell"] is None and lin["stability_map"] is None and draft["accuracy"] is None
    assert draft["postbuckling"] is None
    html = render(draft, ("html",))["html"].decode()
    assert "not for signature" in html and "Fidelity: draft" in html
    assert "located to a tolerance of 1×10<sup>-6</sup> (a draft)" in " ".join(html.split())  # not 1e-10


def test_a_draft_report_is_marked_on_its_title_verdict_and_every_page():
    """An engineer who finds a printed page of a draft sees that it is one: the title, the verdict box and every
    page's footer say so; a sign-off report carries none of those marks."""
    mission = load_mission(MISSIONS / "set-static.toml")
    draft = " ".join(render(check(mission.with_fidelity("draft")).results, ("html",))["html"].decode().split())
    sign = " ".join(render(check(mission).results, ("html",))["html"].decode().split())
    assert '<span class="draft-mark">DRAFT</span></h1>' in draft and "(DRAFT)</title>" in draft
    assert "Draft verdict, not for signature" in draft
    assert f' · {mission.provenance.name} · DRAFT, not for signature"; font-size' in draft  # the PDF's page footer
    for mark in ("draft-mark\">", "(DRAFT)", "Draft verdict", "DRAFT, not for signature"):
        assert mark not in sign
