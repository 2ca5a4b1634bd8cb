"""The declaration as the runtime reads it: the records (data only), the generated schema by name,
the values of parameters and options, cases, mechanisms in crankgen's units and in SI, the unit
system, the selected ingredients of a model, input checks, a motor's torque curve, cross-sections.

Nothing here imports the engine, an analysis, a result or a plot."""
