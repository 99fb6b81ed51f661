"""The layout holds: the unitless core (etcheck.rod, etcheck.numerics) never imports astropy,
pint, matplotlib or jinja2, ``import etcheck`` stays free of matplotlib, the import graph
of the package has no cycle and every layer imports only the layers below it."""

from __future__ import annotations

import json
import os
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "etcheck"
FORBIDDEN = ("astropy", "pint", "matplotlib", "jinja2")


def core_modules() -> list[str]:
    names = []
    for sub in ("rod", "numerics", "runtime"):
        names.append(f"etcheck.{sub}")
        for info in pkgutil.walk_packages([str(PACKAGE / sub)], prefix=f"etcheck.{sub}."):
            names.append(info.name)
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
    assert "etcheck.rod.straight.analytic" in names
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
    """`import etcheck.rod.straight.analytic` etc. as a user writes it (parent package included)."""
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


#: what each layer may import (besides itself, etcheck/__init__, etcheck.errors and etcheck.jsonable);
#: the data flow is input -> scaling -> check -> studies -> report -> cli, with rod/numerics underneath
LAYERS = {
    "runtime": set(),  # process plumbing: BLAS threads, forked helpers, memory budget, deadlines
    "numerics": {"runtime"},
    "rod": {"numerics", "runtime"},
    "orbit": set(),  # the orbit package reads no mission: the [orbit] table is read by input/orbit_table.py
    "input": {"rod.core", "orbit"},  # reading needs the ends and the parameters' types, never a solver
    "scaling": {"input", "rod"},
    "checks": {"input", "scaling", "rod", "numerics", "runtime", "orbit"},
    "studies": {"input", "scaling", "checks", "rod", "numerics", "runtime", "orbit"},
    "report": {"input", "numerics", "runtime"},  # never checks: reports are drawn from results alone
    "cli": {"input", "scaling", "checks", "studies", "report", "rod", "numerics", "runtime", "orbit"},
}
SHARED = {"__init__", "errors", "jsonable", "__main__"}


def _absolute(node, name: str, is_package: bool) -> str | None:
    """The absolute module an ``ImportFrom`` node names, relative imports resolved
    (``from ..checks import plan`` in etcheck.rod.core.linear -> etcheck.rod.checks... per its level)."""
    if node.level == 0:
        return node.module
    base = name.split(".") if is_package else name.split(".")[:-1]
    if node.level > 1:
        base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _import_graph(root: Path = ROOT) -> dict[str, set[str]]:
    """etcheck module -> etcheck modules it imports (anywhere in the file, absolute or
    relative), from the source of the package under ``root``."""
    import ast

    graph: dict[str, set[str]] = {}
    modules, packages = {}, set()
    for path in (root / "etcheck").rglob("*.py"):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
            packages.add(".".join(parts))
        modules[".".join(parts)] = path
    for name, path in modules.items():
        deps = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                module = _absolute(node, name, name in packages)
                if not module or not module.startswith("etcheck"):
                    continue
                subs = {f"{module}.{a.name}" for a in node.names if f"{module}.{a.name}" in modules}
                deps |= subs if len(subs) == len(node.names) else subs | {module}
            elif isinstance(node, ast.Import):
                deps |= {a.name for a in node.names if a.name.startswith("etcheck")}
        graph[name] = {d for d in deps if d in modules and d != name and d != "etcheck"}
    return graph


def test_import_graph_has_no_cycle():
    graph = _import_graph()
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph[n]):
            if state.get(m) == 1:
                raise AssertionError("import cycle: " + " -> ".join(stack[stack.index(m):] + [m]))
            if m not in state:
                visit(m)
        stack.pop()
        state[n] = 2

    for n in sorted(graph):
        if n not in state:
            visit(n)


def _allowed(module: str, allowed: set[str]) -> bool:
    """Whether ``module`` lies in one of the ``allowed`` layers ("rod" or a part of one, "rod.core")."""
    return any(module == f"etcheck.{a}" or module.startswith(f"etcheck.{a}.") for a in allowed)


