"""Compiled engine: the same model as model.py / newmark.py, compiled with numba for speed.

The generated one-element kernels (emitted by derive/ beside the vectorized ones) are compiled
here: `*_into` (residual and separate tangents K, C, M), and the accumulating `*_newmark_add`
(residual and M + cv C + cd K, the element part of the iteration matrix of eq. 37) and
`*_residual_add` (residual only) used by the Newton iteration.  The element loop, the exact
slider-constraint elimination, the banded assembly, a fixed-bandwidth LU without pivoting (with a
fallback to a banded LU with partial pivoting) and the Newmark/Newton iteration of newmark.py are
compiled around them.  A batch of cases with the same mesh and steps per revolution advances in
lock step on the crank angle (theta_m = 2 pi m / steps_per_rev for every case); each case keeps its
own Newton iteration and status, so a failing case stops alone.  The NumPy implementation in
model.py / newmark.py stays the reference: tests check that both give the same numbers and the
same iteration counts.

Case parameters travel as a float array P[b] = (a, eps, ms, mu, omega, dt) and integer codes
C[b] = (formulation, approach, damping, integrator, membrane, groups_off bit mask).
"""

import math

import numpy as np
from numba import njit, prange

from ._generated import damping as _dmp
from ._generated import groups as _grp
from ._generated import lagrange as _lag
from ._generated import paper as _pap
from ._generated import shape as _shape
from .newmark import SCHEMES

FORMULATION_CODE = {"lagrange": 0, "paper": 1}
APPROACH_CODE = {"A": 0, "B": 1, "C": 2}
DAMPING_CODE = {"paper": 0, "kelvin-voigt": 1}
MEMBRANE_CODE = {"pointwise": 0, "averaged": 1}

# integrator codes, and the constants of the "newton" scheme (newmark.py; numba freezes globals
# into its cached code, so they are written here and a test checks that they equal newmark's)
REFRESH_RATE = 0.1
ESTIMATE_FRACTION = 0.1
HISTORY = 4                 # displacements kept for the starting guess (quartic extrapolation)
INTEGRATOR_CODE = {name: code for code, name in enumerate(SCHEMES)}
NEWTON, ONE_PASS, FULL_NEWTON = (INTEGRATOR_CODE[k] for k in ("newton", "one-pass", "full-newton"))

# status codes of a case
OK, NOT_CONVERGED, SINGULAR, NOT_FINITE = 0, 1, 2, 3
STATUS_TEXT = {OK: "ok", NOT_CONVERGED: "Newton did not converge", SINGULAR: "singular iteration matrix",
               NOT_FINITE: "non-finite state"}

PI4 = math.pi ** 4


def _jit(f):
    return njit(cache=True)(f)


lag_inertia = _jit(_lag.rod_inertia_into)
lag_slider = _jit(_lag.slider_inertia_into)
lag_elastic_A = _jit(_lag.rod_elastic_A_into)
lag_elastic_B = _jit(_lag.rod_elastic_B_into)
lag_elastic_C = _jit(_lag.rod_elastic_C_into)
pap_inertia = _jit(_pap.rod_inertia_into)
pap_slider = _jit(_pap.slider_inertia_into)
pap_elastic_A = _jit(_pap.rod_elastic_A_into)
pap_elastic_B = _jit(_pap.rod_elastic_B_into)
pap_elastic_C = _jit(_pap.rod_elastic_C_into)
kv_A = _jit(_dmp.kelvin_voigt_A_into)
kv_B = _jit(_dmp.kelvin_voigt_B_into)
kv_C = _jit(_dmp.kelvin_voigt_C_into)
pd_A = _jit(_dmp.paper_A_into)
pd_B = _jit(_dmp.paper_B_into)
pd_C = _jit(_dmp.paper_C_into)
pd_slider = _jit(_dmp.paper_slider_into)
lag_elastic_A_avg = _jit(_lag.rod_elastic_A_averaged_into)
lag_elastic_B_avg = _jit(_lag.rod_elastic_B_averaged_into)
kv_A_avg = _jit(_dmp.kelvin_voigt_A_averaged_into)
kv_B_avg = _jit(_dmp.kelvin_voigt_B_averaged_into)

# accumulating variants for the Newton iteration: *_nm adds (r, M + cv C + cd K), *_res adds r
def _accumulating(module, name):
    return _jit(getattr(module, name + "_newmark_add")), _jit(getattr(module, name + "_residual_add"))


lag_inertia_nm, lag_inertia_res = _accumulating(_lag, "rod_inertia")
pap_inertia_nm, pap_inertia_res = _accumulating(_pap, "rod_inertia")
lag_el_A_nm, lag_el_A_res = _accumulating(_lag, "rod_elastic_A")
lag_el_B_nm, lag_el_B_res = _accumulating(_lag, "rod_elastic_B")
lag_el_C_nm, lag_el_C_res = _accumulating(_lag, "rod_elastic_C")
lag_el_Aa_nm, lag_el_Aa_res = _accumulating(_lag, "rod_elastic_A_averaged")
lag_el_Ba_nm, lag_el_Ba_res = _accumulating(_lag, "rod_elastic_B_averaged")
pap_el_A_nm, pap_el_A_res = _accumulating(_pap, "rod_elastic_A")
pap_el_B_nm, pap_el_B_res = _accumulating(_pap, "rod_elastic_B")
pap_el_C_nm, pap_el_C_res = _accumulating(_pap, "rod_elastic_C")
kv_A_nm, kv_A_res = _accumulating(_dmp, "kelvin_voigt_A")
kv_B_nm, kv_B_res = _accumulating(_dmp, "kelvin_voigt_B")
kv_C_nm, kv_C_res = _accumulating(_dmp, "kelvin_voigt_C")
kv_Aa_nm, kv_Aa_res = _accumulating(_dmp, "kelvin_voigt_A_averaged")
kv_Ba_nm, kv_Ba_res = _accumulating(_dmp, "kelvin_voigt_B_averaged")
pd_A_nm, pd_A_res = _accumulating(_dmp, "paper_A")
pd_B_nm, pd_B_res = _accumulating(_dmp, "paper_B")
pd_C_nm, pd_C_res = _accumulating(_dmp, "paper_C")
lag_slider_res = _jit(_lag.slider_inertia_residual_add)
pap_slider_res = _jit(_pap.slider_inertia_residual_add)
pd_slider_res = _jit(_dmp.paper_slider_residual_add)

# Term groups that the audit can switch off (consistent model, approach A): bit i of codes[5].
SWITCHABLE_GROUPS = ("gyroscopic", "phidd", "centrifugal", "cubic_axial", "cubic_transverse", "quartic")
g_rod_gyro = _jit(_grp.rod_inertia__gyroscopic_into)
g_rod_phidd = _jit(_grp.rod_inertia__phidd_into)
g_rod_cent = _jit(_grp.rod_inertia__centrifugal_into)
g_sl_gyro = _jit(_grp.slider_inertia__gyroscopic_into)
g_sl_phidd = _jit(_grp.slider_inertia__phidd_into)
g_sl_cent = _jit(_grp.slider_inertia__centrifugal_into)
g_el_cax = _jit(_grp.rod_elastic_A__cubic_axial_into)
g_el_ctr = _jit(_grp.rod_elastic_A__cubic_transverse_into)
g_el_qua = _jit(_grp.rod_elastic_A__quartic_into)
g_ela_cax = _jit(_grp.rod_elastic_A_averaged__cubic_axial_into)
g_ela_ctr = _jit(_grp.rod_elastic_A_averaged__cubic_transverse_into)
g_ela_qua = _jit(_grp.rod_elastic_A_averaged__quartic_into)


