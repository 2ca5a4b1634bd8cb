"""What approach A drops relative to the exact strain, weighed along real trajectories (audit
section 7; the series are crankgen._derive.audit.exact_strain).

Along one steady revolution of the consistent model (approach A, element-mean membrane strain):
- membrane: the exact stretch |r'| - 1 of A's own deformation field (its linear u, cubic v) less A's
  pointwise strain u_x + v_x^2/2, at the elements' midpoints, RMS over the revolution and the
  elements, relative to the RMS of A's membrane strain there; curvature: the same for the exact
  curvature ((1 + u_x) v_xx - v_x u_xx) / |r'|^2 (u_xx = 0 in A's elements) less v_xx at the
  elements' ends and midpoints, relative to the RMS of v_xx.  Both are what the series of 7.1
  measure: A's measures against the exact ones of the same field;
- force: RMS |F_exact - F_A| over RMS |F_A| on the transverse DOFs (v, psi), as section 4 weighs the
  groups: the exact rod's elastic force (its generated kernel) at A's transverse state, its own
  axial unknowns (u, chi and the end's) settled so that its axial elastic forces are A's (the two
  rods represent u differently, the exact rod's u cubic: read on A's nodal u alone, the exact rod's
  axial force would carry the difference of the two interpolations instead of the physics);
- slope: the largest |v_x| over the revolution (the ordering's delta).
Every difference is of relative order delta^2 (the series), so `scaled` reads the same revolution
at amplitudes scaled in the ordering (v, psi by s, u and s by s^2) to show it.
"""

from dataclasses import dataclass, replace

import numpy as np

from ..declaration import ingredients
from ..declaration.cases import exact_case  # noqa: F401  (the exact rod's case; used here and by the tests)
from .._generated import elements as _elements
from ..discrete.constraints import project_residual
from ..discrete.mesh import CHI, NODE_DOFS, PSI, U, V, transfer
from ..discrete.system import Model
from ..results.outputs import StateHistory


@dataclass(frozen=True)
class ExactWeights:
    case: object               # the consistent model's case
    amplitude: float           # its steady max |v*(1/2)|
    slope: float               # the largest |v_x| over the revolution
    membrane: float            # RMS (|r'| - 1 - e_A) / RMS e_A at the element midpoints
    curvature: float           # RMS (kappa - v_xx) / RMS v_xx at the element ends and midpoints
    transverse: float          # RMS |F_exact - F_A| / RMS |F_A| on v, psi


def _elastic(model, q, kin):
    """The elastic family's element forces of a model at element vectors q (steps, n, NDOF)."""
    kernel = next(getattr(_elements, k) for name, k in zip(ingredients.FAMILIES, model.selection.kernels)
                  if name == "elastic")
    zeros = np.zeros_like(q)
    return kernel(q, zeros, zeros, model.geometry, model.coefficients, kin.vector[:, None, :])[0]


def _reduced_forces(model, t, states):
    """(steps, N) elastic forces of the reduced states, the constraint projected."""
    kin = model.kinematics(t)
    zeros = np.zeros_like(states)
    q, _, _, E = model.nodal_state(kin, states, zeros, zeros)
    r = _elastic(model, q, kin)
    for h, slots, reduced in model.mesh.holders():
        r[:, h] = project_residual(E, r[:, h], slots, reduced)
    return np.stack([model.assembler.vector(r[k]) for k in range(len(t))])


def _rms(x):
    return float(np.sqrt(np.mean(np.square(x))))


def _a_fields(q, l, zeta):
    """(u_x, v_x, v_xx) of A's element vectors q (steps, n, NDOF) at the abscissae zeta (P,) of each
    element: u linear, v cubic Hermite (eqs. 8-13)."""
    z = np.asarray(zeta, dtype=float)[:, None, None]
    u_x = (q[..., NODE_DOFS + U] - q[..., U]) / l
    v1, p1, v2, p2 = q[..., V], q[..., PSI], q[..., NODE_DOFS + V], q[..., NODE_DOFS + PSI]
    v_x = ((-6 * z + 6 * z**2) / l * v1 + (1 - 4 * z + 3 * z**2) * p1 + (6 * z - 6 * z**2) / l * v2
           + (-2 * z + 3 * z**2) * p2)
    v_xx = ((-6 + 12 * z) / l**2 * v1 + (-4 + 6 * z) / l * p1 + (6 - 12 * z) / l**2 * v2 + (-2 + 6 * z) / l * p2)
    return np.broadcast_to(u_x, v_x.shape), v_x, v_xx


def _settled(model_x, t, states_x, target, axial, iterations=12):
    """states_x with the axial unknowns `axial` moved (Newton, a difference Jacobian) until the
    exact rod's elastic forces there equal `target` (steps, len(axial))."""
    d = np.array(states_x, dtype=float)
    for _ in range(iterations):
        r = _reduced_forces(model_x, t, d)[:, axial] - target
        scale = np.maximum(np.abs(d[:, axial]), 1e-9)
        J = np.empty(r.shape + (len(axial),))
        for k, i in enumerate(axial):
            h = 1e-6 * scale[:, k]
            dp = d.copy()
            dp[:, i] += h
            J[..., k] = (_reduced_forces(model_x, t, dp)[:, axial] - target - r) / h[:, None]
        step = -np.linalg.solve(J, r[..., None])[..., 0]
        d[:, axial] += step
        if np.max(np.abs(step)) <= 1e-12 * (1.0 + np.max(np.abs(d[:, axial]))):
            break
    return d


