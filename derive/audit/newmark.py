"""The Newmark update of eqs. (35)-(39) on scalar stand-ins of eq. (30): the residual of eq. (37)
under each velocity corrector, and the local defects of the updates for a smooth motion."""

import sympy as sp


# Scalar stand-ins of eq. (30) for the Newmark checks, the predictors of eqs. (35)-(36), and the
# derivatives d_k = d^(k)(t_m) of a smooth motion with step h = dt.
NM_M, NM_C, NM_K, NM_F, NM_DT, NM_BETA, NM_GAMMA = sp.symbols("M C K F dt beta gamma", positive=True)
D_PRED, V_PRED, V_PRED_PREV = sp.symbols("d_pred v_pred v_pred_prev", real=True)
H = sp.Symbol("h", positive=True)
DERIVS = sp.symbols("d0:7", real=True)
NEWMARK_LATEX_NAMES = {
    NM_DT: r"\Delta t", NM_BETA: r"\beta", NM_GAMMA: r"\gamma", D_PRED: r"\tilde{d}_{m+1}",
    V_PRED: r"\tilde{v}_{m+1}", V_PRED_PREV: r"\tilde{v}_{m}",
    **{d: "d^{(%d)}" % k for k, d in enumerate(DERIVS)},
}


def newmark_eq37_residual(corrector_velocity):
    """R = M a + C v + K d - F at t_{m+1} for the a of eq. (37), with d from eq. (38) and the
    given velocity corrector ('corrected': v~_{m+1} + gamma dt a; 'printed': v~_m + gamma dt a)."""
    M, C, K, F, dt, beta, gamma = NM_M, NM_C, NM_K, NM_F, NM_DT, NM_BETA, NM_GAMMA
    d_pred, v_pred, v_pred_prev = D_PRED, V_PRED, V_PRED_PREV
    a = (F - C * v_pred - K * d_pred) / (M + gamma * dt * C + beta * dt**2 * K)       # eq. (37)
    d_new = d_pred + beta * dt**2 * a                                                  # eq. (38)
    v_base = v_pred if corrector_velocity == "corrected" else v_pred_prev
    v_new = v_base + gamma * dt * a                                                    # eq. (39)
    return sp.simplify(M * a + C * v_new + K * d_new - F)


def _taylor(derivs, k, shift, h):
    """Taylor series of the k-th derivative of a smooth motion at t + shift h (derivs: d^(j)(t))."""
    return sum(derivs[k + j] * (shift * h) ** j / sp.factorial(j) for j in range(len(derivs) - k))


def newmark_defects(gamma=sp.Rational(1, 2), beta=sp.Rational(1, 4)):
    """Local defects (exact motion inserted) of the corrected and printed velocity correctors
    (eq. 39, with the predictor of eq. 36) and of the displacement corrector (eqs. 35, 38)."""
    h, derivs = H, DERIVS
    disp, vel, acc = (lambda c, k=k: _taylor(derivs, k, c, h) for k in range(3))
    corrected = vel(1) - (vel(0) + h * (1 - gamma) * acc(0) + gamma * h * acc(1))
    printed_ = vel(1) - (vel(-1) + h * (1 - gamma) * acc(-1) + gamma * h * acc(1))
    displacement = disp(1) - (disp(0) + h * vel(0) + h**2 / 2 * (1 - 2 * beta) * acc(0) + beta * h**2 * acc(1))
    return {name: sp.expand(expr) for name, expr in
            (("velocity, corrected", corrected), ("velocity, as printed", printed_),
             ("displacement, eq. (38)", displacement))}, h


def leading_order(expr, h):
    poly = sp.Poly(expr, h)
    return min(m[0] for m in poly.monoms())