# ----------------------------------------------------------------------------------------------
# kinematics and element terms
# ----------------------------------------------------------------------------------------------

@njit(cache=True)
def crank_kinematics(a, omega, t, out):
    """theta, thetad, phi, phid, phidd at time t (see kinematics.py)."""
    theta = omega * t
    sp = a * math.sin(theta)
    cp = math.sqrt(1.0 - sp * sp)
    phid = a * omega * math.cos(theta) / cp
    out[0] = theta
    out[1] = omega
    out[2] = math.asin(sp)
    out[3] = phid
    out[4] = -a * omega * omega * math.sin(theta) / cp + phid * phid * sp / cp


@njit(cache=True)
def _rod_terms(form, app, damp, secant, avg, q, qd, qdd, l, x0, rhoA, rhoI, EA, EI, mu, a, kin,
               r, K, C, M, w6, w66a, w66b, w66c, w66d):
    """Residual and tangents of one rod element: inertia + elastic + damping."""
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    if form == 0:
        lag_inertia(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, r, K, C, M)
        if app == 0 and avg:
            lag_elastic_A_avg(q, l, EA, EI, w6, w66a)
        elif app == 1 and avg:
            lag_elastic_B_avg(q, l, EA, EI, w6, w66a)
        elif app == 0:
            lag_elastic_A(q, l, EA, EI, w6, w66a)
        elif app == 1:
            lag_elastic_B(q, l, EA, EI, w6, w66a)
        else:
            lag_elastic_C(q, l, EA, EI, w6, w66a)
    else:
        pap_inertia(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, r, K, C, M)
        if app == 0:
            pap_elastic_A(q, l, EA, EI, w6, w66d, w66a)
        elif app == 1:
            pap_elastic_B(q, l, EA, EI, w6, w66d, w66a)
        else:
            pap_elastic_C(q, l, EA, EI, w6, w66d, w66a)
        if not secant:
            for i in range(6):
                for j in range(6):
                    w66a[i, j] = w66d[i, j]
    for i in range(6):
        r[i] += w6[i]
        for j in range(6):
            K[i, j] += w66a[i, j]
    # damping: w6 = r_d, w66b = K_d, w66c = C_d
    if damp == 1:
        if app == 0 and avg:
            kv_A_avg(q, qd, l, EA, EI, mu, w6, w66b, w66c)
        elif app == 1 and avg:
            kv_B_avg(q, qd, l, EA, EI, mu, w6, w66b, w66c)
        elif app == 0:
            kv_A(q, qd, l, EA, EI, mu, w6, w66b, w66c)
        elif app == 1:
            kv_B(q, qd, l, EA, EI, mu, w6, w66b, w66c)
        else:
            kv_C(q, qd, l, EA, EI, mu, w6, w66b, w66c)
    else:
        if app == 0:
            pd_A(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, w6, w66b, w66c)
        elif app == 1:
            pd_B(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, w6, w66b, w66c)
        else:
            pd_C(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, w6, w66b, w66c)
    for i in range(6):
        r[i] += w6[i]
        for j in range(6):
            C[i, j] += w66c[i, j]
            if not secant:
                K[i, j] += w66b[i, j]


@njit(cache=True)
def _rod_newmark(form, app, damp, avg, q, qd, qdd, l, x0, rhoA, rhoI, EA, EI, mu, a, kin, cv, cd, r, S):
    """r = r_e and S = M_e + cv C_e + cd K_e of one rod element (inertia + elastic + damping)
    from the accumulating kernels: the element part of the iteration matrix of eq. (37)."""
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    r[:] = 0.0
    S[:, :] = 0.0
    if form == 0:
        lag_inertia_nm(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, cv, cd, r, S)
        if app == 0 and avg:
            lag_el_Aa_nm(q, l, EA, EI, cv, cd, r, S)
        elif app == 1 and avg:
            lag_el_Ba_nm(q, l, EA, EI, cv, cd, r, S)
        elif app == 0:
            lag_el_A_nm(q, l, EA, EI, cv, cd, r, S)
        elif app == 1:
            lag_el_B_nm(q, l, EA, EI, cv, cd, r, S)
        else:
            lag_el_C_nm(q, l, EA, EI, cv, cd, r, S)
    else:
        pap_inertia_nm(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, cv, cd, r, S)
        if app == 0:
            pap_el_A_nm(q, l, EA, EI, cv, cd, r, S)
        elif app == 1:
            pap_el_B_nm(q, l, EA, EI, cv, cd, r, S)
        else:
            pap_el_C_nm(q, l, EA, EI, cv, cd, r, S)
    if damp == 1:
        if app == 0 and avg:
            kv_Aa_nm(q, qd, l, EA, EI, mu, cv, cd, r, S)
        elif app == 1 and avg:
            kv_Ba_nm(q, qd, l, EA, EI, mu, cv, cd, r, S)
        elif app == 0:
            kv_A_nm(q, qd, l, EA, EI, mu, cv, cd, r, S)
        elif app == 1:
            kv_B_nm(q, qd, l, EA, EI, mu, cv, cd, r, S)
        else:
            kv_C_nm(q, qd, l, EA, EI, mu, cv, cd, r, S)
    else:
        if app == 0:
            pd_A_nm(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, cv, cd, r, S)
        elif app == 1:
            pd_B_nm(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, cv, cd, r, S)
        else:
            pd_C_nm(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, cv, cd, r, S)


@njit(cache=True)
def _rod_residual(form, app, damp, avg, q, qd, qdd, l, x0, rhoA, rhoI, EA, EI, mu, a, kin, r):
    """r = r_e of one rod element (inertia + elastic + damping), no tangents."""
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    r[:] = 0.0
    if form == 0:
        lag_inertia_res(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, r)
        if app == 0 and avg:
            lag_el_Aa_res(q, l, EA, EI, r)
        elif app == 1 and avg:
            lag_el_Ba_res(q, l, EA, EI, r)
        elif app == 0:
            lag_el_A_res(q, l, EA, EI, r)
        elif app == 1:
            lag_el_B_res(q, l, EA, EI, r)
        else:
            lag_el_C_res(q, l, EA, EI, r)
    else:
        pap_inertia_res(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, r)
        if app == 0:
            pap_el_A_res(q, l, EA, EI, r)
        elif app == 1:
            pap_el_B_res(q, l, EA, EI, r)
        else:
            pap_el_C_res(q, l, EA, EI, r)
    if damp == 1:
        if app == 0 and avg:
            kv_Aa_res(q, qd, l, EA, EI, mu, r)
        elif app == 1 and avg:
            kv_Ba_res(q, qd, l, EA, EI, mu, r)
        elif app == 0:
            kv_A_res(q, qd, l, EA, EI, mu, r)
        elif app == 1:
            kv_B_res(q, qd, l, EA, EI, mu, r)
        else:
            kv_C_res(q, qd, l, EA, EI, mu, r)
    else:
        if app == 0:
            pd_A_res(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, r)
        elif app == 1:
            pd_B_res(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, r)
        else:
            pd_C_res(q, qd, l, EA, EI, rhoA, rhoI, phd, mu, r)


