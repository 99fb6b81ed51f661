"""Generic, rod-agnostic numerics (Chebyshev collocation, eigenproblems)."""
