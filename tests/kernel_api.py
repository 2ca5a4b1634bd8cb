"""The element kernels under their physical argument lists, for the kernel tests.

Generated element kernels share one calling convention, (q, qd, qdd, geo, coef, kin) with
geo = (l, x0), coef = the coefficient vector (crankgen.declaration.ingredients.COEFFICIENTS) and kin = the
kinematics vector of crankgen.declaration.schema.KINEMATICS (a, theta, thetad, phi, phid, phidd, thetadd, ...).  The tests compare them with independent quadrature and finite
differences written with physical arguments (l, x0, rhoA, ..., a, theta, ...); these wrappers pack
those arguments into the convention (and cut slider terms to the last node's (u, v), slots END_UV of the 8-slot element vector), nothing
else.
"""

from types import SimpleNamespace

import numpy as np

from reference import END_UV, NDOF
from crankgen.declaration import ingredients, schema
from crankgen._generated import elements as E
from crankgen._generated import energy as _energy

_NAMES = ingredients.COEFFICIENTS


def coef(**values):
    """Coefficient vector(s): the given ones, 0 for the other physical ones, weights 1."""
    parts = [np.asarray(values.get(name, 1.0 if name.startswith("w_") else 0.0), dtype=float)
             for name in _NAMES]
    shape = np.broadcast_shapes(*(p.shape for p in parts))
    return np.stack([np.broadcast_to(p, shape) for p in parts], axis=-1)


def vec(*parts):
    arrays = [np.asarray(p, dtype=float) for p in parts]
    shape = np.broadcast_shapes(*(a.shape for a in arrays))
    return np.stack([np.broadcast_to(a, shape) for a in arrays], axis=-1)


def _kin(a=0.0, theta=0.0, thetad=0.0, phi=0.0, phid=0.0, phidd=0.0, thetadd=0.0):
    """The kinematics vector in the schema's layout (guide co-ordinates beta, ... zero)."""
    values = dict(a=a, theta=theta, thetad=thetad, phi=phi, phid=phid, phidd=phidd, thetadd=thetadd)
    return vec(*(values.get(name, 0.0) for name in schema.KINEMATICS))


def _zeros_like_q(q):
    return np.zeros(np.shape(q))


def _slider_q(qs):
    qs = np.asarray(qs, dtype=float)
    q = np.zeros(qs.shape[:-1] + (NDOF,))
    q[..., END_UV] = qs
    return q


def _rod_inertia(kernel):
    def f(q, qd, qdd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid, phidd, thetadd=0.0):
        return kernel(q, qd, qdd, vec(l, x0), coef(rhoA=rhoA, rhoI=rhoI),
                      _kin(a, theta, thetad, phi, phid, phidd, thetadd))[:4]
    return f


def _slider_inertia(kernel):
    def f(qs, qsd, qsdd, ms, L, a, theta, thetad, phi, phid, phidd, thetadd=0.0):
        out = kernel(_slider_q(qs), _slider_q(qsd), _slider_q(qsdd), vec(L, 0.0), coef(ms=ms),
                     _kin(a, theta, thetad, phi, phid, phidd, thetadd))
        r, K, C, M = out[:4]
        return r[..., END_UV], K[..., END_UV, END_UV], C[..., END_UV, END_UV], M[..., END_UV, END_UV]
    return f


def _elastic(kernel, printed=False):
    def f(q, l, EA, EI):
        z = _zeros_like_q(q)
        out = kernel(q, z, z, vec(l, 0.0), coef(EA=EA, EI=EI), _kin())
        return (out[0], out[1], out[4]) if printed else (out[0], out[1])
    return f


def _kelvin_voigt(kernel):
    def f(q, qd, l, EA, EI, mu):
        out = kernel(q, qd, _zeros_like_q(q), vec(l, 0.0), coef(EA=EA, EI=EI, mu=mu), _kin())
        return out[0], out[1], out[2]
    return f


def _paper_damping(kernel):
    def f(q, qd, l, EA, EI, rhoA, rhoI, phid, mu):
        out = kernel(q, qd, _zeros_like_q(q), vec(l, 0.0), coef(EA=EA, EI=EI, rhoA=rhoA, rhoI=rhoI, mu=mu),
                     _kin(phid=phid))
        return out[0], out[1], out[2]
    return f


def _paper_slider_damping(qsd, ms, phid, mu):
    qd = _slider_q(qsd)
    out = E.slider_dissipation_paper(np.zeros_like(qd), qd, np.zeros_like(qd), vec(1.0, 0.0),
                                     coef(ms=ms, mu=mu), _kin(phid=phid))
    r, K, C = out[:3]
    return r[..., END_UV], K[..., END_UV, END_UV], C[..., END_UV, END_UV]


APPROACHES = ("A", "B", "C")
lagrange = SimpleNamespace(rod_inertia=_rod_inertia(E.inertia_lagrange),
                           slider_inertia=_slider_inertia(E.slider_inertia_lagrange))
paper = SimpleNamespace(rod_inertia=_rod_inertia(E.inertia_paper),
                        slider_inertia=_slider_inertia(E.slider_inertia_paper))
damping = SimpleNamespace(paper_slider=_paper_slider_damping)
for _ap in APPROACHES:
    setattr(lagrange, f"rod_elastic_{_ap}", _elastic(getattr(E, f"elastic_lagrange_{_ap}")))
    setattr(paper, f"rod_elastic_{_ap}", _elastic(getattr(E, f"elastic_paper_{_ap}"), printed=True))
    setattr(damping, f"kelvin_voigt_{_ap}", _kelvin_voigt(getattr(E, f"dissipation_kelvin_voigt_{_ap}")))
    setattr(damping, f"paper_{_ap}", _paper_damping(getattr(E, f"dissipation_paper_{_ap}")))
for _ap in ("A", "B"):
    setattr(lagrange, f"rod_elastic_{_ap}_averaged", _elastic(getattr(E, f"elastic_lagrange_{_ap}_averaged")))
    setattr(damping, f"kelvin_voigt_{_ap}_averaged",
            _kelvin_voigt(getattr(E, f"dissipation_kelvin_voigt_{_ap}_averaged")))


def _rod_T(q, qd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid):
    return _energy.rod_kinetic_energy(q, qd, vec(l, x0), coef(rhoA=rhoA, rhoI=rhoI),
                                      _kin(a, theta, thetad, phi, phid))


def _slider_T(qs, qsd, ms, L, a, theta, thetad, phi, phid):
    return _energy.slider_kinetic_energy(_slider_q(qs), _slider_q(qsd), vec(L, 0.0), coef(ms=ms),
                                         _kin(a, theta, thetad, phi, phid))


def _strain(kernel):
    def f(q, l, EA, EI):
        return kernel(q, _zeros_like_q(q), vec(l, 0.0), coef(EA=EA, EI=EI), _kin())
    return f


def _dissipation(kernel):
    def f(q, qd, l, EA, EI, mu):
        return kernel(q, qd, vec(l, 0.0), coef(EA=EA, EI=EI, mu=mu), _kin())
    return f


energy = SimpleNamespace(rod_kinetic_energy=_rod_T, slider_kinetic_energy=_slider_T)
for _name in dir(_energy):
    if _name.startswith("strain_energy_"):
        setattr(energy, _name, _strain(getattr(_energy, _name)))
    elif _name.startswith("dissipation_"):
        setattr(energy, _name, _dissipation(getattr(_energy, _name)))