@njit(cache=True)
def _slider_terms(form, us, usd, usdd, ms, a, kin, r, K, C, M, w2, w22a, w22b, w22c):
    """Slider residual and tangents on (u, v) of the last node, added into the last element."""
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    if form == 0:
        lag_slider(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2, w22a, w22b, w22c)
    else:
        pap_slider(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2, w22a, w22b, w22c)
    for i in range(2):
        r[3 + i] += w2[i]
        for j in range(2):
            K[3 + i, 3 + j] += w22a[i, j]
            C[3 + i, 3 + j] += w22b[i, j]
            M[3 + i, 3 + j] += w22c[i, j]


@njit(cache=True)
def _slider_residual(form, damp, us, usd, usdd, ms, mu, a, kin, r, w2):
    """Slider residual (inertia, and the printed damping if damp == 0) added into the last element,
    which is then projected by the slider map: r <- T^T r (see _project_last)."""
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    w2[0] = 0.0
    w2[1] = 0.0
    if form == 0:
        lag_slider_res(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2)
    else:
        pap_slider_res(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2)
    if damp == 0:
        pd_slider_res(usd, ms, phd, mu, w2)
    r[3] += w2[0]
    r[4] += w2[1]
    _project_residual(math.cos(ph), math.sin(ph), r)


@njit(cache=True)
def _subtract(r, K, C, M, w6, wK, wC, wM, with_rates, with_accels, offset, size):
    for i in range(size):
        r[offset + i] -= w6[i]
        for j in range(size):
            K[offset + i, offset + j] -= wK[i, j]
            if with_rates:
                C[offset + i, offset + j] -= wC[i, j]
            if with_accels:
                M[offset + i, offset + j] -= wM[i, j]


@njit(cache=True)
def _rod_groups_off(mask, avg, q, qd, qdd, l, x0, rhoA, rhoI, EA, EI, a, kin, r, K, C, M,
                    w6, wK, wC, wM):
    """Remove the switched-off groups (bit mask, SWITCHABLE_GROUPS order) from a rod element."""
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    if mask & 1:
        g_rod_gyro(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, w6, wK, wC, wM)
        _subtract(r, K, C, M, w6, wK, wC, wM, True, True, 0, 6)
    if mask & 2:
        g_rod_phidd(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, w6, wK, wC, wM)
        _subtract(r, K, C, M, w6, wK, wC, wM, True, True, 0, 6)
    if mask & 4:
        g_rod_cent(q, qd, qdd, l, x0, rhoA, rhoI, a, th, thd, ph, phd, phdd, w6, wK, wC, wM)
        _subtract(r, K, C, M, w6, wK, wC, wM, True, True, 0, 6)
    if mask & 8:
        if avg:
            g_ela_cax(q, l, EA, EI, w6, wK)
        else:
            g_el_cax(q, l, EA, EI, w6, wK)
        _subtract(r, K, C, M, w6, wK, wC, wM, False, False, 0, 6)
    if mask & 16:
        if avg:
            g_ela_ctr(q, l, EA, EI, w6, wK)
        else:
            g_el_ctr(q, l, EA, EI, w6, wK)
        _subtract(r, K, C, M, w6, wK, wC, wM, False, False, 0, 6)
    if mask & 32:
        if avg:
            g_ela_qua(q, l, EA, EI, w6, wK)
        else:
            g_el_qua(q, l, EA, EI, w6, wK)
        _subtract(r, K, C, M, w6, wK, wC, wM, False, False, 0, 6)


@njit(cache=True)
def _slider_groups_off(mask, us, usd, usdd, ms, a, kin, r, K, C, M, w2, wK, wC, wM):
    th, thd, ph, phd, phdd = kin[0], kin[1], kin[2], kin[3], kin[4]
    if mask & 1:
        g_sl_gyro(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2, wK, wC, wM)
        _subtract(r, K, C, M, w2, wK, wC, wM, True, True, 3, 2)
    if mask & 2:
        g_sl_phidd(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2, wK, wC, wM)
        _subtract(r, K, C, M, w2, wK, wC, wM, True, True, 3, 2)
    if mask & 4:
        g_sl_cent(us, usd, usdd, ms, 1.0, a, th, thd, ph, phd, phdd, w2, wK, wC, wM)
        _subtract(r, K, C, M, w2, wK, wC, wM, True, True, 3, 2)


@njit(cache=True)
def _slider_damping(usd, ms, phd, mu, r, C, w2, w22a, w22b):
    pd_slider(usd, ms, phd, mu, w2, w22a, w22b)
    for i in range(2):
        r[3 + i] += w2[i]
        for j in range(2):
            C[3 + i, 3 + j] += w22b[i, j]


@njit(cache=True)
def _project_last(kin, r, K, C, M):
    """The slider map of the last element, q = T p with T = I except T[3, 3] = cos phi,
    T[4, 3] = sin phi, T[4, 4] = 0 (constraints.py):
        r <- T^T r,  M <- T^T M T,  C <- T^T (C T + 2 M Td),  K <- T^T (K T + C Td + M Tdd),
    written out for the two non-trivial columns and rows of T, Td and Tdd."""
    ph, phd, phdd = kin[2], kin[3], kin[4]
    c, s = math.cos(ph), math.sin(ph)
    td3, td4 = -s * phd, c * phd                                   # Td[3, 3], Td[4, 3]
    tdd3, tdd4 = -c * phd * phd - s * phdd, -s * phd * phd + c * phdd   # Tdd[3, 3], Tdd[4, 3]
    for i in range(6):                  # right factors: only column 3 changes, column 4 vanishes
        k3, k4, c3, c4, m3, m4 = K[i, 3], K[i, 4], C[i, 3], C[i, 4], M[i, 3], M[i, 4]
        K[i, 3] = c * k3 + s * k4 + td3 * c3 + td4 * c4 + tdd3 * m3 + tdd4 * m4
        C[i, 3] = c * c3 + s * c4 + 2.0 * (td3 * m3 + td4 * m4)
        M[i, 3] = c * m3 + s * m4
        K[i, 4] = 0.0
        C[i, 4] = 0.0
        M[i, 4] = 0.0
    for j in range(6):                  # T^T from the left: row 3 combines rows 3 and 4
        K[3, j] = c * K[3, j] + s * K[4, j]
        C[3, j] = c * C[3, j] + s * C[4, j]
        M[3, j] = c * M[3, j] + s * M[4, j]
        K[4, j] = 0.0
        C[4, j] = 0.0
        M[4, j] = 0.0
    _project_residual(c, s, r)


@njit(cache=True)
def _project_residual(c, s, r):
    """r <- T^T r of the slider map (c, s = cos phi, sin phi): see _project_last."""
    r[3] = c * r[3] + s * r[4]
    r[4] = 0.0


