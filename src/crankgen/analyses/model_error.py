"""Which model to trust where: how far a result of the paper's approaches (A, B, C: the consistent
and the paper's model) is from the geometrically exact rod's, estimated from the result alone, and
the verdict "trust this model here / use the exact rod / beyond both".

**The estimate.**  The exact rod (model="exact") keeps what approaches A-C drop: the
moderate-rotation strain u_x + v_x^2/2 and curvature v_xx in place of the exact stretch and
curvature (and the section's rotary inertia by its slope in place of its director).  Along a
result's states (d, v, a)(t), which satisfy the model's equations R_m = 0, the exact rod's residual

    f(t) = R_x(t, d, v, a) - R_m(t, d, v, a)

is the force the model leaves out, evaluated on its own motion (eq. 30 from both models' generated
kernels, NumPy), once the exact rod's axial unknowns have taken up its different measure of the
membrane strain (_membrane_consistent: u_x + v_x^2/2 and the exact stretch differ at fourth order
in v_x, which EA, large for a slender rod, turns into an axial force the axial modes carry off at
once).  To first order the exact rod's motion is d + x with

    M x'' + C x' + K x = -f(t)      (M, C, K: the model's own tangents along its states)

x periodic over a steady state's revolution (this linear system's monodromy solved for it), or from
x = 0 for a transient; by the result's own time scheme on its own steps.  `error` is the largest
transverse displacement of x over the nodes and steps relative to the largest of d.  Near a
resonance the correction is amplified as the response is (the tangents carry the resonance), which
a weight of the dropped terms alone misses.  Measured against the exact rod's own steady orbits
(the largest |v| difference over the nodes and the revolution, over the largest |v|; the consistent
model, 16 elements): at eps = 0.01 and Omega* = 0.4, 0.6, 0.7, 0.8, 0.9, 0.95, 1.0 the estimate is
0.10, 0.62, 2.1, 10.9, 10.8, 6.0, 3.9 % where the orbits differ by 0.10, 0.61, 2.0, 9.2, 9.1, 4.6,
3.1 % (the amplitude max |v*| by 5.8 % at 0.8); at eps = 0.002 and 0.05 likewise (2.1 % for 2.0 %
at 0.7; 10.6 % for 10.2 % at 0.8).  Accurate to a few per cent of itself near 1 %, it overestimates
by up to a third where the models differ by 5-15 % (tests/test_model_error.py).

**The verdict** (`Verdict`): "beyond both" when the exact rod's own limits are exceeded
(crankgen.theory.EXACT_CRITERION: slenderness, the outer-fibre strain of a linear elastic material,
the element's section rotation: what every crankgen model shares), measured on the result's own
states; otherwise "use the exact rod" when the estimate exceeds ERROR_LIMIT (1 %), "trust this
model here" when not.  An exact-model result is "trust this model here" within its limits (the
estimate is 0: it is the reference), "beyond both" beyond them.  A motor-driven crank's result has
no estimate (its kinematics are its own unknowns; the verdict then rests on the limits alone).
"""

import math
from dataclasses import dataclass

import numpy as np

from . import theory
from ..discrete.mesh import V

ERROR_LIMIT = 0.01               # the model error a result may carry and still be trusted
CHUNK = 200                      # steps whose dense tangents are held at once (a transient's memory)
TRUST, EXACT, BOTH = "trust this model here", "use the exact rod", "beyond both"


def _dense(model, kin, d, v, a):
    """(r (T, N), K, C, M (T, N, N)): the reduced residual and tangents at each step, dense."""
    terms = model.element_terms(kin, d, v, a)
    T, N = d.shape[0], model.mesh.n_dofs
    r = np.zeros((T, N + 1))
    K, C, M = (np.zeros((T, N + 1, N + 1)) for _ in range(3))
    for e, dofs in enumerate(model.mesh.element_dofs):   # the dummy slot N collects nothing kept
        r[:, dofs] += terms.r[:, e]
        block = (slice(None), dofs[:, None], dofs[None, :])
        K[block] += terms.K[:, e]
        C[block] += terms.C[:, e]
        M[block] += terms.M[:, e]
    return r[:, :N], K[:, :N, :N], C[:, :N, :N], M[:, :N, :N]