def _axial(mesh):
    idx = [mesh.reduced_index(k, c) for k in range(mesh.n_elements + 1) for c in (U, CHI)]
    return np.array(sorted({i for i in idx if i is not None} | set(mesh.reduced_coordinates())), dtype=np.intp)


def weigh(case, t, states, amplitude=np.nan):
    """ExactWeights of the reduced states (steps, N) at times t of a consistent-model case."""
    exact = exact_case(case)
    model_a, model_x = Model.from_case(case), Model.from_case(exact)
    a_hist = StateHistory(case, t, states)
    n = case.n_elements
    l = 1.0 / n
    q = a_hist.element_vectors()
    u_x, v_x, _ = _a_fields(q, l, [0.5])
    e_a, e_x = u_x + v_x**2 / 2, np.sqrt((1 + u_x) ** 2 + v_x**2) - 1
    u_x, v_x, v_xx = _a_fields(q, l, [1e-9, 0.5, 1 - 1e-9])
    k_a, k_x = v_xx, (1 + u_x) * v_xx / ((1 + u_x) ** 2 + v_x**2)
    slope = float(np.max(np.abs(q[..., [PSI, NODE_DOFS + PSI]])))
    f_a = _reduced_forces(model_a, t, states)
    mesh_a, mesh_x = model_a.mesh, model_x.mesh
    axial_x = _axial(mesh_x)
    target = transfer(f_a, mesh_a, mesh_x)[:, axial_x]          # A's axial forces; 0 on chi
    for k, i in enumerate(axial_x):
        if i in {mesh_x.reduced_index(node, CHI) for node in range(n + 1)}:
            target[:, k] = 0.0
    states_x = _settled(model_x, t, transfer(states, mesh_a, mesh_x), target, axial_x)
    f_x = transfer(_reduced_forces(model_x, t, states_x), mesh_x, mesh_a)   # on A's rows
    transverse = np.ones(mesh_a.n_dofs, dtype=bool)
    transverse[_axial(mesh_a)] = False
    return ExactWeights(case, float(amplitude), slope, _rms(e_x - e_a) / _rms(e_a), _rms(k_x - k_a) / _rms(k_a),
                        _rms(f_x[:, transverse] - f_a[:, transverse]) / _rms(f_a[:, transverse]))


def scaled_states(case, states, s):
    """The reduced states scaled in the moderate-rotation ordering: v, psi by s, the axial DOFs
    (u of every node, the slider co-ordinate) by s^2."""
    mesh = Model.from_case(case).mesh
    out = np.array(states, dtype=float) * s
    axial = [mesh.reduced_index(k, U) for k in range(case.n_elements + 1)
             if mesh.reduced_index(k, U) is not None] + [mesh.reduced_coordinates()[0]]
    out[:, axial] *= s
    return out


def scaled(case, steady, factors=(1.0, 0.5, 0.25, 0.125)):
    """[ExactWeights] of one steady revolution scaled by each factor (scaled_states)."""
    return [replace(weigh(case, steady.t, scaled_states(case, steady.states, s)), amplitude=s * steady.amplitude)
            for s in factors]


def weights_table(eps_values, omegas, n_elements):
    """([ExactWeights], {(eps, Omega*): (consistent SteadyState, exact SteadyState)}, skipped)."""
    from ..analyses.steady import steady_states
    from .term_weights import consistent_case
    cases = [consistent_case(e, w, n_elements) for e in eps_values for w in omegas]
    exacts = [exact_case(c) for c in cases]
    states = steady_states(cases + exacts)
    out, pairs, skipped = [], {}, []
    for case, st, st_x in zip(cases, states[:len(cases)], states[len(cases):]):
        pairs[(case.eps, case.omega)] = (st, st_x)
        if st.ok:
            out.append(weigh(case, st.t, st.states, st.amplitude))
        else:
            skipped.append((case, st.status, st.message))
    return out, pairs, skipped


def _num(x, fmt="{:.3g}"):
    return "—" if x is None or not np.isfinite(x) else fmt.format(x)


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n" + "\n".join(lines) + "\n"


SCALE_CASE = (0.01, 0.8)                  # the revolution read at scaled amplitudes (7.3)
FACTORS = (1.0, 0.5, 0.25, 0.125, 0.0625)


