"""Static equilibria of crankgen's discrete model with the crank at rest (test helper).

With omega = 0 the rigid kinematics are constant and the inertia and damping forces vanish at zero
rates, so an equilibrium is a root of the NumPy reference's residual R(d) (crankgen.discrete.system.Model,
the generated kernels and the guide's end map), found by Newton's method on its tangent
K = dR/dd.  Gravity's forces do not depend on the state, so a load that scales a gravity field,
R(d) + lam G, can itself be the unknown of a displacement-controlled Newton: one DOF prescribed,
the load factor lam found.
"""

import numpy as np

from crankgen.declaration.cases import Case
from crankgen.discrete.system import Model


def _terms(model, d):
    z = np.zeros_like(d)
    terms = model.element_terms(model.kinematics(0.0), d, z, z)
    return model.assembler.vector(terms.r), model.assembler.dense(terms.K)


def equilibrium(model, d0, load=0.0, tol=1e-10, max_iter=50):
    """Newton on R(d) + load = 0 (load: a constant vector, e.g. lam G) from d0 until the step is
    below tol (1 + |d|); returns d."""
    d = np.array(d0, dtype=float)
    for _ in range(max_iter):
        r, K = _terms(model, d)
        step = np.linalg.solve(K, -(r + load))
        d += step
        if np.max(np.abs(step)) < tol * (1 + np.max(np.abs(d))):
            return d
    raise RuntimeError(f"no static equilibrium in {max_iter} Newton iterations")


def gravity_models(gravity, **case):
    """(model without gravity, load vector G = R_with(d) - R_without(d) of the gravity field `gravity`)
    for a case at rest: R(d) + lam G is the residual under lam times that field."""
    base = Model(Case(omega=0.0, **case))
    loaded = Model(Case(omega=0.0, gravity=gravity, **case))
    d = np.zeros(base.n_dofs)
    return base, _terms(loaded, d)[0] - _terms(base, d)[0]


def displacement_control(model, G, dof, value, d0, lam0, tol=1e-10, max_iter=50):
    """Newton on R(d) + lam G = 0 with d[dof] = value: the unknowns are the other DOFs and lam.
    Returns (d, lam)."""
    d = np.array(d0, dtype=float)
    d[dof] = value
    lam = float(lam0)
    free = np.arange(len(d)) != dof
    for _ in range(max_iter):
        r, K = _terms(model, d)
        J = np.column_stack([K[:, free], G])
        step = np.linalg.solve(J, -(r + lam * G))
        d[free] += step[:-1]
        lam += step[-1]
        if np.max(np.abs(step[:-1])) < tol * (1 + np.max(np.abs(d))) and abs(step[-1]) < tol * (1 + abs(lam)):
            return d, lam
    raise RuntimeError(f"no static equilibrium in {max_iter} Newton iterations")