class _Linear:
    """The model's linearization along a result's states and the defect forcing, in chunks of steps."""

    def __init__(self, result):
        from ..declaration.cases import exact_case
        from ..discrete.system import Model
        case = result.case
        self.t = np.asarray(result.t, dtype=float)
        self.d, self.v, self.a = (np.asarray(x, dtype=float) for x in
                                  (result.states, result.rates, result.accelerations))
        self.model, self.exact = Model(case), Model(exact_case(case))

    def chunks(self):
        """(K, C, M, f) of consecutive chunks of steps.  The exact rod reads the states in its own
        layout (its nodes' chi: the nodal slopes of the model's u, then settled with the other axial
        unknowns: _membrane_consistent) and its residual is read back on the model's unknowns."""
        from ..discrete.mesh import transfer
        mine, exact = self.model.mesh, self.exact.mesh
        axial = _axial_dofs(exact)
        for start in range(0, len(self.t), CHUNK):
            part = slice(start, start + CHUNK)
            kin = self.model.kinematics(self.t[part])
            d, v, a = self.d[part], self.v[part], self.a[part]
            r_m, K, C, M = _dense(self.model, kin, d, v, a)
            dx, vx, ax = (transfer(x, mine, exact) for x in (d, v, a))
            yield K, C, M, transfer(_membrane_consistent(self.exact, kin, dx, vx, ax, axial), exact, mine) - r_m


def _axial_dofs(mesh):
    """The reduced indices of the axial unknowns: u (and the exact rod's chi) of every node that has
    one, and the end's."""
    from ..discrete.mesh import CHI, U
    idx = ({mesh.reduced_index(node, c) for node in range(mesh.n_elements + 1) for c in (U, CHI)}
           | set(mesh.reduced_coordinates()))
    return np.array(sorted(i for i in idx if i is not None), dtype=np.intp)


def _membrane_consistent(exact, kin, d, v, a, axial, iterations=8):
    """The exact rod's residual at the states d with their axial unknowns moved so that its axial
    rows vanish (Newton on them, the transverse unknowns held).  The two models measure the membrane
    strain differently (u_x + v_x^2/2 against the exact stretch, which differ at fourth order in
    v_x), so the same u gives the exact rod an axial force EA times that difference, large for a
    slender rod, which its own axial unknowns take up at once (the axial modes are the fast ones).
    Evaluated on the model's own u, that force and its transverse share would cancel only through
    the model's linearized coupling, at the order the estimate looks for: the axial unknowns are
    settled first, and what remains in the transverse rows is what the model's kinematics drop."""
    d = np.array(d, dtype=float)
    rows = (slice(None), axial[:, None], axial[None, :])
    for _ in range(iterations):
        r, K, _, _ = _dense(exact, kin, d, v, a)
        step = -np.linalg.solve(K[rows], r[:, axial, None])[..., 0]
        d[:, axial] += step
        if np.max(np.abs(step)) <= 1e-14 * (1.0 + np.max(np.abs(d[:, axial]))):
            break
    return _dense(exact, kin, d, v, a)[0]


def _march(chunks, h, x0, scheme):
    """The result's own time scheme (generalized-alpha in Arnold & Bruls' form, crankgen.time_scheme;
    Newmark's trapezoidal rule for rho_inf = 1) for M x'' + C x' + K x = -f w^T on uniform steps h
    from the states x0 ((3N, m): displacements, velocities, algorithmic accelerations; w = (1, 0,
    ...): the forcing drives the first column only, the others are the homogeneous solutions of the
    monodromy).  The scheme matters: the trapezoidal rule keeps the rod's heavily damped stiff axial
    modes ringing from step to step, which the result's own scheme damps.  Returns (x, the final
    states (3N, m))."""
    am, af, b, g = scheme.alpha_m, scheme.alpha_f, scheme.beta, scheme.gamma
    r = (1 - af) / (1 - am)
    N = x0.shape[0] // 3
    w = np.zeros((1, x0.shape[1]))
    w[0, 0] = 1.0
    x, xd, alg = x0[:N].copy(), x0[N:2 * N].copy(), x0[2 * N:].copy()
    qdd = None
    xs = []
    for K, C, M, f in chunks:
        for n in range(f.shape[0]):
            load = f[n][:, None] * w
            if qdd is None:                                 # the first step: the equation there
                qdd = np.linalg.solve(M[n], -load - C[n] @ xd - K[n] @ x)
            else:
                memory = (af * qdd - am * alg) / (1 - am)
                xp = x + h * xd + h * h * ((0.5 - b) * alg + b * memory)
                vp = xd + h * ((1 - g) * alg + g * memory)
                new = np.linalg.solve(M[n] + g * h * r * C[n] + b * h * h * r * K[n],
                                      -load - C[n] @ vp - K[n] @ xp)
                alg = memory + r * new
                x, xd, qdd = xp + b * h * h * r * new, vp + g * h * r * new, new
            xs.append(x)
    return np.stack(xs), np.concatenate([x, xd, alg])


