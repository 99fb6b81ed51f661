"""etcheck: design checks of electrodynamic space tethers against magnetic
buckling and whirl (Valverde & van der Heijden's whirling conducting rod).

Public API::

    from etcheck import load_mission, check
    result = check(load_mission("missions/set.toml"))
    result.verdict, result.results["margins"]
"""

__version__ = "0.1.0"

from .runtime.numpy_clone import install as _install_import_hook

_install_import_hook()  # scipy's clone of numpy skips numpy's developer tools (~0.15 s of every cold start)

# Lazy public API (PEP 562): importing the unitless core (etcheck.rod,
# etcheck.numerics) must not pull in astropy, pint or the report stack.
_EXPORTS = {
    "CheckResult": "etcheck.checks.pipeline",
    "check": "etcheck.checks.pipeline",
    "EtcheckError": "etcheck.errors",
    "MissionError": "etcheck.errors",
    "SolverError": "etcheck.errors",
    "Mission": "etcheck.input.mission",
    "load_mission": "etcheck.input.mission",
    "mission_from_dict": "etcheck.input.mission",
    "scale": "etcheck.scaling",
    "scene": "etcheck.scaling",
    "unscale": "etcheck.scaling",
}


def __getattr__(name: str):
    if name in _EXPORTS:
        import importlib

        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'etcheck' has no attribute {name!r}")


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
