"""How the tether is attached (etcheck/checks/margins/attachment.py): the check under pinned and mixed ends, the margins
under the other attachments beside each margin, and the buckled rungs refused for non-welded ends."""

from __future__ import annotations

import json
import math
from pathlib import Path

import jsonschema
import pytest
from helpers import set_like

from etcheck.checks.pipeline import check
from etcheck.report import render
from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.exact.roots import exact_critical

SCHEMA = json.loads((Path(__file__).resolve().parents[2] / "docs" / "results.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
#: SET spinning as in missions/set.toml (the paper's omega = 0.25), with its default damping
SPUN = {"spin_rate": "0.1041 rpm"}


def results(**fields) -> dict:
    return check(set_like(**fields)).results


def margin(r: dict, starts: str) -> dict:
    return next(m for m in r["margins"] if m["name"].startswith(starts))


def valid(r: dict) -> None:
    errors = list(VALIDATOR.iter_errors(json.loads(json.dumps(r))))
    assert not errors, errors[0].message[:300]


@pytest.fixture(scope="module")
def spun():
    return {ends: results(end_conditions=list(ends), **SPUN)
            for ends in (("welded", "welded"), ("pinned", "pinned"), ("welded", "pinned"))}


def test_each_margin_has_the_same_margin_under_the_other_attachment(spun):
    """Welded SET beside both-pinned, pinned beside both-welded: each alternative is the other check's margin
    (to the two checks' tolerances), and mixed ends lie between the two."""
    welded, pinned, mixed = spun.values()
    for r, other in ((welded, pinned), (pinned, welded)):
        valid(r)
        assert [a["ends"] for a in r["attachment"]["alternatives"]] == [other["attachment"]["ends"]]
        for m in r["margins"]:
            (alt,) = m["alternatives"]
            mine = margin(other, m["name"])
            assert alt["value"] == pytest.approx(mine["value"], rel=1e-8)
            assert alt["verdict"] == mine["verdict"]
    valid(mixed)
    for m in mixed["margins"]:
        lo, hi = sorted(a["value"] for a in m["alternatives"])
        assert lo < m["value"] < hi  # the all-pinned and all-welded attachments bound one of each
    # the verdict hangs on the attachment: SET passes welded, its spin margin fails with both ends pinned (and
    # pinned it bows five times as far under the field across it, 4.3 % of its length: outside the model)
    assert welded["verdict"] == "pass" and "fail" in {m["verdict"] for m in pinned["margins"]}
    assert pinned["verdict"] == "outside"
    assert welded["attachment"]["alternatives"][0]["verdict"] == "fail"


def test_pinned_critical_load_from_an_independent_route(spun):
    """The check's pinned load margin (collocation, static pencils) against the exact determinant."""
    r = spun[("pinned", "pinned")]
    p = RodParameters(**{k: r["scaled"][k] for k in ("P", "R", "Gamma", "f", "B", "omega", "T", "gamma")},
                      ends=("pinned", "pinned"))
    exact = exact_critical(p, tol=1e-10)
    load = margin(r, "magnetic load")
    assert load["critical"] == pytest.approx(exact.critical_load.value * r["scales"]["load_N_per_m"], rel=1e-9)
    spin = margin(r, "spin rate")
    assert spin["critical"] == pytest.approx(exact.critical_spin.value * r["scales"]["reference_frequency_rad_s"]
                                             * 30 / math.pi, rel=1e-8)


def test_rung0_pinned_margin_is_the_closed_form():
    r = results(end_conditions="pinned")
    assert r["plan"]["rung"] == 0 and "closed-form" in r["plan"]["reason"]
    B1 = critical_loads(21 / 38, F_CLAMPED, 1, ("pinned", "pinned"))[0]
    (m,) = r["margins"]
    assert m["value"] == pytest.approx(B1 / r["scaled"]["B"], rel=1e-13)
    assert m["alternatives"][0]["value"] / m["value"] == pytest.approx(1 / 0.3619152543, rel=1e-9)
    assert r["straight_rod"]["critical_loads"][0]["beta"] == pytest.approx(5.225154248768965, rel=1e-15)
    valid(r)


def test_buckled_rungs_refused_for_pinned_ends():
    """Past the first critical load (SET at 600 m): the buckled tether is not computed with the wrong ends, and
    the report's post-buckling section says why; the straight margins decide (they fail)."""
    r = results(length="600 m", end_conditions=["pinned", "welded"])
    post = r["postbuckling"]
    assert post is not None and post["computed"] is False
    assert "welded ends only" in post["reason"] and "not computed" in r["attachment"]["buckled"]
    assert all(m["rung"] != 3 for m in r["margins"]) and "fail" in {m["verdict"] for m in r["margins"]}
    assert r["verdict"] == "outside"  # untensioned at 600 m it also bows far past the straight model's limit
    html = render(r, ("html",))["html"].decode()
    assert "Not computed:" in html and "welded ends only" in html
    valid(r)


def test_report_names_the_attachment_and_the_alternative(spun):
    r = spun[("welded", "pinned")]
    html = render(r, ("html",))["html"].decode()
    assert "lower end welded, upper end pinned" in html
    assert "tether.end_conditions" in html  # the inputs table
    assert "The verdict hangs on how the tether is held" in html  # passes mixed, fails both pinned
    for m in r["margins"]:
        for a in m["alternatives"]:
            assert f"both {a['ends'][0]}: " in html
    assert any("welded and with both pinned, which bound it" in v for v in r["validity"])
