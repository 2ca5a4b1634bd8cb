"""The discrete system in NumPy: the mesh and its DOF map, the condensation of the constraints,
the rigid kinematics, assembly, the reference `System` (residual and iteration matrix of the
selected kernels), the time schemes and Newton's decisions (shared with the compiled engine), the
reference integrator and the initial elastic state."""
