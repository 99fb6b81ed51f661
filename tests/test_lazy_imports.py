"""Start-up cost: the CLI loads no solver to parse its options, and a JSON-only check loads no report stack.

One fresh interpreter (sys.modules of this test process is shared with every other test).
"""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from etcheck.runtime.blas import BLAS_THREAD_VARIABLES

ROOT = Path(__file__).resolve().parents[1]
#: never needed to check a mission without [orbit] and write its results.json
REPORT_AND_STUDY_STACK = ("matplotlib", "weasyprint", "jinja2", "PIL", "xarray", "dask", "sgp4", "ppigrf",
                          "hypothesis", "pint")

PROBE = """
import json, sys
from etcheck.cli.main import main
at_start = sorted(m for m in ("numpy", "scipy", "astropy") if m in sys.modules)
code = main(["missions/set.toml", "--draft", "--format", "json", "--out", sys.argv[1]])
from etcheck.runtime.blas import pinned_by_environment
import numpy, scipy._lib.array_api_compat.numpy as clone
from etcheck.runtime.numpy_clone import installed
tools = {"numpy_tools": sorted(m for m in ("numpy.f2py", "charset_normalizer") if m in sys.modules),
         "numpy_restored": "testing" in dir(numpy) and numpy.__dict__["__dir__"].__name__ != "<lambda>",
         "hook_left": installed(),
         "clone_works": float(clone.sum(clone.asarray([1.0, 2.0]))) == 3.0}
print(json.dumps(tools | {"at_start": at_start, "code": code, "loaded": sorted({m.split(".")[0] for m in sys.modules}),
                  "scipy_optimize": "scipy.optimize" in sys.modules, "scipy_sparse": "scipy.sparse" in sys.modules,
                  "blas_scanned": not pinned_by_environment()}))
"""


def test_a_json_only_draft_check_loads_no_report_stack(tmp_path):
    # without the BLAS thread variables that CI sets: the CLI sets them itself
    env = {k: v for k, v in os.environ.items() if k not in (*BLAS_THREAD_VARIABLES, "OMP_NUM_THREADS")}
    run = subprocess.run([sys.executable, "-c", PROBE, str(tmp_path)], cwd=ROOT, capture_output=True, text=True,
                         timeout=120, env=env)
    assert run.returncode == 0, run.stderr[-2000:]
    out = json.loads(run.stdout.strip().splitlines()[-1])
    assert out["code"] == 0 and (tmp_path / "set" / "results.json").exists()
    assert out["at_start"] == []  # `etcheck --help` and option errors answer before numpy is loaded
    assert "numpy" in out["loaded"]  # the probe saw the check's own imports
    assert [m for m in REPORT_AND_STUDY_STACK if m in out["loaded"]] == []
    assert not out["scipy_optimize"]  # 0.3 s of imports a draft check does not need
    # ARPACK and graph components (0.1 s): no eigenvalues in a damped draft (scipy < 1.16 loads scipy.sparse with
    # scipy.linalg itself)
    assert not out["scipy_sparse"] or _linalg_loads_sparse()
    assert not out["blas_scanned"]  # BLAS started with one thread: nothing for threadpoolctl to limit
    # scipy's clone of numpy without numpy's f2py and its Fortran parser (0.13 s), numpy unchanged afterwards
    assert out["numpy_tools"] == [] and out["numpy_restored"] and out["clone_works"] and not out["hook_left"]


def _linalg_loads_sparse() -> bool:
    run = subprocess.run([sys.executable, "-c", "import sys, scipy.linalg; print('scipy.sparse' in sys.modules)"],
                         capture_output=True, text=True, timeout=120)
    return run.stdout.strip() == "True"


REPORT_PROBE = """
import json, sys
from etcheck.report.background import _warm
_warm(("html",), "check")
print(json.dumps(sorted(m for m in ("astropy", "scipy", "pint") if m in sys.modules)))
"""


def test_the_report_process_of_a_check_loads_no_units_or_solvers():
    # it loads while the check runs, on the other core: astropy.units alone would cost it 0.35 s
    run = subprocess.run([sys.executable, "-c", REPORT_PROBE], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert json.loads(run.stdout.strip().splitlines()[-1]) == []


DIAGRAM_PROBE = """
import json, sys
import numpy as np
from etcheck.report.figures.diagram import smooth
smooth(np.linspace(0.0, 1.0, 7), np.sin(np.linspace(0.0, 3.0, 7)), (1.0, 1.0))
print(json.dumps(sorted(m for m in sys.modules if m == "scipy" or m.startswith("scipy."))))
"""


def test_a_diagram_s_branches_are_drawn_without_scipy():
    # a diagram's report process loads no scipy: scipy.interpolate (for its PCHIP) took it 0.4-1.1 s after the study
    run = subprocess.run([sys.executable, "-c", DIAGRAM_PROBE], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert json.loads(run.stdout.strip().splitlines()[-1]) == []


@pytest.mark.parametrize("fails", [False, True])
def test_the_import_hook_hides_numpys_tools_only_while_the_clone_is_made(tmp_path, monkeypatch, fails):
    import numpy

    from etcheck.runtime import numpy_clone as hook

    before = (list(numpy.__all__), dir(numpy))
    name = f"fake_clone_{int(fails)}"
    (tmp_path / f"{name}.py").write_text(
        "import numpy\n"
        "SEEN = ('f2py' in numpy.__all__, 'testing' in dir(numpy), 'linalg' in dir(numpy))\n"
        + ("raise RuntimeError('the clone failed')\n" if fails else ""))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(hook, "CLONE", name)
    hook.install()
    try:
        if fails:
            with pytest.raises(RuntimeError, match="the clone failed"):
                importlib.import_module(name)
        else:
            assert importlib.import_module(name).SEEN == (False, False, True)
    finally:
        hook.uninstall()
        sys.modules.pop(name, None)
    assert (list(numpy.__all__), dir(numpy)) == before and "testing" in dir(numpy)
    assert not hook.installed()


LOAD_PROBE = """
import json, sys
from etcheck import load_mission
m = load_mission("missions/proseds-orbit.toml")
assert m.orbit is not None
print(json.dumps(sorted(m for m in sys.modules if m.split(".")[0] in ("ppigrf", "pandas", "sgp4")
                        or m.startswith(("astropy.utils.iers", "etcheck.orbit.envelope", "etcheck.orbit.field",
                                         "etcheck.orbit.attitude")))))
"""


def test_loading_an_orbit_mission_only_reads_it():
    # the field over the orbit (IGRF through ppigrf and pandas, SGP4, Earth orientation from IERS tables) is the
    # check's orbit stage: reading the [orbit] table loads none of it
    run = subprocess.run([sys.executable, "-c", LOAD_PROBE], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert json.loads(run.stdout.strip().splitlines()[-1]) == []
