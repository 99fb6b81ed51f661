"""The committed example reports (reports/, written by scripts/regenerate-reports) are not stale.

Each shipped mission is checked afresh (JSON only) and its margins must agree
with the committed results.json within their stated errors; the mission files
must be the ones the examples were made from (SHA-256). The sweep, diagram and
damping map take minutes to recompute: only their mission file and the sweep's
zero-spin critical length (the check's static critical length) are compared.
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

import pytest

from etcheck.checks.orbit_field import resolve
from etcheck.checks.rungs.static_buckling import static_buckling
from etcheck.input.mission import load_mission
from etcheck.scaling import scale

ROOT = Path(__file__).resolve().parents[2]
REPORTS = ROOT / "reports"
MISSIONS = sorted((ROOT / "missions").glob("*.toml"))
#: a committed check slower than this is compared in its rung-0 margin only (keeps the suite fast)
SLOW_S = 5.0
REGENERATE = "stale example reports: run scripts/regenerate-reports and commit reports/"


def _committed(mission: Path) -> dict:
    folder = REPORTS / load_mission(mission).slug
    path = folder / "results.json"
    assert path.exists(), f"{path.relative_to(ROOT)} missing: {REGENERATE}"
    assert (folder / "report.html").exists() and (folder / "report.pdf").exists(), REGENERATE
    return json.loads(path.read_text())


def _agree(old: float | None, new: float | None, err_old, err_new, what: str) -> None:
    if old is None or new is None:
        assert old == new, f"{what}: committed {old}, fresh {new}; {REGENERATE}"
        return
    # both errors are relative; allow their sum plus round-off
    tol = (abs(err_old or 0.0) + abs(err_new or 0.0) + 1e-9) * max(abs(old), abs(new))
    assert math.isclose(old, new, rel_tol=0, abs_tol=tol), f"{what}: committed {old}, fresh {new} (tol {tol:.2e}); {REGENERATE}"


@pytest.mark.parametrize("mission", MISSIONS, ids=[m.stem for m in MISSIONS])
def test_committed_check_agrees_with_a_fresh_run(mission):
    old = _committed(mission)
    assert old["mission"]["sha256"] == hashlib.sha256(mission.read_bytes()).hexdigest(), \
        f"{mission.name} changed since its example report was made; {REGENERATE}"
    if old["elapsed_s"] > SLOW_S:  # the buckled tether: its rung-0 margin (rungs 2-3, seconds, are tested in tests/checks/test_buckled.py)
        sc = resolve(load_mission(mission)).scene  # an [orbit] table's field is the check's orbit stage
        fresh = static_buckling(scale(sc)).critical_loads[0]
        committed = old["straight_rod"]["critical_loads"][0]
        _agree(committed["IB0_N_per_m"], fresh.IB0_N_per_m, committed["relative_error"], fresh.relative_error,
               f"{mission.name}: first critical load")
        return
    from etcheck import check

    new = check(mission).results
    assert [g["name"] for g in new["margins"]] == [g["name"] for g in old["margins"]], REGENERATE
    assert new["verdict"] == old["verdict"], REGENERATE
    for a, b in zip(old["margins"], new["margins"]):
        assert a["verdict"] == b["verdict"], f"{mission.name}: {a['name']}; {REGENERATE}"
        _agree(a["value"], b["value"], a["error"], b["error"], f"{mission.name}: {a['name']}")


@pytest.mark.parametrize("name", ["sweep/sweep.json", "diagram-w0.25/diagram.json", "damping-map/damping.json"])
def test_committed_studies_match_their_mission(name):
    path = REPORTS / "set" / name
    assert path.exists(), f"{path.relative_to(ROOT)} missing: {REGENERATE}"
    assert path.with_suffix(".html").exists() and path.with_suffix(".pdf").exists(), REGENERATE
    r = json.loads(path.read_text())
    assert r["mission"]["sha256"] == hashlib.sha256((ROOT / "missions" / "set.toml").read_bytes()).hexdigest(), REGENERATE


def test_committed_sweep_meets_the_check_at_zero_spin():
    """The sweep's exactly located critical length at zero spin is the check's static critical length."""
    sweep = json.loads((REPORTS / "set" / "sweep" / "sweep.json").read_text())
    row = next(r for r in sweep["critical_length"] if r["other_display"] == 0.0)
    fresh = json.loads((REPORTS / "set" / "results.json").read_text())["straight_rod"]["limits"]["critical_length_m"]
    assert math.isclose(row["length_m"], fresh, rel_tol=10 * sweep["tolerance"]), (row["length_m"], fresh)
