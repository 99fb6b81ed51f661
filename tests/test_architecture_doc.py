"""Every module, function and file that docs/architecture.md names exists: a dotted name
(``etcheck.checks.plan.plan``, ``etcheck.checks.results.sections.Margin.as_dict``) resolves to a module
of the package and a name defined at its top level (then in its class), a path
(``etcheck/checks/plan.py``, ``etcheck/report/templates/``) is a file or folder of the
repository. Read from the source (nothing is imported)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "architecture.md"
CODE = re.compile(r"`([^`\n]+)`")
DOTTED = re.compile(r"^etcheck(\.\w+)+$")
PATH = re.compile(r"^(etcheck|tests|docs|missions|benchmarks|scripts)/[\w./-]*$")


def _module_file(parts: list[str], root: Path) -> Path | None:
    base = root.joinpath(*parts)
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


def _defined(body: list[ast.stmt]) -> dict[str, ast.stmt]:
    """Names bound at the top of ``body``: functions, classes, assignments, imports."""
    names: dict[str, ast.stmt] = {}
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names[node.name] = node
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                for t in ast.walk(target):
                    if isinstance(t, ast.Name):
                        names[t.id] = node
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[node.target.id] = node
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            for a in node.names:
                names[(a.asname or a.name).split(".")[0]] = node
    return names


def missing_name(dotted: str, root: Path = ROOT) -> str | None:
    """Why ``dotted`` does not resolve in the source under ``root`` (None when it does)."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        path = _module_file(parts[:cut], root)
        if path is not None:
            break
    else:
        return f"{dotted}: no such module"
    rest = parts[cut:]
    body = ast.parse(path.read_text()).body
    for i, name in enumerate(rest):
        names = _defined(body)
        if name not in names:
            return f"{dotted}: {'.'.join(parts[:cut] + rest[:i]) or path} has no {name!r}"
        node = names[name]
        body = node.body if isinstance(node, ast.ClassDef) else []
        if i + 1 < len(rest) and not isinstance(node, ast.ClassDef):
            return f"{dotted}: {name!r} is not a class, nothing can be looked up in it"
    return None


def quoted(text: str) -> tuple[list[str], list[str]]:
    """The dotted etcheck names and the repository paths quoted (in backticks) in ``text``."""
    tokens = CODE.findall(text)
    return [t for t in tokens if DOTTED.match(t)], [t for t in tokens if PATH.match(t)]


def test_every_name_quoted_in_architecture_md_exists():
    names, paths = quoted(DOC.read_text())
    assert len(names) >= 60 and len(paths) >= 60, "the page names the modules and functions of the worked example"
    bad = [why for why in map(missing_name, sorted(set(names))) if why]
    bad += [f"{p}: no such file or folder" for p in sorted(set(paths)) if not (ROOT / p).exists()]
    assert not bad, "\n".join(bad)


def test_every_package_has_a_paragraph():
    text = DOC.read_text()
    for package in sorted(p.name for p in (ROOT / "etcheck").iterdir() if (p / "__init__.py").is_file()):
        assert f"**`etcheck/{package}/`**" in text, package


def test_a_wrong_name_is_found():
    """The checker fails on a module, a function, a method and a file that do not exist."""
    assert missing_name("etcheck.checks.plan.plan") is None
    assert missing_name("etcheck.checks.results.sections.Margin.as_dict") is None
    assert missing_name("etcheck.checks.plann.plan")  # a module misspelt: resolves to the package, which lacks it
    assert missing_name("etcheck.checks.plan.plan_route")
    assert missing_name("etcheck.checks.margins.margin.Margin.as_json")
    assert missing_name("etcheck.checks.plan.plan.route")  # a function has no attributes to name
    names, paths = quoted("`etcheck.checks.plan.plan` and `etcheck/checks/plan.py` but not `plan`")
    assert names == ["etcheck.checks.plan.plan"] and paths == ["etcheck/checks/plan.py"]
    assert not (ROOT / "etcheck/checks/plann.py").exists()
