"""The buckled tether: whirling equilibria (Sec. V A of arXiv:0810.3668), their
symmetries and continuation into branches (rung 2), and the stability of the
coiled states along them (rung 3: spectra, secondary pitchforks, Hopf search,
structure checks, damping maps)."""
