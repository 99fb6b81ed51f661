"""Arrays as JSON: a missing (NaN) or unbounded (inf) entry becomes None, never NaN in a report."""

from __future__ import annotations

import numpy as np


def finite_or_none(a) -> list:
    """Nested lists of floats with None wherever ``a`` is not finite (same shape as ``a``)."""
    a = np.asarray(a, dtype=float)
    return np.where(np.isfinite(a), a, None).tolist()
