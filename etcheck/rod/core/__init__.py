"""What every rod model shares: the dimensionless parameters (eqs. (36), (42) of
arXiv:0810.3668), the base state the linearisation sees, the O(delta)
linearisation about it (Sec. V B) and its spectra with two-resolution errors."""