def section_numbers(eps_values, omegas, n_elements, facts=None):
    """Sections 7.2 and 7.3 of the audit (Markdown); facts, if given, receives the weights."""
    weights, pairs, skipped = weights_table(eps_values, omegas, n_elements)
    out = ["\n### 7.2 Weights along steady revolutions of the consistent model\n\n"
           f"The consistent model (approach A, element-mean membrane strain, {n_elements} elements) at its "
           "periodic steady state; along that revolution A's deformation is measured by A's strain and "
           "curvature and by the exact ones, and its transverse state is read by the exact rod's generated "
           "elastic kernel (`model=\"exact\"`, its own axial unknowns settled to A's axial forces). "
           "Columns: the largest slope $|v_{,x}|$ (the ordering's $\\delta$); the RMS over the revolution "
           "of the exact stretch of A's field less A's strain (element midpoints), relative to the RMS of A's; the same "
           "for the curvature (element ends and midpoints); the RMS of the exact rod's transverse elastic "
           "force less A's, relative to the RMS of A's; then the exact rod's own steady amplitude and "
           "its change from the consistent model's.\n"]
    rows = []
    for w in weights:
        _, st_x = pairs[(w.case.eps, w.case.omega)]
        change = (f"{(st_x.amplitude - w.amplitude) / w.amplitude:+.2%}" if st_x.ok else st_x.status)
        rows.append([f"{w.case.eps:g}", f"{w.case.omega:g}", f"{w.amplitude:.4g}", _num(w.slope),
                     _num(w.membrane), _num(w.curvature), _num(w.transverse),
                     f"{st_x.amplitude:.4g}" if st_x.ok else st_x.status, change])
    out.append(_table(["eps", "Omega*", "v* (A)", "max abs v_x", "membrane", "curvature",
                       "transverse force", "v* (exact)", "change"], rows))
    if skipped:
        out.append("\nNot periodic with the crank period (no weights): "
                   + "; ".join(f"eps = {c.eps:g}, Omega* = {c.omega:g}: {s} ({m})" for c, s, m in skipped) + "\n")
    base = next((w for w in weights if (w.case.eps, w.case.omega) == SCALE_CASE), None)
    scaled_rows = []
    if base is not None:
        st, _ = pairs[SCALE_CASE]
        series = scaled(base.case, st, FACTORS)
        out.append("\n### 7.3 The weights against the amplitude\n\n"
                   f"The revolution of eps = {SCALE_CASE[0]:g}, Omega* = {SCALE_CASE[1]:g} read at amplitudes "
                   "scaled in the ordering of 7.1 ($v$, $\\psi$ by $s$; $u$ and the slider co-ordinate by "
                   "$s^2$). Every difference A drops is of relative order $\\delta^2$ (7.1), so each weight "
                   "should fall fourfold per halving, slope 2 in $\\log$ weight against $\\log s$ (the "
                   "columns 'slope': $\\log_2$ of the ratio to the previous row).\n")
        prev = None
        for s, w in zip(FACTORS, series):
            slopes = (["—"] * 3 if prev is None else
                      [_num(np.log2(getattr(prev, k) / getattr(w, k)) / np.log2(prev.amplitude / w.amplitude), "{:.2f}")
                       for k in ("membrane", "curvature", "transverse")])
            scaled_rows.append(w)
            out_row = [f"{s:g}", f"{w.amplitude:.4g}", _num(w.slope), _num(w.membrane), slopes[0],
                       _num(w.curvature), slopes[1], _num(w.transverse), slopes[2]]
            out.append(("" if prev is not None else _table_head()) + "| " + " | ".join(out_row) + " |\n")
            prev = w
    if facts is not None:
        facts.update(exact_weights=weights, exact_pairs=pairs, exact_scaled=scaled_rows)
    out.append(_observations(weights, scaled_rows))
    return "".join(out)


def _table_head():
    header = ["s", "v*", "max abs v_x", "membrane", "slope", "curvature", "slope", "transverse force", "slope"]
    return "\n| " + " | ".join(header) + " |\n|" + "|".join("---" for _ in header) + "|\n"


def _observations(weights, scaled_rows):
    if not weights:
        return ""
    big = max(weights, key=lambda w: w.transverse)
    lines = ["\nRead off the tables:\n",
             f"- The largest transverse weight is {big.transverse:.3g} (eps = {big.case.eps:g}, Omega* = "
             f"{big.case.omega:g}, slopes up to {big.slope:.3g}): there the exact rod's elastic force differs "
             f"from A's by that fraction of A's, at the same state. The membrane difference reaches "
             f"{max(w.membrane for w in weights):.3g} of A's membrane strain and the curvature difference "
             f"{max(w.curvature for w in weights):.3g} of A's curvature.\n"]
    if len(scaled_rows) >= 2:
        a, b = scaled_rows[-2], scaled_rows[-1]
        lines.append(f"- At the smallest amplitudes of 7.3 the weights fall as "
                     f"$s^{{{np.log2(a.membrane / b.membrane):.2f}}}$ (membrane), "
                     f"$s^{{{np.log2(a.curvature / b.curvature):.2f}}}$ (curvature) and "
                     f"$s^{{{np.log2(a.transverse / b.transverse):.2f}}}$ (transverse force): the order 2 "
                     f"of the series of 7.1.\n")
    return "".join(lines)
