"""The check of one mission: plan, one module per rung, margins and results.

Flow: :mod:`.plan` picks the rungs a scene needs; :mod:`.static_buckling` (rung 0),
:mod:`.straight` (rung 1), :mod:`.buckled` (rung 2) and :mod:`.coil` (rung 3) answer;
:mod:`.margins` turns the answers into margins; :mod:`.pipeline` runs the flow.
"""
