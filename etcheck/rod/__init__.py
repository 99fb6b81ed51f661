"""The dimensionless rod physics (no units, no I/O).

Symbols follow Valverde & van der Heijden, "Magnetically-induced buckling of a
whirling conducting rod" (arXiv:0810.3668; the physics as implemented is in
docs/model.md): P, R, Gamma, B, omega, T, gamma, f.
"""
