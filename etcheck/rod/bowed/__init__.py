"""The bowed tether: equilibria under a magnetic field with a component across the chord, where the straight
state is no longer an equilibrium (dimensionless; docs/model.md, section 11)."""
