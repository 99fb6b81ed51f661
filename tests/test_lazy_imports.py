"""Start-up cost: the CLI loads no solver to parse its options, and a JSON-only check loads no report stack.

One fresh interpreter (sys.modules of this test process is shared with every other test).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from etcheck.numerics.blas import BLAS_THREAD_VARIABLES

ROOT = Path(__file__).resolve().parents[1]
#: never needed to check a mission without [orbit] and write its results.json
REPORT_AND_STUDY_STACK = ("matplotlib", "weasyprint", "jinja2", "PIL", "xarray", "dask", "sgp4", "ppigrf",
                          "hypothesis", "pint")

PROBE = """
import json, sys
from etcheck.cli.main import main
at_start = sorted(m for m in ("numpy", "scipy", "astropy") if m in sys.modules)
code = main(["missions/set.toml", "--draft", "--format", "json", "--out", sys.argv[1]])
from etcheck.numerics.blas import _blas
import numpy, scipy._lib.array_api_compat.numpy as clone
from etcheck._numpy_clone import _HOOK
tools = {"numpy_tools": sorted(m for m in ("numpy.f2py", "numpy.testing", "charset_normalizer") if m in sys.modules),
         "numpy_restored": "f2py" in numpy.__all__ and "testing" in dir(numpy), "hook_left": _HOOK in sys.meta_path,
         "clone_works": float(clone.sum(clone.asarray([1.0, 2.0]))) == 3.0}
print(json.dumps(tools | {"at_start": at_start, "code": code, "loaded": sorted({m.split(".")[0] for m in sys.modules}),
                  "scipy_optimize": "scipy.optimize" in sys.modules, "scipy_sparse": "scipy.sparse" in sys.modules,
                  "blas_scanned": _blas() is not None}))
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
    assert not out["scipy_sparse"]  # ARPACK and graph components (0.1 s): no eigenvalues in a damped draft
    assert not out["blas_scanned"]  # BLAS started with one thread: nothing for threadpoolctl to limit
    # scipy's clone of numpy without numpy's developer tools (0.15 s), numpy itself unchanged afterwards
    assert out["numpy_tools"] == [] and out["numpy_restored"] and out["clone_works"] and not out["hook_left"]


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
