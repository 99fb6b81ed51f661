"""The straight tether (the trivial solution, eq. (86) of arXiv:0810.3668, with the
tension of eq. (25)): closed-form static loads (rung 0), its linear stability by
collocation spectra, static pencils, the exact characteristic determinant and the
undamped determinant in mu = -lambda^2 (rung 1)."""
