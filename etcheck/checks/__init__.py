"""The check of one mission: plan, one module per rung, margins and results.

Flow: :mod:`.plan` picks the rung and route a scene needs and :mod:`.fidelity` what a
draft leaves out; :mod:`.static_buckling` (rung 0), :mod:`.straight` (rung 1: spectral or
exact determinant), :mod:`.buckled` (rung 2) and :mod:`.coil` (rung 3) answer;
:mod:`.orbit_load` follows the load around the orbit; :mod:`.margins` turns the answers
into margins, :mod:`.validity` states the models' limits, :mod:`.results` stamps the
results; :mod:`.pipeline` runs the flow.
"""