TERMS_FULL, TERMS_NEWMARK, TERMS_RESIDUAL = 0, 1, 2


@njit(cache=True)
def element_terms(codes, par, secant, dofs, l, d, v, acc, kin, rE, KE, CE, ME, ws):
    """All element residuals and tangents of one case (constraint applied) into rE, KE, CE, ME.
    ws is a workspace tuple of small arrays."""
    _element_loop(TERMS_FULL, codes, par, secant, dofs, l, d, v, acc, kin, 0.0, 0.0,
                  rE, KE, CE, ME, KE, ws)


@njit(cache=True)
def element_newmark(codes, par, secant, dofs, l, d, v, acc, kin, cv, cd, rE, SE, KE, CE, ME, ws):
    """Element residuals rE and iteration matrices SE = M + cv C + cd K (eq. 37) of one case.
    Interior elements use the accumulating kernels; the last element (slider map) and cases with
    switched-off groups or the printed secant matrix go through the full terms (KE, CE, ME: scratch)."""
    _element_loop(TERMS_NEWMARK, codes, par, secant, dofs, l, d, v, acc, kin, cv, cd,
                  rE, KE, CE, ME, SE, ws)


@njit(cache=True)
def element_residual(codes, par, dofs, l, d, v, acc, kin, rE, KE, CE, ME, ws):
    """Element residuals rE of one case, without tangents (KE, CE, ME: scratch)."""
    _element_loop(TERMS_RESIDUAL, codes, par, False, dofs, l, d, v, acc, kin, 0.0, 0.0,
                  rE, KE, CE, ME, KE, ws)


@njit(cache=True)
def _element_loop(mode, codes, par, secant, dofs, l, d, v, acc, kin, cv, cd, rE, KE, CE, ME, SE, ws):
    (q, qd, qdd, w6, w66a, w66b, w66c, w66d, w2, w22a, w22b, w22c) = ws
    form, app, damp = codes[0], codes[1], codes[2]
    avg = codes[4] == 1
    a, eps, ms, mu = par[0], par[1], par[2], par[3]
    rhoA, rhoI, EA, EI = 1.0, eps * eps, 1.0 / (PI4 * eps * eps), 1.0 / PI4
    n = dofs.shape[0]
    N = d.shape[0]
    ph, phd, phdd = kin[2], kin[3], kin[4]
    c, s = math.cos(ph), math.sin(ph)
    fast = codes[5] == 0 and not secant
    for e in range(n):
        for k in range(6):
            idx = dofs[e, k]
            if idx < N:
                q[k] = d[idx]
                qd[k] = v[idx]
                qdd[k] = acc[idx]
            else:
                q[k] = 0.0
                qd[k] = 0.0
                qdd[k] = 0.0
        last = e == n - 1
        if last:
            p, pd, pdd = q[3], qd[3], qdd[3]
            q[3] = c * p
            q[4] = s * p
            qd[3] = c * pd - s * phd * p
            qd[4] = s * pd + c * phd * p
            qdd[3] = c * pdd - 2.0 * s * phd * pd - (c * phd * phd + s * phdd) * p
            qdd[4] = s * pdd + 2.0 * c * phd * pd + (-s * phd * phd + c * phdd) * p
        elif fast and mode == TERMS_NEWMARK:
            _rod_newmark(form, app, damp, avg, q, qd, qdd, l, e * l, rhoA, rhoI, EA, EI, mu, a, kin,
                         cv, cd, rE[e], SE[e])
            continue
        if fast and mode == TERMS_RESIDUAL:
            _rod_residual(form, app, damp, avg, q, qd, qdd, l, e * l, rhoA, rhoI, EA, EI, mu, a, kin,
                          rE[e])
            if last:
                _slider_residual(form, damp, q[3:5], qd[3:5], qdd[3:5], ms, mu, a, kin, rE[e], w2)
            continue
        _rod_terms(form, app, damp, secant, avg, q, qd, qdd, l, e * l, rhoA, rhoI, EA, EI, mu, a, kin,
                   rE[e], KE[e], CE[e], ME[e], w6, w66a, w66b, w66c, w66d)
        if codes[5] != 0:
            _rod_groups_off(codes[5], avg, q, qd, qdd, l, e * l, rhoA, rhoI, EA, EI, a, kin,
                            rE[e], KE[e], CE[e], ME[e], w6, w66a, w66b, w66c)
        if last:
            _slider_terms(form, q[3:5], qd[3:5], qdd[3:5], ms, a, kin, rE[e], KE[e], CE[e],
                          ME[e], w2, w22a, w22b, w22c)
            if codes[5] != 0:
                _slider_groups_off(codes[5], q[3:5], qd[3:5], qdd[3:5], ms, a, kin, rE[e], KE[e],
                                   CE[e], ME[e], w2, w22a, w22b, w22c)
            if damp == 0:
                _slider_damping(qd[3:5], ms, phd, mu, rE[e], CE[e], w2, w22a, w22b)
            _project_last(kin, rE[e], KE[e], CE[e], ME[e])
        if mode == TERMS_NEWMARK:
            for i in range(6):
                for j in range(6):
                    SE[e, i, j] = ME[e, i, j] + cv * CE[e, i, j] + cd * KE[e, i, j]


# ----------------------------------------------------------------------------------------------
# assembly and banded solver
# ----------------------------------------------------------------------------------------------

@njit(cache=True)
def assemble_vector(dofs, rE, out):
    out[:] = 0.0
    N = out.shape[0]
    for e in range(dofs.shape[0]):
        for i in range(6):
            gi = dofs[e, i]
            if gi < N:
                out[gi] += rE[e, i]


@njit(cache=True)
def assemble_band(dofs, kb, ME, CE, KE, cm, cv, cd, W):
    """W[i, j - i + kb] += cm M + cv C + cd K (row band storage, width 3 kb + 1 for pivoting fill)."""
    W[:, :] = 0.0
    N = W.shape[0]
    for e in range(dofs.shape[0]):
        for i in range(6):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(6):
                gj = dofs[e, j]
                if gj >= N:
                    continue
                W[gi, gj - gi + kb] += cm * ME[e, i, j] + cv * CE[e, i, j] + cd * KE[e, i, j]


@njit(cache=True)
def assemble_band_newmark(dofs, kb, SE, W):
    """W[i, j - i + kb] += S_e[i, j]: the iteration matrix from element matrices SE (row band storage)."""
    W[:, :] = 0.0
    N = W.shape[0]
    for e in range(dofs.shape[0]):
        for i in range(6):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(6):
                gj = dofs[e, j]
                if gj < N:
                    W[gi, gj - gi + kb] += SE[e, i, j]


