"""etcheck: design checks of electrodynamic space tethers against magnetic
buckling and whirl (Valverde & van der Heijden's whirling conducting rod).

Public API::

    from etcheck import load_mission, check
    result = check(load_mission("missions/set.toml"))
    result.verdict, result.results["margins"]
"""

__version__ = "0.1.0"

from .check import CheckResult, check  # noqa: E402
from .errors import EtcheckError, MissionError, SolverError  # noqa: E402
from .mission import Mission, load_mission, mission_from_dict  # noqa: E402
from .scaling import scale, scene, unscale  # noqa: E402

__all__ = [
    "CheckResult",
    "EtcheckError",
    "Mission",
    "MissionError",
    "SolverError",
    "__version__",
    "check",
    "load_mission",
    "mission_from_dict",
    "scale",
    "scene",
    "unscale",
]
