"""The check of one mission: plan, one module per rung, margins and results.

Flow: :mod:`.plan` picks the rung and route a scene needs and :mod:`.fidelity` what a
draft leaves out; :mod:`.orbit_field` resolves the field of an orbit; the rungs answer
(:mod:`.rungs`: rung 0 static buckling, rung 1 the straight tether, rung 1v with profiles,
rungs 2-3 the buckled tether); :mod:`.margins` turns the answers into margins and studies
their uncertainty; :mod:`.verdict` holds page 1's parts (validity, assumptions, design
limits, flight, the orbit's load); :mod:`.results` types the results; :mod:`.pipeline`
runs the flow.
"""
