"""The input edge: mission files, physical quantities and sweep axes (astropy units live here)."""
