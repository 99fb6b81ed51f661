"""The straight tether by Chebyshev collocation (rung 1): spectra along parameter lines,
static pencils (damped critical values), the (B, omega) stability map, resolution studies."""
