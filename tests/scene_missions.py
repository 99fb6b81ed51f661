"""Valid physical missions for the property tests of the subcommands (diagram, damping-map, sweep,
accuracy), written as mission files, and the checks every command's output must pass.

A scene is drawn in the paper's dimensionless numbers (arXiv:0810.3668 eq. (36)): stiffness ratio R,
rotary inertia P, tension T, damping gamma, spin omega as a multiple of the unloaded tether's critical
spin, and turned into SI fields of a mission file at a drawn length (1 m - 100 km) with EI1 = 38 N m2
and 0.1 kg/m, so that the same dimensionless scene is reached through a short or a long tether.

The tests' hypothesis settings come from :func:`profile`: by default very few derandomised examples
(a diagram or damping-map run costs seconds), many more with HYPOTHESIS_PROFILE=thorough, e.g.
``HYPOTHESIS_PROFILE=thorough pytest tests/cli tests/studies/test_diagram_properties.py -n 0``.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st

from etcheck.rod.core.parameters import F_CLAMPED

#: EI1 [N m2] and mass per length [kg/m] of every drawn tether (only the dimensionless scene matters)
EI1, MASS = 38.0, 0.1
#: the dimensionless dampings drawn: none, tiny, the paper's (Sec. VII B), heavy
GAMMAS = (0.0, 1e-9, 0.04375, 0.5)

THOROUGH = os.environ.get("HYPOTHESIS_PROFILE", "") == "thorough"
_COMMON = dict(deadline=None, derandomize=True, suppress_health_check=list(HealthCheck), database=None)


def profile(default: int, thorough: int) -> settings:
    """Settings of one property test: ``default`` drawn examples normally (0: its explicit examples
    only), ``thorough`` under HYPOTHESIS_PROFILE=thorough (still derandomised: the same scenes every run)."""
    n = thorough if THOROUGH else default
    if n == 0:
        return settings(max_examples=1, phases=(Phase.explicit,), **_COMMON)
    return settings(max_examples=n, **_COMMON)


def reference_frequency(length: float) -> float:
    """omega_c = sqrt(f EI1 / (rho A L^4)) [rad/s] of a drawn tether of this length [m]."""
    return math.sqrt(F_CLAMPED * EI1 / (MASS * length**4))


@st.composite
def scenes(draw, spin: bool = True) -> dict[str, Any]:
    """A valid dimensionless scene with the length that carries it: dict of R, P, T, gamma,
    omega_factor (multiple of sqrt(R), about the unloaded critical spin), omega and length [m]."""
    R = draw(st.sampled_from([1.0, 0.5526, 0.1, 0.01]))
    P = 10 ** draw(st.sampled_from([-9.0, -5.0, -3.0, -1.0]))
    T = draw(st.sampled_from([0.0, 0.3, 30.0]))
    gamma = draw(st.sampled_from(GAMMAS))
    factor = draw(st.sampled_from([0.0, 0.1, 0.5, 1.0, 3.0, 10.0] if spin else [0.0]))
    length = 10 ** draw(st.sampled_from([0.0, 2.0, 5.0]))  # 1 m, 100 m, 100 km
    return {"R": R, "P": P, "T": T, "gamma": gamma, "omega_factor": factor,
            "omega": factor * math.sqrt(R), "length": length}


def mission_dict(s: dict[str, Any], B: float = 0.0, name: str = "scene") -> dict:
    """Mission (nested dicts) of scene ``s`` at dimensionless load B (0: no current)."""
    L = s["length"]
    wc = reference_frequency(L)
    force = F_CLAMPED * EI1 / L**2  # [N]
    load = force / L  # [N/m]
    field = 70e-6  # [T]
    return {
        "mission": {"name": name, "description": "drawn by the property tests"},
        "tether": {
            "length": f"{L!r} m",
            "bending_stiffness": [f"{EI1!r} N m2", f"{EI1 * s['R']!r} N m2"],
            "poisson_ratio": 0.3,
            "mass_per_length": f"{MASS!r} kg/m",
            "rotary_inertia_ratio": s["P"],
            "damping_time": f"{s['gamma'] / wc!r} s",
        },
        "operation": {
            "current": f"{B * load / field!r} A",
            "axial_field": "70 uT",
            "spin_rate": f"{s['omega'] * wc!r} rad/s",
            "end_tension": f"{s['T'] * force!r} N",
        },
        "check": {"fidelity": "draft"},
    }


def _toml_value(v: Any) -> str:
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):  # an inline table, e.g. an [uncertainty] input
        return "{ " + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"no TOML for {v!r}")


def write_mission(data: dict, folder: Path, stem: str = "scene") -> Path:
    """The mission dicts as a TOML file ``folder/stem.toml``."""
    lines = []
    for table, fields in data.items():
        lines.append(f"[{table}]")
        lines += [f"{key} = {_toml_value(value)}" for key, value in fields.items()]
        lines.append("")
    path = folder / f"{stem}.toml"
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def _reject(constant: str):
    raise ValueError(f"not strict JSON: {constant}")


def strict_json(text: str) -> Any:
    """Parse ``text``, refusing NaN, Infinity and -Infinity (which json.loads accepts by default)."""
    return json.loads(text, parse_constant=_reject)


def numbers(obj: Any, where: str = "") -> list[tuple[str, float]]:
    """Every number in a JSON-able tree with its path (bools excluded)."""
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return []
    if isinstance(obj, int | float):
        return [(where, float(obj))]
    if isinstance(obj, dict):
        return [x for k, v in obj.items() for x in numbers(v, f"{where}.{k}")]
    if isinstance(obj, list | tuple):
        return [x for i, v in enumerate(obj) for x in numbers(v, f"{where}[{i}]")]
    raise TypeError(f"{where}: not JSON-able: {type(obj).__name__}")


def assert_all_finite(obj: Any) -> None:
    """Every number of a results tree is finite (a missing one must be None, never NaN or inf)."""
    bad = [(w, x) for w, x in numbers(obj) if not math.isfinite(x)]
    assert not bad, f"non-finite numbers: {bad[:5]}"


def assert_clean_exit(code: int, err: str, allowed: tuple[int, ...] = (0, 1)) -> None:
    """An exit code the command documents for a valid scene, a refusal (2) with a message, never a
    traceback, an internal error or a failed solve (3)."""
    assert "Traceback" not in err, err
    assert code in (*allowed, 2), f"exit {code}: {err.strip()}"
    if code == 2:
        assert err.startswith("etcheck: ") and len(err.strip()) > len("etcheck: error: "), err
