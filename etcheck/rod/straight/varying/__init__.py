"""Rung 1v: the straight tether with a current and a tension that vary along it (graded
multi-domain collocation), where it first loses stability and how."""
