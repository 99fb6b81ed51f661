"""Bifurcation diagram of a mission's tether: the post-buckling branches at a chosen spin (rungs 2-3).

The branches, their stability and shapes come from :func:`etcheck.checks.buckled.bifurcation_diagram`;
this study fixes the scene (the mission, a spin, optionally another stiffness ratio) and
returns the JSON-able results the diagram report is rendered from, with SI scales.
"""

from __future__ import annotations

from typing import Any

from etcheck.checks.buckled import DiagramOptions, bifurcation_diagram
from etcheck.checks.results import results_header
from etcheck.input.mission import Mission
from etcheck.scaling import RPM, scale, scene


def diagram_study(mission: Mission, omega: float | None = None, R: float | None = None,
                  options: DiagramOptions | None = None) -> dict[str, Any]:
    """Branches of the mission's tether at dimensionless spin ``omega`` (default: the mission's)
    and stiffness ratio ``R`` (default: the mission's); JSON-able with SI scales."""
    scaled = scale(scene(mission))
    params = scaled.params if omega is None else scaled.params.with_(omega=omega)
    if R is not None:
        params = params.with_(R=R)
    d = bifurcation_diagram(params, scaled.scales, options or DiagramOptions())
    return results_header(mission) | {
        "spin_rpm": params.omega * scaled.scales.frequency * RPM,
        "R_override": R,
        "scales": {"length_m": scaled.scales.length, "load_N_per_m": scaled.scales.load,
                   "force_N": scaled.scales.force},
        "diagram": d,
    }


def folder_name(omega: float, R: float | None) -> str:
    """Report folder of a diagram: ``diagram-w<omega>[-R<R>]``."""
    return f"diagram-w{omega:.4g}" + (f"-R{R:g}" if R is not None else "")