def correction(result, periodic=None):
    """(t, x (T, N)): the first-order correction of a result's motion towards the exact rod's
    (module docstring); periodic: a steady state's revolution (default: whether the result has a
    steady state's `status`)."""
    from ..discrete.time_scheme import coefficients
    lin = _Linear(result)
    t = lin.t
    h = float(t[1] - t[0])
    N = lin.d.shape[1]
    scheme = coefficients(result.case.rho_inf)
    if periodic is None:
        periodic = hasattr(result, "status")
    if not periodic:
        x, _ = _march(lin.chunks(), h, np.zeros((3 * N, 1)), scheme)
        return t, x[..., 0]
    x0 = np.zeros((3 * N, 3 * N + 1))
    x0[:, 1:] = np.eye(3 * N)
    x, end = _march(lin.chunks(), h, x0, scheme)
    y0 = np.linalg.solve(np.eye(3 * N) - end[:, 1:], end[:, 0])            # y(T) = y(0)
    return t, x[..., 0] + x[..., 1:] @ y0


def transverse(case, d):
    """(..., n + 1): the transverse displacement v of every node of reduced states d (the end
    node's, on the guide, left at 0)."""
    from ..discrete.mesh import nodal_mesh
    mesh = nodal_mesh(case)
    d = np.asarray(d, dtype=float)
    out = np.zeros(d.shape[:-1] + (case.n_elements + 1,))
    for node in range(case.n_elements + 1):
        idx = mesh.reduced_index(node, V)
        if idx is not None:
            out[..., node] = d[..., idx]
    return out


def error(result, periodic=None):
    """The estimated relative difference of a result's response from the exact rod's: the largest
    |v| of the first-order correction over the nodes and steps, over the largest |v| of the result
    (0 for a result at rest); None where it is not estimated (no stored states, rates and
    accelerations; a motor-driven crank; fewer than two steps)."""
    case = getattr(result, "case", None)
    if case is None or theory.is_exact(case):
        return None if case is None else 0.0
    if any(getattr(result, name, None) is None for name in ("states", "rates", "accelerations")) \
            or case.motion_record.driven or len(result.t) < 2:
        return None
    base = float(np.max(np.abs(transverse(case, result.states))))
    if base == 0.0:
        return 0.0
    with np.errstate(all="ignore"):
        try:
            _, x = correction(result, periodic)
        except np.linalg.LinAlgError:            # a multiplier at 1: no unique periodic correction
            return None
        value = float(np.max(np.abs(transverse(case, x)))) / base
    return value if math.isfinite(value) else None


@dataclass(frozen=True)
class Verdict:
    """Which model to trust for a result: `words` (TRUST, EXACT or BOTH; "" when unknown),
    `error` (the estimated relative difference from the exact rod, None when not estimated),
    `limits` (the exact rod's RangeFlag on the result's states: its tripped measures are why
    "beyond both"), `exact` (whether the result is the exact rod's)."""

    words: str
    error: object
    limits: object
    exact: bool = False

    def __str__(self):
        if not self.words:
            if self.limits.known:               # a motor-driven crank: the limits, no estimate
                return ("no estimate of the difference from the exact rod for a motor-driven crank; "
                        + str(self.limits).replace("the range of the theory", "the exact rod's limits"))
            return "model verdict unknown (no stored states)"
        est = ("" if self.error is None or self.exact else
               f"this model's response is an estimated {self.error:.2%} from the exact rod's")
        if self.words == BOTH:
            return (f"{BOTH}: beyond the exact rod's limits ({self.limits.reason}), which every crankgen "
                    f"model shares: {self.limits.remedy}" + (f"; {est}" if est else ""))
        if self.words == EXACT:
            return (f"{EXACT}: {est}, more than {ERROR_LIMIT:.0%} (the model's moderate rotations and small "
                    f"strains cost that much here): model=\"exact\"")
        return TRUST + (f": {est}, within {ERROR_LIMIT:.0%}" if est else ": within the exact rod's limits")


def verdict(result, periodic=None):
    """The Verdict of a result that stores its states (module docstring)."""
    case = getattr(result, "case", None)
    if case is None or getattr(result, "states", None) is None or not np.size(result.states):
        return Verdict("", None, theory.exact_range_flag())
    fibre, rotation = theory.exact_measures(result)
    limits = theory.exact_range_flag(case.eps, fibre, rotation)
    exact = theory.is_exact(case)
    value = error(result, periodic)
    if limits:
        return Verdict(BOTH, value, limits, exact)
    if exact or (value is not None and value <= ERROR_LIMIT):
        return Verdict(TRUST, value, limits, exact)
    if value is None:
        return Verdict("", None, limits, exact)
    return Verdict(EXACT, value, limits, exact)
