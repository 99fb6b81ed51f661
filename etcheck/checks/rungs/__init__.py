"""The rungs' answers for one mission, in the numbers the report shows: rung 0 (static
buckling), rung 1 (the straight tether), rung 1v (current and tension along it),
rungs 2-3 (the buckled and coiled tether)."""
