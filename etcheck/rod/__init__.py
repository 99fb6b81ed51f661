"""The dimensionless rod physics (no units, no I/O).

Symbols follow Valverde & van der Heijden, "Magnetically-induced buckling of a
whirling conducting rod": P, R, Gamma, B, omega, T, gamma, f.
"""