@njit(cache=True)
def band_factor(W, kb, piv, ext):
    """LU factorization with partial pivoting of the band matrix in row band storage W (N, 3 kb + 1),
    in place, like LAPACK gbtrf: U on and above the diagonal (upper bandwidth up to 2 kb after row
    interchanges), the multipliers of column k below it, piv[k] the row swapped with row k, ext[i]
    the last column of row i of U that can be non-zero.  Returns False if a pivot is zero."""
    N = W.shape[0]
    for i in range(N):
        ext[i] = min(N - 1, i + kb)
    for k in range(N):
        imax = min(N - 1, k + kb)
        p = k
        best = abs(W[k, kb])
        for i in range(k + 1, imax + 1):
            val = abs(W[i, k - i + kb])
            if val > best:
                best = val
                p = i
        if best == 0.0 or not np.isfinite(best):
            return False
        piv[k] = p
        if p != k:
            jmax = max(ext[k], ext[p])
            for j in range(k, jmax + 1):
                tmp = W[k, j - k + kb]
                W[k, j - k + kb] = W[p, j - p + kb]
                W[p, j - p + kb] = tmp
            ext[k], ext[p] = jmax, jmax
        jmax = ext[k]
        inv = 1.0 / W[k, kb]
        for i in range(k + 1, imax + 1):
            f = W[i, k - i + kb] * inv
            W[i, k - i + kb] = f
            if f == 0.0:
                continue
            oi = kb - i
            ok = kb - k
            for j in range(k + 1, jmax + 1):
                W[i, j + oi] -= f * W[k, j + ok]
            if jmax > ext[i]:
                ext[i] = jmax
    return True


@njit(cache=True)
def band_lu_solve(W, kb, piv, ext, B):
    """Solve A X = B in place (B: (N, m)) with the factors of band_factor."""
    N = W.shape[0]
    m = B.shape[1]
    for k in range(N):
        p = piv[k]
        if p != k:
            for c in range(m):
                tmp = B[k, c]
                B[k, c] = B[p, c]
                B[p, c] = tmp
        for i in range(k + 1, min(N - 1, k + kb) + 1):
            f = W[i, k - i + kb]
            if f != 0.0:
                for c in range(m):
                    B[i, c] -= f * B[k, c]
    for i in range(N - 1, -1, -1):
        inv = 1.0 / W[i, kb]
        for c in range(m):
            s = B[i, c]
            for j in range(i + 1, ext[i] + 1):
                s -= W[i, j - i + kb] * B[j, c]
            B[i, c] = s * inv


@njit(cache=True)
def band_solve(W, kb, B):
    """Solve A X = B in place (B: (N, m)); A in row band storage W (N, 3 kb + 1), overwritten by its
    LU factors.  Returns False if a pivot is zero."""
    N = W.shape[0]
    piv = np.empty(N, dtype=np.int64)
    ext = np.empty(N, dtype=np.int64)
    if not band_factor(W, kb, piv, ext):
        return False
    band_lu_solve(W, kb, piv, ext, B)
    return True


# Iteration matrices have a positive definite symmetric part (mass + beta dt^2 stiffness +
# gamma dt damping, with skew gyroscopic terms), for which LU without pivoting is stable.  With the
# element DOFs on consecutive indices the bandwidth is 5 (n_elements >= 2), and a fixed-width,
# padded LU without pivoting is several times faster than the general pivoted one.  It is used
# when every pivot keeps at least PIVOT_RATIO of its (non-zero) original diagonal entry and no
# multiplier exceeds MAX_MULTIPLIER (no large element growth); otherwise the step falls back to
# band_factor (partial pivoting).  The converged state does not depend on it: the residual is exact,
# the factorization only steers the iteration.
KB_FIXED = 5
PIVOT_RATIO = 1e-6
MAX_MULTIPLIER = 1e3


@njit(cache=True)
def assemble_fixed(dofs, SE, F, N):
    """F[i, j - i + 5] = A[i, j] (F: (N + 5, 11)); rows N.. are identity padding."""
    F[:, :] = 0.0
    for i in range(N, F.shape[0]):
        F[i, KB_FIXED] = 1.0
    for e in range(dofs.shape[0]):
        for i in range(6):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(6):
                gj = dofs[e, j]
                if gj < N:
                    F[gi, gj - gi + KB_FIXED] += SE[e, i, j]


@njit(cache=True)
def factor_fixed(F, N, diag):
    """In-place LU without pivoting of the padded bandwidth-5 matrix F (assemble_fixed).  Returns
    False (F then unusable) if a diagonal entry is zero, a pivot falls below PIVOT_RATIO times its
    diagonal entry or a multiplier exceeds MAX_MULTIPLIER."""
    for k in range(N):
        diag[k] = abs(F[k, KB_FIXED])
    for k in range(N):
        pivot = F[k, KB_FIXED]
        if not (abs(pivot) > PIVOT_RATIO * diag[k] and diag[k] > 0.0) or not np.isfinite(pivot):
            return False
        inv = 1.0 / pivot
        for ii in range(1, KB_FIXED + 1):
            i = k + ii
            o = KB_FIXED - ii
            f = F[i, o] * inv
            if abs(f) > MAX_MULTIPLIER:
                return False
            F[i, o] = f
            for j in range(1, KB_FIXED + 1):
                F[i, o + j] -= f * F[k, KB_FIXED + j]
    return True


@njit(cache=True)
def solve_fixed(F, N, b):
    """Solve with the factors of factor_fixed; b: (N + 5,) right-hand side, overwritten."""
    for i in range(N, b.shape[0]):
        b[i] = 0.0
    for k in range(N):
        bk = b[k]
        for ii in range(1, KB_FIXED + 1):
            b[k + ii] -= F[k + ii, KB_FIXED - ii] * bk
    for i in range(N - 1, -1, -1):
        s = b[i]
        for j in range(1, KB_FIXED + 1):
            s -= F[i, KB_FIXED + j] * b[i + j]
        b[i] = s / F[i, KB_FIXED]


@njit(cache=True)
def band_matmul(dofs, kb, XE, X, out):
    """out = A X for A assembled from element matrices XE (no band storage needed), X: (N, m)."""
    out[:, :] = 0.0
    N = X.shape[0]
    m = X.shape[1]
    for e in range(dofs.shape[0]):
        for i in range(6):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(6):
                gj = dofs[e, j]
                if gj >= N:
                    continue
                aij = XE[e, i, j]
                if aij != 0.0:
                    for c in range(m):
                        out[gi, c] += aij * X[gj, c]


# ----------------------------------------------------------------------------------------------
# Newmark
# ----------------------------------------------------------------------------------------------

@njit(cache=True)
def _make_ws():
    """Workspace of element_terms: q, qd, qdd, four 6-vectors/6x6 scratch blocks, slider scratch."""
    return (np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6), np.zeros((6, 6)), np.zeros((6, 6)),
            np.zeros((6, 6)), np.zeros((6, 6)), np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2)),
            np.zeros((2, 2)))


@njit(cache=True)
def initial_acceleration(codes, par, dofs, kb, l, t0, d, v, out):
    """Solve R(t0, d, v, a) = 0 for a (eq. 34; R is linear in a).  Returns False if singular."""
    n = dofs.shape[0]
    N = d.shape[0]
    ws = _make_ws()
    rE, KE, CE, ME = np.zeros((n, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6))
    kin = np.zeros(5)
    crank_kinematics(par[0], par[4], t0, kin)
    zero = np.zeros(N)
    element_terms(codes, par, False, dofs, l, d, v, zero, kin, rE, KE, CE, ME, ws)
    R = np.zeros(N)
    assemble_vector(dofs, rE, R)
    W = np.zeros((N, 3 * kb + 1))
    assemble_band(dofs, kb, ME, CE, KE, 1.0, 0.0, 0.0, W)
    rhs = np.zeros((N, 1))
    for i in range(N):
        rhs[i, 0] = -R[i]
    ok = band_solve(W, kb, rhs)
    for i in range(N):
        out[i] = rhs[i, 0]
    return ok


