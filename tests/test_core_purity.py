"""The unitless core (etcheck.rod, etcheck.numerics) never imports astropy, pint,
matplotlib or jinja2 (DESIGN.md, conventions); ``import etcheck`` stays free of
matplotlib. Each check runs in a fresh interpreter and inspects sys.modules."""

from __future__ import annotations

import json
import os
import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "etcheck"
FORBIDDEN = ("astropy", "pint", "matplotlib", "jinja2")


def core_modules() -> list[str]:
    names = []
    for sub in ("rod", "numerics"):
        names.append(f"etcheck.{sub}")
        for info in pkgutil.iter_modules([str(PACKAGE / sub)]):
            names.append(f"etcheck.{sub}.{info.name}")
    return names


def loaded_after(code: str) -> list[str]:
    """Run ``code`` in a fresh interpreter; return the forbidden top-level packages it loaded."""
    probe = (
        code
        + "\nimport json, sys\n"
        + f"print(json.dumps(sorted({{m.split('.')[0] for m in sys.modules}} & set({list(FORBIDDEN)!r}))))\n"
    )
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120, cwd=ROOT, env=env)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])


def test_core_modules_found():
    names = core_modules()
    assert "etcheck.rod.analytic" in names
    assert "etcheck.numerics.chebyshev" in names


def test_core_modules_alone_are_pure():
    """The core modules' own imports: the parent package is stubbed so that only
    etcheck.rod.* and etcheck.numerics.* (and what they import) are loaded."""
    stub = (
        "import sys, types\n"
        "pkg = types.ModuleType('etcheck')\n"
        f"pkg.__path__ = [{str(PACKAGE)!r}]\n"
        "sys.modules['etcheck'] = pkg\n"
    )
    imports = "".join(f"import {name}\n" for name in core_modules())
    assert loaded_after(stub + imports) == []


def test_importing_core_does_not_load_units_or_plotting():
    """`import etcheck.rod.analytic` etc. as a user writes it (parent package included)."""
    imports = "".join(f"import {name}\n" for name in core_modules())
    loaded = loaded_after(imports)
    assert loaded == [], (
        f"importing the core loads {loaded}: importing a subpackage runs etcheck/__init__.py first, "
        "so the public API there must be imported lazily (PEP 562 __getattr__)"
    )


@pytest.mark.parametrize("name", ["etcheck"])
def test_import_etcheck_does_not_load_plotting(name):
    loaded = loaded_after(f"import {name}")
    assert "matplotlib" not in loaded
    assert "jinja2" not in loaded
