"""What a user asks of a mechanism: simulate, steady states (shooting), sweeps (with their
checkpoint, lock and workers), natural frequencies (modes, the Campbell diagram), continuation and
bifurcations (bifurcation/), stability charts (charts/), the range of the theory, stresses, and
the bounds of a run's size."""