@njit(cache=True)
def newmark_step(codes, par, dofs, kb, l, scales, beta, gamma, tol, max_iter, t_new,
                 d, v, acc, hist, n_prev, d_new, v_new, a_new, rE, SE, KE, CE, ME, R, W, piv, ext,
                 F, diag, rhs, kin, ws):
    """One Newmark step from (d, v, acc) to (d_new, v_new, a_new) at t_new (scheme codes[3], see
    newmark.py: 0 newton, 1 one-pass, 2 full-newton).  hist[k]: the displacements k + 1 steps
    before d, of which the first n_prev (0 to HISTORY) are known, for the starting guess.
    W, piv, ext / F, diag: storage of the pivoted and of the fixed-bandwidth factorization;
    rhs: (N + 5, 1).  Returns (status, iterations, residual norm)."""
    N = d.shape[0]
    dt = par[5]
    scheme = codes[3]
    one_pass = scheme == ONE_PASS
    secant = one_pass and codes[0] == 1
    cd = beta * dt * dt
    cv = gamma * dt
    crank_kinematics(par[0], par[4], t_new, kin)
    for i in range(N):
        if one_pass:
            a_new[i] = 0.0
        elif n_prev == 0:
            a_new[i] = acc[i]
        else:
            dp = d[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * acc[i]
            if n_prev == 1:                 # newmark.extrapolate, same order of operations
                dx = -hist[0, i] + 2.0 * d[i]
            elif n_prev == 2:
                dx = hist[1, i] - 3.0 * hist[0, i] + 3.0 * d[i]
            elif n_prev == 3:
                dx = -hist[2, i] + 4.0 * hist[1, i] - 6.0 * hist[0, i] + 4.0 * d[i]
            else:
                dx = hist[3, i] - 5.0 * hist[2, i] + 10.0 * hist[1, i] - 10.0 * hist[0, i] + 5.0 * d[i]
            a_new[i] = (dx - dp) / cd
    rnorm = 0.0
    refresh = True
    fixed = False
    previous = 0.0
    reused_before = False
    for i in range(N):                  # eqs. (38)-(39) at the starting guess; each iteration
        dp = d[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * acc[i]    # updates them below
        vp = v[i] + dt * (1.0 - gamma) * acc[i]
        d_new[i] = dp + cd * a_new[i]
        v_new[i] = vp + cv * a_new[i]
    for it in range(1, max_iter + 1):
        if refresh:
            element_newmark(codes, par, secant, dofs, l, d_new, v_new, a_new, kin, cv, cd, rE, SE,
                            KE, CE, ME, ws)
        else:
            element_residual(codes, par, dofs, l, d_new, v_new, a_new, kin, rE, KE, CE, ME, ws)
        assemble_vector(dofs, rE, R)
        rnorm = 0.0
        for i in range(N):
            rnorm += R[i] * R[i]
            rhs[i, 0] = -R[i]
        rnorm = math.sqrt(rnorm)
        if not np.isfinite(rnorm):
            return NOT_FINITE, it, rnorm
        if refresh:
            fixed = False
            if kb == KB_FIXED:
                assemble_fixed(dofs, SE, F, N)
                fixed = factor_fixed(F, N, diag)
            if not fixed:
                assemble_band_newmark(dofs, kb, SE, W)
                if not band_factor(W, kb, piv, ext):
                    return SINGULAR, it, rnorm
        if fixed:
            solve_fixed(F, N, rhs[:, 0])
        else:
            band_lu_solve(W, kb, piv, ext, rhs)
        inc = 0.0
        size = 0.0
        for i in range(N):
            a_new[i] += rhs[i, 0]
            x = abs(cd * rhs[i, 0]) / scales[i]
            if x > inc:
                inc = x
        for i in range(N):
            d_new[i] = d[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * acc[i] + cd * a_new[i]
            v_new[i] = v[i] + dt * (1.0 - gamma) * acc[i] + cv * a_new[i]
            x = abs(d_new[i]) / scales[i]
            if x > size:
                size = x
        if not np.isfinite(inc):
            return NOT_FINITE, it, rnorm
        limit = tol * (1.0 + size)
        if one_pass or inc <= limit:
            return OK, it, rnorm
        if scheme == NEWTON:
            if it > 1:
                # |delta_k| / |delta_{k-1}| estimates the contraction of the next iteration when
                # both increments came from the same kind of iteration (two fresh Newton ones or
                # two with a reused factorization), not across the switch from fresh to reused
                rate = inc / previous
                if refresh == reused_before:
                    pass
                elif rate < 1.0 and rate / (1.0 - rate) * inc <= ESTIMATE_FRACTION * limit:
                    return OK, it, rnorm
                reused_before = not refresh
                refresh = rate > REFRESH_RATE
            else:
                refresh = False
        previous = inc
    return NOT_CONVERGED, max_iter, rnorm


@njit(cache=True)
def _outputs(dofs, mid_e, Nv_mid, G, eps, phi, d, out):
    """v* at x* = 1/2, u*(1), delta* (eq. 40) of the state d."""
    n = dofs.shape[0]
    N = d.shape[0]
    c, s = math.cos(phi), math.sin(phi)
    vmid = 0.0
    slope = 0.0
    q = np.zeros(6)
    u_end = 0.0
    for e in range(n):
        for k in range(6):
            idx = dofs[e, k]
            q[k] = d[idx] if idx < N else 0.0
        if e == n - 1:
            p = q[3]
            q[3] = c * p
            q[4] = s * p
            u_end = q[3]
        if e == mid_e:
            for k in range(6):
                vmid += Nv_mid[k] * q[k]
        for i in range(6):
            for j in range(6):
                slope += q[i] * G[i, j] * q[j]
    out[0] = vmid / eps
    out[1] = u_end / (eps * eps)
    out[2] = u_end + 0.5 * slope


def _march_impl(codes, par, dofs, kb, l, scales, mid_e, Nv_mid, G, beta, gamma, tol, max_iter,
                step0, n_steps, steps_per_rev, D0, V0, A0, P, n_prev, keep_history,
                out_y, out_iter, status, fail_step, fail_res, Dh, Vh, Ah, D1, V1, A1):
    """Advance every case of the batch n_steps in lock step (see march)."""
    B = D0.shape[0]
    n = dofs.shape[0]
    N = D0.shape[1]
    for b in prange(B):
        ws = _make_ws()
        rE, KE, CE, ME = np.zeros((n, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6))
        R, W, rhs = np.zeros(N), np.zeros((N, 3 * kb + 1)), np.zeros((N + KB_FIXED, 1))
        SE = np.zeros((n, 6, 6))
        piv, ext = np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64)
        F, diag = np.zeros((N + KB_FIXED, 2 * KB_FIXED + 1)), np.zeros(N)
        kin = np.zeros(5)
        d, v, acc = D0[b].copy(), V0[b].copy(), A0[b].copy()
        dn, vn, an = np.zeros(N), np.zeros(N), np.zeros(N)
        y = np.zeros(3)
        dt = par[b, 5]
        crank_kinematics(par[b, 0], par[b, 4], step0 * dt, kin)
        _outputs(dofs, mid_e, Nv_mid, G, par[b, 1], kin[2], d, y)
        out_y[b, 0, :] = y
        if keep_history:
            Dh[b, 0, :] = d
            Vh[b, 0, :] = v
            Ah[b, 0, :] = acc
        for m in range(n_steps):
            if status[b] != OK:
                break
            t_new = (step0 + m + 1) * dt
            st, it, rn = newmark_step(codes[b], par[b], dofs, kb, l, scales[b], beta, gamma, tol,
                                      max_iter, t_new, d, v, acc, P[b], n_prev[b], dn,
                                      vn, an, rE, SE, KE, CE, ME, R, W, piv, ext, F, diag, rhs,
                                      kin, ws)
            out_iter[b, m] = it
            if st == OK:
                for i in range(N):
                    if not (np.isfinite(dn[i]) and np.isfinite(vn[i])):
                        st = NOT_FINITE
                        break
            if st != OK:
                status[b] = st
                fail_step[b] = step0 + m + 1
                fail_res[b] = rn
                break
            for k in range(HISTORY - 1, 0, -1):
                P[b, k, :] = P[b, k - 1]
            P[b, 0, :] = d
            n_prev[b] = min(n_prev[b] + 1, HISTORY)
            d[:] = dn
            v[:] = vn
            acc[:] = an
            _outputs(dofs, mid_e, Nv_mid, G, par[b, 1], kin[2], d, y)
            out_y[b, m + 1, :] = y
            if keep_history:
                Dh[b, m + 1, :] = d
                Vh[b, m + 1, :] = v
                Ah[b, m + 1, :] = acc
        D1[b, :] = d
        V1[b, :] = v
        A1[b, :] = acc


def _variant(impl, name, parallel):
    """A compiled copy of impl under its own name: numba's on-disk cache is keyed by the function's
    qualified name, so the serial and the parallel compilation must not share one."""
    import types
    fn = types.FunctionType(impl.__code__, impl.__globals__, name, impl.__defaults__, impl.__closure__)
    fn.__qualname__ = name
    fn.__doc__ = impl.__doc__
    return njit(cache=True, parallel=parallel)(fn)


_march_serial = _variant(_march_impl, "_march_serial", False)
_march_parallel = _variant(_march_impl, "_march_parallel", True)


@njit(cache=True)
def _initial_accelerations(codes, par, dofs, kb, l, step0, D0, V0, A0, status):
    for b in range(D0.shape[0]):
        if not initial_acceleration(codes[b], par[b], dofs, kb, l, step0 * par[b, 5], D0[b], V0[b], A0[b]):
            status[b] = SINGULAR


# ----------------------------------------------------------------------------------------------
# Python-level API
# ----------------------------------------------------------------------------------------------

def groups_mask(groups_off):
    """Bit mask of the comma-separated group names (SWITCHABLE_GROUPS)."""
    mask = 0
    for name in filter(None, (g.strip() for g in groups_off.split(","))):
        mask |= 1 << SWITCHABLE_GROUPS.index(name)
    return mask


class Batch:
    """Cases that share a mesh and steps per revolution, packed for the compiled engine."""

    def __init__(self, cases, dt=None):
        """dt overrides the time step 2 pi / (omega steps_per_rev) (free vibration, omega ~ 0)."""
        from .assembly import BandedAssembler
        from .mesh import Mesh

        cases = list(cases)
        if not cases:
            raise ValueError("a batch needs at least one case")
        n, spr = cases[0].n_elements, cases[0].steps_per_rev
        if any(c.n_elements != n or c.steps_per_rev != spr for c in cases):
            raise ValueError("all cases of a batch must share n_elements and steps_per_rev")
        self.cases, self.n_elements, self.steps_per_rev = cases, n, spr
        self.mesh = Mesh(n)
        self.N = self.mesh.n_dofs
        self.dofs = np.ascontiguousarray(self.mesh.element_dofs, dtype=np.int64)
        self.kb = BandedAssembler(self.mesh).bandwidth
        self.l = self.mesh.length
        self.mid_element, zeta = self.mesh.locate(0.5)
        self.Nv_mid = np.ascontiguousarray(_shape.shape_functions(zeta, self.l)[1], dtype=float)
        self.G = np.ascontiguousarray(_shape.slope_gram(self.l), dtype=float)
        self.codes = np.array([[FORMULATION_CODE[c.formulation], APPROACH_CODE[c.approach],
                                DAMPING_CODE[c.damping], INTEGRATOR_CODE[c.integrator],
                                MEMBRANE_CODE[c.membrane], groups_mask(c.groups_off)]
                               for c in cases], dtype=np.int64)
        self.par = np.array([[c.a, c.eps, c.ms, c.mu, c.omega,
                              dt if dt is not None else 2 * math.pi / c.omega / spr]
                             for c in cases], dtype=float)
        self.scales = np.array([self.mesh.dof_scales(c.eps) for c in cases])

    def __len__(self):
        return len(self.cases)


class MarchResult:
    """Outputs of march: y[b, m] = (v*, u*(1), delta*) at step m, final states, statuses."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


def march(batch, n_steps, D0=None, V0=None, A0=None, step0=0, keep_history=False, parallel=None,
          beta=0.25, gamma=0.5, tol=1e-10, max_iter=30, status=None, previous=None):
    """Advance all cases of the batch from step index step0 (t = step0 dt) by n_steps Newmark steps.

    D0, V0: (B, N) initial reduced states (zero by default); A0 the accelerations, by default
    solved from eq. (34).  previous: the `previous` of the MarchResult this run continues (the
    displacements of the two steps before D0, for the Newton starting guess; none by default).
    Cases whose status is not OK on entry are not advanced."""
    B, N = len(batch), batch.N
    D0 = np.zeros((B, N)) if D0 is None else np.ascontiguousarray(D0, dtype=float)
    V0 = np.zeros((B, N)) if V0 is None else np.ascontiguousarray(V0, dtype=float)
    status = np.zeros(B, dtype=np.int64) if status is None else np.array(status, dtype=np.int64)
    if A0 is None:
        A0 = np.zeros((B, N))
        _initial_accelerations(batch.codes, batch.par, batch.dofs, batch.kb, batch.l, step0, D0, V0,
                               A0, status)
    else:
        A0 = np.ascontiguousarray(A0, dtype=float)
    if previous is None:
        P, n_prev = np.zeros((B, HISTORY, N)), np.zeros(B, dtype=np.int64)
    else:
        P, n_prev = np.array(previous[0], dtype=float), np.array(previous[1], dtype=np.int64)
    out_y = np.full((B, n_steps + 1, 3), np.nan)
    out_iter = np.zeros((B, n_steps), dtype=np.int64)
    fail_step = np.zeros(B, dtype=np.int64)
    fail_res = np.zeros(B)
    hist_shape = (B, n_steps + 1, N) if keep_history else (1, 1, 1)
    Dh, Vh, Ah = np.zeros(hist_shape), np.zeros(hist_shape), np.zeros(hist_shape)
    D1, V1, A1 = np.zeros((B, N)), np.zeros((B, N)), np.zeros((B, N))
    if parallel is None:
        parallel = B > 1
    fn = _march_parallel if parallel else _march_serial
    fn(batch.codes, batch.par, batch.dofs, batch.kb, batch.l, batch.scales, batch.mid_element,
       batch.Nv_mid, batch.G, beta, gamma, tol, max_iter, step0, n_steps, batch.steps_per_rev,
       D0, V0, A0, P, n_prev, keep_history, out_y, out_iter, status, fail_step, fail_res, Dh, Vh, Ah,
       D1, V1, A1)
    return MarchResult(y=out_y, iterations=out_iter, status=status, fail_step=fail_step,
                       fail_residual=fail_res, D=D1, V=V1, A=A1, previous=(P, n_prev),
                       D_history=Dh if keep_history else None, V_history=Vh if keep_history else None,
                       A_history=Ah if keep_history else None)


# ----------------------------------------------------------------------------------------------
# one revolution with its exact linearization (shooting)
# ----------------------------------------------------------------------------------------------

def _revolution_impl(codes, par, dofs, kb, l, scales, beta, gamma, tol, max_iter, step0, n_steps,
                     X0, active, X1, J, status):
    """For every active case: state x = (d, v) at step step0 -> state after n_steps Newton steps,
    and J = dx1/dx0, the exact linearization of the converged Newmark steps:
        S da' = -(K dd~ + C dv~),  dd' = dd~ + beta dt^2 da',  dv' = dv~ + gamma dt da'
    with S, K, C the exact tangents at the converged state of each step (a0 from eq. 34)."""
    B = X0.shape[0]
    n = dofs.shape[0]
    N = X0.shape[1] // 2
    for b in prange(B):
        if not active[b]:
            continue
        ws = _make_ws()
        rE, KE, CE, ME = np.zeros((n, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6))
        R, W, rhs = np.zeros(N), np.zeros((N, 3 * kb + 1)), np.zeros((N + KB_FIXED, 1))
        SE = np.zeros((n, 6, 6))
        piv, ext = np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64)
        F, diag = np.zeros((N + KB_FIXED, 2 * KB_FIXED + 1)), np.zeros(N)
        kin = np.zeros(5)
        cb, pb = codes[b], par[b]
        dt = pb[5]
        cd, cv = beta * dt * dt, gamma * dt
        d, v = X0[b, :N].copy(), X0[b, N:].copy()
        acc = np.zeros(N)
        dn, vn, an = np.zeros(N), np.zeros(N), np.zeros(N)
        if not initial_acceleration(cb, pb, dofs, kb, l, step0 * dt, d, v, acc):
            status[b] = SINGULAR
            continue
        # sensitivities (N, 2N)
        Dd = np.zeros((N, 2 * N))
        Dv = np.zeros((N, 2 * N))
        for i in range(N):
            Dd[i, i] = 1.0
            Dv[i, N + i] = 1.0
        Da = np.zeros((N, 2 * N))
        tmp = np.zeros((N, 2 * N))
        # da0 = -M^-1 (K dd0 + C dv0) at t0
        crank_kinematics(pb[0], pb[4], step0 * dt, kin)
        element_terms(cb, pb, False, dofs, l, d, v, acc, kin, rE, KE, CE, ME, ws)
        band_matmul(dofs, kb, KE, Dd, Da)
        band_matmul(dofs, kb, CE, Dv, tmp)
        for i in range(N):
            for c in range(2 * N):
                Da[i, c] = -(Da[i, c] + tmp[i, c])
        assemble_band(dofs, kb, ME, CE, KE, 1.0, 0.0, 0.0, W)
        if not band_solve(W, kb, Da):
            status[b] = SINGULAR
            continue
        ok = True
        hist = np.zeros((HISTORY, N))
        for m in range(n_steps):
            t_new = (step0 + m + 1) * dt
            st, it, rn = newmark_step(cb, pb, dofs, kb, l, scales[b], beta, gamma, tol, max_iter,
                                      t_new, d, v, acc, hist, min(m, HISTORY), dn, vn, an, rE, SE, KE,
                                      CE, ME, R, W, piv, ext, F, diag, rhs, kin, ws)
            if st != OK:
                status[b] = st
                ok = False
                break
            # predictor sensitivities (in place): Dd <- dd~, Dv <- dv~
            for i in range(N):
                for c in range(2 * N):
                    Dd[i, c] = Dd[i, c] + dt * Dv[i, c] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * Da[i, c]
                    Dv[i, c] = Dv[i, c] + dt * (1.0 - gamma) * Da[i, c]
            # exact tangents at the converged state
            element_terms(cb, pb, False, dofs, l, dn, vn, an, kin, rE, KE, CE, ME, ws)
            band_matmul(dofs, kb, KE, Dd, Da)
            band_matmul(dofs, kb, CE, Dv, tmp)
            for i in range(N):
                for c in range(2 * N):
                    Da[i, c] = -(Da[i, c] + tmp[i, c])
            assemble_band(dofs, kb, ME, CE, KE, 1.0, cv, cd, W)
            if not band_factor(W, kb, piv, ext):
                status[b] = SINGULAR
                ok = False
                break
            band_lu_solve(W, kb, piv, ext, Da)
            for i in range(N):
                for c in range(2 * N):
                    Dd[i, c] += cd * Da[i, c]
                    Dv[i, c] += cv * Da[i, c]
            for k in range(HISTORY - 1, 0, -1):
                hist[k, :] = hist[k - 1]
            hist[0, :] = d
            d[:] = dn
            v[:] = vn
            acc[:] = an
        if not ok:
            continue
        X1[b, :N] = d
        X1[b, N:] = v
        J[b, :N, :] = Dd
        J[b, N:, :] = Dv


_revolution_serial = _variant(_revolution_impl, "_revolution_serial", False)
_revolution_parallel = _variant(_revolution_impl, "_revolution_parallel", True)


def revolution(batch, X0, step0=0, active=None, parallel=None, beta=0.25, gamma=0.5, tol=1e-10,
               max_iter=30, revolutions=1):
    """(X1, J, status): the one-revolution map of the Newton-Newmark scheme and its Jacobian, for
    states X0 (B, 2N) = (d, v) at step index step0 (revolutions > 1: that many revolutions)."""
    B, N = len(batch), batch.N
    X0 = np.ascontiguousarray(X0, dtype=float)
    active = np.ones(B, dtype=np.bool_) if active is None else np.asarray(active, dtype=np.bool_)
    X1 = np.full((B, 2 * N), np.nan)
    J = np.full((B, 2 * N, 2 * N), np.nan)
    status = np.zeros(B, dtype=np.int64)
    if parallel is None:
        parallel = int(active.sum()) > 1
    fn = _revolution_parallel if parallel else _revolution_serial
    fn(batch.codes, batch.par, batch.dofs, batch.kb, batch.l, batch.scales, beta, gamma, tol,
       max_iter, step0, revolutions * batch.steps_per_rev, X0, active, X1, J, status)
    return X1, J, status
