"""Bifurcation diagram of a mission's tether: the post-buckling branches at a chosen spin (rungs 2-3).

The branches, their stability and shapes come from :func:`etcheck.checks.rungs.buckled.bifurcation_diagram`;
this study fixes the scene (the mission, a spin, optionally another stiffness ratio) and
returns the JSON-able results the diagram report is rendered from, with SI scales.
"""

from __future__ import annotations

from typing import Any

from etcheck.checks.orbit_field import resolve
from etcheck.checks.plan import LAYER_MIN, R_MIN_SPECTRAL, boundary_layer
from etcheck.checks.results.header import results_header
from etcheck.checks.rungs.buckled import DiagramOptions, bifurcation_diagram
from etcheck.errors import MissionError
from etcheck.input.mission import Mission
from etcheck.jsonable import to_json
from etcheck.rod.buckled import pitchforks
from etcheck.rod.core.ends import BUCKLED_WELDED_ONLY, describe, is_welded
from etcheck.rod.core.parameters import RodParameters
from etcheck.scaling import scale


def postbuckling_limit(params: RodParameters) -> str | None:
    """Why rungs 2-3 (the buckled branches) are outside their validated range at ``params``, or None.

    The check's own limit (:mod:`etcheck.checks.plan`): end boundary layers thinner than LAYER_MIN of
    the length, or a nearly string-like weak axis (R < R_MIN_SPECTRAL), are not resolved by the Chebyshev
    collocation of the buckled tether; the text names the number exceeded and the limit.
    """
    layer = boundary_layer(params)
    if layer < LAYER_MIN:
        return (f"the end boundary layers are {layer:.2g} of the tether's length (spin {params.omega:.4g}, "
                f"tension T = {params.T:.4g}, R = {params.R:.4g}), thinner than the {LAYER_MIN:g} the buckled "
                "branches (rungs 2-3) are validated for")
    if params.R < R_MIN_SPECTRAL:
        return (f"the weak axis is nearly a string (R = {params.R:.2g} < {R_MIN_SPECTRAL:g}), below the "
                "stiffness ratio the buckled branches (rungs 2-3) are validated for")
    return None


def refuse_outside_limit(mission: Mission, params: RodParameters, what: str, field: str | None = None) -> None:
    """A :class:`~etcheck.errors.MissionError` (exit 2) when ``params`` are outside rungs 2-3's validated
    range (:func:`postbuckling_limit`) or the tether's ends are not welded, before any solve; ``what`` names the
    study."""
    if not is_welded(params.ends):
        raise MissionError(mission.provenance.file or "mission", "tether.end_conditions",
                           f"{what} needs the buckled tether (rungs 2-3), which is {BUCKLED_WELDED_ONLY} (this "
                           f"tether is {describe(params.ends)})",
                           "the straight tether's margins for these ends are given by 'etcheck MISSION'")
    why = postbuckling_limit(params)
    if why is not None:
        if field is None:
            field = ("tether.bending_stiffness" if params.R < R_MIN_SPECTRAL
                     else "operation.end_tension" if params.T > 0 else "operation.spin_rate")
        raise MissionError(mission.provenance.file or "mission", field,
                           f"{what} is outside the model's validated range: {why}",
                           "lower the end tension or spin, or raise EI2 (tether.bending_stiffness), so that "
                           f"the boundary layers sqrt(R / (f T_eff)) are at least {LAYER_MIN:g} of the length; "
                           "the straight tether's critical loads are given by 'etcheck MISSION' (rung 1)")


def _refuse_below_first_pitchfork(params: RodParameters, options: DiagramOptions) -> None:
    """A usage error (exit 2) naming --B-max when the load range ends at or below the diagram's first
    pitchfork (the smallest static load of either symmetry class at the scene's spin): no branch would be drawn."""
    loads = [float(x[0]) for x in (pitchforks.class_loads(params.with_(B=0.0), which, options.N, n=1) for which in ("S1", "S2"))
             if x.size]
    if loads and options.B_max <= min(loads):
        raise MissionError("command line", "--B-max",
                           f"the load range ends at B = {options.B_max:g}, at or below the diagram's first pitchfork "
                           f"B = {min(loads):.6g} (where the first buckled branch starts): no branch would be drawn",
                           f"give --B-max above {min(loads):.4g}, or leave it out (default: 3 or 1.3 times the last "
                           "pitchfork)")


def diagram_study(mission: Mission, omega: float | None = None, R: float | None = None,
                  options: DiagramOptions | None = None) -> dict[str, Any]:
    """Branches of the mission's tether at dimensionless spin ``omega`` (default: the mission's)
    and stiffness ratio ``R`` (default: the mission's); JSON-able with SI scales."""
    scaled = scale(resolve(mission).scene)
    params = scaled.params if omega is None else scaled.params.with_(omega=omega)
    if R is not None:
        params = params.with_(R=R)
    refuse_outside_limit(mission, params, "the bifurcation diagram", "--R" if R is not None else None)
    options = options or DiagramOptions()
    if options.B_max is not None:
        _refuse_below_first_pitchfork(params, options)
    d = bifurcation_diagram(params, scaled.scales, options)
    op = scaled.params
    here = "" if op.omega == params.omega else f"; the mission spins at ω = {op.omega:.3g}"
    return to_json(results_header(mission)) | {
        "spin_rpm": scaled.scales.rpm(params.omega),
        "R_override": R,
        "operating": {"B": op.B, "omega": op.omega, "IB0_N_per_m": scaled.scales.line_load(op.B),
                      "label": f"mission operating load, straight tether{here}"},
        "scales": {"length_m": scaled.scales.length, "load_N_per_m": scaled.scales.load,
                   "force_N": scaled.scales.force},
        "diagram": d,
    }


def folder_name(omega: float, R: float | None) -> str:
    """Report folder of a diagram: ``diagram-w<omega>[-R<R>]``."""
    return f"diagram-w{omega:.4g}" + (f"-R{R:g}" if R is not None else "")