def _layer_violations(root: Path = ROOT) -> list[str]:
    bad = []
    for name, deps in _import_graph(root).items():
        layer = name.split(".")[1] if "." in name else None
        if layer is None or layer in SHARED:
            continue
        for d in deps:
            other = d.split(".")[1]
            if other != layer and other not in SHARED and not _allowed(d, LAYERS[layer]):
                bad.append(f"{name} imports {d}")
    return sorted(bad)


def test_layers_import_only_layers_below():
    bad = _layer_violations()
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("planted", [
    "from ...checks import plan\n",            # relative, two packages up
    "from ...checks.plan import plan\n",
    "from etcheck.checks import plan\n",       # absolute
    "import etcheck.report.html\n",
])
def test_a_planted_layer_violation_is_found(tmp_path, planted):
    """The layer test sees through relative imports: a rod module (two packages deep)
    importing checks/ or report/ in any spelling fails it."""
    import shutil

    shutil.copytree(PACKAGE, tmp_path / "etcheck", ignore=shutil.ignore_patterns("__pycache__"))
    target = tmp_path / "etcheck" / "rod" / "core" / "parameters.py"
    target.write_text(target.read_text() + "\n" + planted)
    bad = _layer_violations(tmp_path)
    assert bad and all(b.startswith("etcheck.rod.core.parameters imports etcheck.") for b in bad), bad


@pytest.mark.parametrize("where, planted", [
    ("input/mission.py", "from etcheck.rod.straight import analytic\n"),   # input reads; it never solves
    ("report/html.py", "from etcheck.checks.margins import margin\n"),     # reports are drawn from results alone
    ("runtime/blas.py", "from etcheck.numerics import chebyshev\n"),      # plumbing knows no numerics
])
def test_the_tightened_layers_hold(tmp_path, where, planted):
    """input may import rod.core only, report never imports checks, runtime imports nothing of etcheck."""
    import shutil

    shutil.copytree(PACKAGE, tmp_path / "etcheck", ignore=shutil.ignore_patterns("__pycache__"))
    target = tmp_path / "etcheck" / where
    target.write_text(target.read_text() + "\n" + planted)
    module = "etcheck." + where.removesuffix(".py").replace("/", ".")
    bad = _layer_violations(tmp_path)
    assert bad and all(b.startswith(f"{module} imports etcheck.") for b in bad), bad


def test_relative_imports_resolve():
    """``from .. import x`` and ``from ..numerics.blas import y`` resolve to the modules they name."""
    graph = _import_graph()
    assert "etcheck.runtime.blas" in graph["etcheck.numerics.eigen"]


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _etcheck_imports(tree, where: str, package: bool) -> tuple[list[str], set[str]]:
    """The private names imported from etcheck (relative imports count in the package), and the local names of the
    etcheck modules and names imported."""
    import ast

    bad, modules = [], set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and ((package and node.level) or (node.module or "").startswith("etcheck")):
            bad += [f"{where}: from {node.module} import {a.name}" for a in node.names if _private(a.name)]
            modules |= {a.asname or a.name for a in node.names}
        elif isinstance(node, ast.Import):
            modules |= {a.asname or a.name for a in node.names if a.name.startswith("etcheck")}
    return bad, modules


def _private_attributes(tree, where: str, modules: set[str]) -> list[str]:
    """``module._name`` and ``setattr(module, "_name", ...)`` (monkeypatch's included) on the ``modules``."""
    import ast

    bad = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules
                and _private(node.attr)):
            bad.append(f"{where}: {node.value.id}.{node.attr}")
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "setattr"
              and len(node.args) >= 2 and isinstance(node.args[0], ast.Name) and node.args[0].id in modules
              and isinstance(node.args[1], ast.Constant) and _private(str(node.args[1].value))):
            bad.append(f"{where}: setattr({node.args[0].id}, {node.args[1].value!r})")
    return bad


def _private_imports(root: Path = ROOT) -> list[str]:
    """``from etcheck.x import _name`` and ``module._name`` on an imported etcheck module, anywhere in the
    package (a private name belongs to its module; what another module needs is public)."""
    import ast

    bad = []
    for path in (root / "etcheck").rglob("*.py"):
        tree = ast.parse(path.read_text())
        where = str(path.relative_to(root))
        imported, modules = _etcheck_imports(tree, where, package=True)
        bad += imported + _private_attributes(tree, where, modules)
    return sorted(bad)


