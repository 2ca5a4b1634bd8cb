"""The paper's printed matrix form: Appendix B and eqs. (17)-(29), transcribed term by term.

`printed_matrices(corrected=False)` is the text as printed; `corrected=True` corrects the two
transcription problems of the printed text that change numbers (docs/errata.md; B3: rho I phid^2 ->
rho I phid; eq. 29: m_s4 -> d/dt m_s4).
The `paper` formulation of crankgen is the corrected form; the audit compares both with the exact
Lagrange equations of `energies.py`.
"""

from functools import lru_cache

import sympy as sp

from . import symbols as s
from .euler_lagrange import jacobian, total_time_derivative
from .shape_functions import B_PSI, B_U, B_V, N_PSI, N_U, N_V, integrate_element

_NO_COORDS = ()


def _outer(column):
    return column * column.T


def _integrate(matrix):
    return matrix.applyfunc(integrate_element)


def printed_matrices(corrected=True, q=s.q):
    """Matrices and vectors of Appendix B (B1-B9, B13-B16) for one element (a fresh copy of the
    ones derived once per process: every printed variant reads them)."""
    return {k: v.copy() for k, v in _printed_matrices(corrected, tuple(q)).items()}


@lru_cache(maxsize=None)
def _printed_matrices(corrected, q):
    q = sp.Matrix(q)
    x = s.l * s.zeta                      # local co-ordinate inside the element
    sin_tp, cos_tp = sp.sin(s.theta + s.phi), sp.cos(s.theta + s.phi)
    crank = s.a * s.thetad
    translation = _outer(N_U) + _outer(N_V)
    rotary_m3 = s.rhoI * (s.phid if corrected else s.phid**2) * N_PSI

    m = {}
    m["m1"] = _integrate(s.rhoA * translation + s.rhoI * _outer(N_PSI))                       # B1
    m["m2"] = _integrate(s.rhoA * s.phid**2 * translation + s.rhoI * s.phid**2 * _outer(N_PSI))  # B2
    m["m3"] = _integrate(s.rhoA * (crank * cos_tp * N_V - s.phid * s.x0 * N_V - s.phid * x * N_V
                                   - crank * sin_tp * N_U) - rotary_m3)                     # B3
    m["m4"] = _integrate(s.rhoA * (-crank * s.phid * sin_tp * N_V + s.phid**2 * s.x0 * N_U
                                   + s.phid**2 * x * N_U - crank * s.phid * cos_tp * N_U))   # B4
    m["kuu"] = _integrate(s.EA * _outer(B_U))                                               # B5
    m["kpsipsi"] = _integrate(s.EI * _outer(B_PSI))                                         # B6
    axial_force = s.EA * (B_U.T * q)[0, 0]                                                  # B9
    m["kpvv"] = axial_force * _integrate(_outer(B_V))                                       # B7
    slope = (B_V.T * q)[0, 0]
    m["kvvv"] = _integrate(s.EA * slope**2 * _outer(B_V) / 4)                               # B8

    end = {s.zeta: 1}                                                                       # B15-16: xi -> zeta
    nu, nv = N_U.subs(end), N_V.subs(end)
    m["ms1"] = s.ms * (_outer(nu) + _outer(nv))                                             # B13
    m["ms2"] = s.ms * s.phid**2 * (_outer(nu) + _outer(nv))                                 # B14
    m["ms3"] = s.ms * (-crank * s.phid * cos_tp * nu - crank * s.phid * sin_tp * nv
                       + s.phid**2 * s.L * nu)                                              # B15
    m["ms4"] = s.ms * (crank * cos_tp * nv - crank * sin_tp * nu - s.phid * s.L * nv)       # B16
    return {k: v.applyfunc(sp.expand) for k, v in m.items()}


def time_derivative(vector):
    """d/dt of a kinematics-only vector (m3, m_s4)."""
    return vector.applyfunc(lambda e: total_time_derivative(e, _NO_COORDS, _NO_COORDS, _NO_COORDS))


def stiffness_matrices(approach, m):
    """(K_lin without -m2, K_non) of eqs. (22)-(23) for an approach: B drops k_vvv, C also k_pvv."""
    k_lin = m["kuu"] + m["kpsipsi"]
    k_non = sp.zeros(s.ELEMENT_DOFS, s.ELEMENT_DOFS)
    if approach in ("A", "B"):
        k_lin = k_lin + m["kpvv"]
    if approach == "A":
        k_non = 2 * m["kvvv"]
    return k_lin, k_non


def rod_kinetic_residual(m, corrected=True):
    """Inertia part of eq. (20): m1 qdd - m2 q - (m4 - d/dt m3)   (eqs. 21, 22, 25)."""
    m3_rate = time_derivative(m["m3"])
    return (m["m1"] * s.qdd - m["m2"] * s.q - (m["m4"] - m3_rate)).applyfunc(sp.expand)


def rod_elastic_residual(approach, m):
    """Elastic part of eq. (20): (k_uu + k_psipsi + k_pvv + k_non) q, P_i of eq. (B9) as given."""
    k_lin, k_non = stiffness_matrices(approach, m)
    return ((k_lin + k_non) * s.q).applyfunc(sp.expand), (k_lin + k_non).applyfunc(sp.expand)


def rod_damping_residual(approach, m):
    """Damping of eq. (24), as printed: c qd with c = mu (K_lin + K_non), K_lin including -m2."""
    k_lin, k_non = stiffness_matrices(approach, m)
    c = (s.mu * (k_lin - m["m2"] + k_non)).applyfunc(sp.expand)
    return (c * s.qd).applyfunc(sp.expand)


SLIDER_DOFS = s.element_slots(1, ("u", "v"))   # u_{n+1}, v_{n+1} in the last element's nodal vector


def _slider_rows(matrix):
    rows = list(SLIDER_DOFS)
    if matrix.shape[1] == 1:
        return matrix.extract(rows, [0])
    return matrix.extract(rows, rows)


def slider_kinetic_residual(m, corrected=True):
    """Slider part of eqs. (27)-(29): m_s1 qdd - m_s2 q - (m_s3 - d/dt m_s4) on (u, v)_{n+1}.

    As printed, eq. (29) subtracts m_s4 itself; `corrected` uses its time derivative (docs/errata.md).
    """
    ms1, ms2 = _slider_rows(m["ms1"]), _slider_rows(m["ms2"])
    ms3, ms4 = _slider_rows(m["ms3"]), _slider_rows(m["ms4"])
    forcing = ms3 - (time_derivative(ms4) if corrected else ms4)
    return (ms1 * s.qsdd - ms2 * s.qs - forcing).applyfunc(sp.expand)


def slider_damping_residual(m):
    """Slider part of the printed damping: eq. (24) with the K_lin of eq. (28), i.e. -mu m_s2 qd."""
    return (-s.mu * _slider_rows(m["ms2"]) * s.qsd).applyfunc(sp.expand)


def tangents(residual, coords, rates, accels):
    """(K, C, M) = d residual / d(q, qd, qdd)."""
    return jacobian(residual, coords), jacobian(residual, rates), jacobian(residual, accels)
