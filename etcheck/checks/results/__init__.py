"""The check's results as types: each section and record a frozen dataclass (the sections of page 1 and of the
buckled tether apart), the head every results file shares, and the JSON Schema made from the records."""
