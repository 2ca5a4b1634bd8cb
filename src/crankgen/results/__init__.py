"""Results and files: the declared outputs of a stored run (and their SI view), per-step tables
and the row of a steady state, sweep tables, CSV cells, atomic writes, provenance stamps."""
