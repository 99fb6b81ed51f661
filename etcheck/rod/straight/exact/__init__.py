"""The straight tether by its exact characteristic determinant (rung 1x, damped; rung 1u,
undamped in mu = -lambda^2): the kernel, its roots along lines, the isotropic scalar case."""
