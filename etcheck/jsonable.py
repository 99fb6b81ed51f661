"""Numbers and arrays as JSON: a missing (NaN) or unbounded (inf) entry becomes None, never NaN in a report."""

from __future__ import annotations

import math

import numpy as np


def finite_or_none(a) -> list:
    """Nested lists of floats with None wherever ``a`` is not finite (same shape as ``a``)."""
    a = np.asarray(a, dtype=float)
    return np.where(np.isfinite(a), a, None).tolist()


def jsonable(x):
    """``x`` as JSON-able data: arrays as (nested) lists, complex arrays as {"real", "imag"}, numpy scalars as
    Python numbers, non-finite floats as None; tuples, lists and dicts converted item by item."""
    if isinstance(x, np.ndarray):
        if np.iscomplexobj(x):
            return {"real": jsonable(x.real), "imag": jsonable(x.imag)}
        return [jsonable(v) for v in x] if x.ndim > 1 else [None if (isinstance(v, float) and not math.isfinite(v))
                                                             else v for v in x.tolist()]
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.bool_,)):
        return bool(x)
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    return x
