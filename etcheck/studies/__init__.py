"""Studies beyond one check: what-if sweeps, bifurcation diagrams, damping maps, accuracy."""
