"""Keep numpy's developer tools out of scipy's import (start-up time only; no numerical effect).

scipy (1.15 and later) clones numpy's namespace for its array-API layer
(``scipy._lib.array_api_compat.numpy``: ``from numpy import *`` and then
``hasattr`` on every name ``dir(numpy)`` lists). numpy loads its submodules
lazily, so the clone imports ``numpy.f2py`` (its Fortran parser pulls in
charset_normalizer) and ``numpy.testing`` (unittest): ~0.15 s of every cold
etcheck run, measured with ``python -X importtime``, for modules that no
solver uses.

:func:`install` puts a one-shot import hook in front of that one module:
while scipy builds its clone, numpy's ``__all__`` and ``__dir__`` leave out
the developer tools :data:`TOOLS`; both are restored as soon as the clone
exists (also when it fails), and the hook removes itself. The clone then
lacks only ``f2py``, ``testing`` and ``matlib``, which scipy's array-API
layer does not use. Where scipy is already imported, or lays its modules
out otherwise, the hook does nothing.
"""

from __future__ import annotations

import importlib.abc
import importlib.util
import sys

#: scipy's clone of the numpy namespace.
CLONE = "scipy._lib.array_api_compat.numpy"
#: numpy's lazily imported developer tools that the clone would import.
TOOLS = frozenset({"f2py", "testing", "matlib"})


class _Hook(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path, target=None):
        if name != CLONE:
            return None
        uninstall()
        spec = importlib.util.find_spec(name)
        if spec is None or spec.loader is None or not hasattr(spec.loader, "exec_module"):
            return spec
        run = spec.loader.exec_module

        def exec_module(module):
            import numpy

            saved = {key: numpy.__dict__[key] for key in ("__all__", "__dir__") if key in numpy.__dict__}
            if "__all__" in saved:
                numpy.__all__ = [n for n in saved["__all__"] if n not in TOOLS]
            if "__dir__" in saved:
                numpy.__dir__ = lambda: [n for n in saved["__dir__"]() if n not in TOOLS]
            try:
                run(module)
            finally:
                numpy.__dict__.update(saved)

        spec.loader.exec_module = exec_module
        return spec


_HOOK = _Hook()


def install() -> None:
    """Put the hook in front of the import system (once; nothing to do where scipy's clone already exists)."""
    if CLONE not in sys.modules and _HOOK not in sys.meta_path:
        sys.meta_path.insert(0, _HOOK)


def installed() -> bool:
    """Whether the hook waits in front of the import system."""
    return _HOOK in sys.meta_path


def uninstall() -> None:
    """Remove the hook (it removes itself when scipy's clone is imported)."""
    if _HOOK in sys.meta_path:
        sys.meta_path.remove(_HOOK)