def test_no_private_name_crosses_a_module():
    bad = _private_imports()
    assert not bad, "\n".join(bad)


def _private_uses_in_tests(tests: Path = ROOT / "tests") -> list[str]:
    """What the tests reach that is not etcheck's public interface: ``from etcheck.x import _name``, ``from etcheck
    import _module``, ``module._name`` on an imported etcheck module, ``setattr(module, "_name", ...)`` (monkeypatch
    included) on one, and any name imported from another test module (shared helpers live in tests/helpers.py)."""
    import ast

    bad = []
    for path in sorted(tests.rglob("*.py")):
        tree = ast.parse(path.read_text())
        where = str(path.relative_to(tests.parent))
        imported, modules = _etcheck_imports(tree, where, package=False)
        bad += imported + _private_attributes(tree, where, modules)
        for node in ast.walk(tree):
            names = ([node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else
                     [a.name for a in node.names] if isinstance(node, ast.Import) else [])
            bad += [f"{where}: import from {n} (another test module)" for n in names if n.startswith("test")]
    return sorted(bad)


def test_tests_use_only_public_names():
    """The tests exercise etcheck through its public interface (a private name may change with no one told)."""
    bad = _private_uses_in_tests()
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("planted, found", [
    ("from etcheck.checks.rungs.straight import _critical\n", "import _critical"),
    ("from etcheck import numpy_clone as hook\nhook._HOOK\n", "hook._HOOK"),
    ("import etcheck.runtime.parallel as par\ndef test_x(monkeypatch):\n"
     "    monkeypatch.setattr(par, '_SERIAL', False)\n", "setattr(par, '_SERIAL')"),
    ("from test_scene_space import assert_well_formed\n", "another test module"),
])
def test_a_planted_private_use_in_a_test_is_found(tmp_path, planted, found):
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_planted.py").write_text(planted)
    bad = _private_uses_in_tests(tmp_path / "tests")
    assert len(bad) == 1 and found in bad[0], bad


def test_a_planted_private_import_is_found(tmp_path):
    import shutil

    shutil.copytree(PACKAGE, tmp_path / "etcheck", ignore=shutil.ignore_patterns("__pycache__"))
    target = tmp_path / "etcheck" / "checks" / "plan.py"
    target.write_text(target.read_text() + "\nfrom etcheck.rod.straight.collocation.spectral import _family_cached\n")
    assert any("_family_cached" in b for b in _private_imports(tmp_path))


#: the modules past the unit boundary (etcheck.scaling) that may still hold astropy units, and why
UNITS_ALLOWED = {
    # the orbit stage writes the worst field over the orbit into the mission's echo of its axial field (a quantity,
    # as the file gives it) and times the orbit's window in UTC
    "etcheck/checks/orbit_field.py",
}
#: an astropy unit conversion or a quantity made from a unit: ``x.to_value(...)``, ``x.to(u.N)``, ``3 * u.s``,
#: an import of astropy (``u.real`` of an eigenvector ``u`` is no unit)
UNIT_PATTERN = re.compile(r"\.to_value\(|\.to\(\s*(u\.|[\"'])|\bastropy\b|"
                          r"\bu\.(?:m|s|N|A|T|uT|nT|kg|rad|deg|km|d|h|min|one|cycle|Quantity|Unit)\b")


def test_nothing_past_scaling_handles_units():
    """docs/scaling.md: the scene carries the operating values in SI floats and the Scales convert dimensionless
    answers back; the checks and studies convert no units themselves (nor read the mission's quantities)."""
    found = []
    for folder in ("checks", "studies"):
        for path in sorted((PACKAGE / folder).rglob("*.py")):
            rel = path.relative_to(ROOT).as_posix()
            if rel in UNITS_ALLOWED:
                continue
            for n, line in enumerate(path.read_text().splitlines(), 1):
                if UNIT_PATTERN.search(line.split("#")[0]):
                    found.append(f"{rel}:{n}: {line.strip()}")
    assert found == [], "unit conversions past etcheck.scaling:\n" + "\n".join(found)
