"""A mission as nested dicts for the Python API: the static SET data
(Table I of the paper, no spin), with fields overridden per test."""

from __future__ import annotations

import copy
import re
from pathlib import Path

OPERATION_KEYS = ("current", "axial_field", "spin_rate", "end_tension")


def set_like(name: str = "api", description: str = "", check: dict | None = None, **fields) -> dict:
    """Static SET mission dict; ``fields`` go to [operation] or [tether] by name."""
    data = {
        "mission": {"name": name, "description": description},
        "tether": {
            "length": "100 m",
            "bending_stiffness": ["38 N m2", "21 N m2"],
            "poisson_ratio": 0.3,
            "mass_per_length": "0.1 kg/m",
            "rotary_inertia_ratio": 0.001,
        },
        "operation": {"current": "1 A", "axial_field": "70 uT"},
        "check": dict(check or {}),
    }
    for key, value in fields.items():
        data["operation" if key in OPERATION_KEYS else "tether"][key] = value
    return data


def tension_free(mission: Path, folder: Path) -> Path:
    """A copy of a shipped flight mission (PMG, ProSEDS) in ``folder`` with its gravity-gradient tension
    neglected, as the paper did (Sec. VII A): end_tension = 0 instead of end_masses and the orbit rate, and one
    current along the tether (no current_profile)."""
    text = re.sub(r"^(end_masses|orbit_rate|orbit_altitude|current_profile) = .*$", "", mission.read_text(), flags=re.M)
    text = re.sub(r"^\[operation\.collection\]\n(?:(?!\[).*\n)*", "", text, flags=re.M)  # one current, as the paper
    path = folder / mission.name
    path.write_text(text.replace("[operation]\n", '[operation]\nend_tension = "0 N"\n', 1))
    return path


def tape(current_profile: bool = True, end_masses: bool = True) -> dict:
    """The shipped tape tether as a mission dict; without its collected current (one current along the tether)
    and/or with its smallest gravity-gradient tension as one end tension instead of its end masses (the uniform
    routes of rung 1: the exact determinant)."""
    import tomllib

    from etcheck.input.mission import mission_from_dict

    data = tomllib.loads((Path(__file__).resolve().parents[1] / "missions" / "tape-tether.toml").read_text())
    minimum = mission_from_dict(copy.deepcopy(data)).operation.gravity_gradient.minimum
    if not current_profile:
        del data["operation"]["current_profile"], data["operation"]["collection"]
    if not end_masses:
        del data["tether"]["end_masses"]
        data["operation"]["end_tension"] = f"{minimum!r} N"
        data["mission"]["assumed"] = [a for a in data["mission"]["assumed"] if a != "tether.end_masses"]
    return data


def assert_well_formed(results: dict) -> None:
    """A check's results as a user may rely on them: strict JSON (no NaN, no Infinity), a verdict, every margin with
    its model and either its numerical error and value or why it is incomplete, and an HTML report that renders."""
    import json
    import math

    from etcheck.report import render

    json.dumps(results, allow_nan=False)
    assert results["verdict"] in ("pass", "fail", "incomplete", "outside")
    assert (results["verdict"] == "outside") == bool(results["model_validity"]["reasons"])
    assert results["margins"]
    for m in results["margins"]:
        assert m["model"]
        if m["verdict"] == "incomplete":
            assert m["why"]
        else:
            assert m["error"] is not None and math.isfinite(m["error"]) and m["error"] >= 0
            assert m["value"] is None or (math.isfinite(m["value"]) and m["value"] >= 0)
    html = render(results, ("html",))["html"].decode()
    assert "</html>" in html


def collocation_growth(p, N: int = 24) -> float:
    """Largest real part of the whole collocation spectrum of the straight rod with parameters ``p``
    (:class:`etcheck.rod.core.parameters.RodParameters`) at N, dense QZ (the spurious modes at |lambda| ~ 1e8 left
    out): an independent check of the critical values that the solvers locate."""
    import numpy as np
    import scipy.linalg as sl

    from etcheck.rod.core.base_state import straight
    from etcheck.rod.core.linear import linear_operator
    from etcheck.runtime.blas import one_blas_thread

    A0, A1, A2 = (np.asarray(a.todense()) if hasattr(a, "todense") else np.asarray(a)
                  for a in linear_operator(p, straight(p), N))
    n = A0.shape[0]
    Z, eye = np.zeros((n, n)), np.eye(n)
    with one_blas_thread():
        lam = sl.eigvals(np.block([[Z, eye], [-A0, -A1]]), np.block([[eye, Z], [Z, A2]]))
    lam = lam[np.isfinite(lam) & (np.abs(lam) < 1e3)]
    return float(lam.real.max())
