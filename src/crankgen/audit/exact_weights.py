"""What approach A drops relative to the exact strain, weighed along real trajectories (audit
section 7; the series are crankgen._derive.audit.exact_strain).

Along one steady revolution of the consistent model (approach A, element-mean membrane strain),
the same states are read twice: by approach A's declared outputs and by the geometrically exact
rod's (model="exact": the strain |r'| - 1 and kappa = ((1 + u_x) v_xx - v_x u_xx) / |r'|^2; its
cubic u takes as nodal slopes chi those of A's piecewise-linear u, crankgen.discrete.mesh.transfer),
and the two elastic forces dU/dq (A's and the exact rod's generated elastic kernels, constraint
applied, assembled on the reduced DOFs) are compared:
- membrane: RMS over the revolution and the elements of the exact strain less u_x + <v_x^2>/2 at
  the element midpoints, relative to the RMS of A's membrane strain; curvature: the same for
  kappa - v_xx at the elements' ends and midpoints, relative to the RMS of v_xx;
- force: RMS |F_exact - F_A| over RMS |F_A| on the transverse DOFs (v, psi), as section 4 weighs
  the groups (an axial DOF's elastic force is the difference of its two elements' axial forces
  EA e, weighed through the membrane strain above);
- slope: the largest |v_x| over the revolution (the ordering's delta).
Both strain differences are of relative order delta^2 (the series), so `scaled` reads the same
revolution at amplitudes scaled in the ordering (v, psi by s, u and s by s^2) to show it.
"""

from dataclasses import dataclass, replace

import numpy as np

from ..declaration import ingredients
from ..declaration.cases import exact_case  # noqa: F401  (the exact rod's case; used here and by the tests)
from .._generated import elements as _elements
from ..discrete.constraints import project_residual
from ..discrete.mesh import PSI, U, NODE_DOFS, transfer
from ..discrete.system import Model
from ..results.outputs import StateHistory


@dataclass(frozen=True)
class ExactWeights:
    case: object               # the consistent model's case
    amplitude: float           # its steady max |v*(1/2)|
    slope: float               # the largest |v_x| over the revolution
    membrane: float            # RMS (lambda - 1 - e_A) / RMS e_A
    curvature: float           # RMS (kappa - v_xx) / RMS v_xx
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


def weigh(case, t, states, amplitude=np.nan):
    """ExactWeights of the reduced states (steps, N) at times t of a consistent-model case."""
    exact = exact_case(case)
    model_a, model_x = Model.from_case(case), Model.from_case(exact)
    states_x = transfer(states, model_a.mesh, model_x.mesh)         # chi: the nodal slopes of A's u
    a_hist, x_hist = StateHistory(case, t, states), StateHistory(exact, t, states_x)
    n = case.n_elements
    mids = (np.arange(n) + 0.5) / n
    e_a = a_hist.field("surface_strain", mids, fiber=0.0)
    e_x = x_hist.field("surface_strain", mids, fiber=0.0)
    points = np.concatenate([np.arange(n) / n + 1e-9, mids, np.arange(1, n + 1) / n - 1e-9])
    k_a = a_hist.field("bending_moment", points)
    k_x = x_hist.field("bending_moment", points)
    q = a_hist.element_vectors()
    slope = float(np.max(np.abs(q[..., [PSI, NODE_DOFS + PSI]])))
    f_a = _reduced_forces(model_a, t, states)
    f_x = transfer(_reduced_forces(model_x, t, states_x), model_x.mesh, model_a.mesh)   # A's rows
    mesh = model_a.mesh
    axial = np.zeros(mesh.n_dofs, dtype=bool)
    axial[[mesh.reduced_index(k, U) for k in range(n + 1) if mesh.reduced_index(k, U) is not None]] = True
    axial[mesh.reduced_coordinates()[0]] = True
    return ExactWeights(case, float(amplitude), slope, _rms(e_x - e_a) / _rms(e_a), _rms(k_x - k_a) / _rms(k_a),
                        _rms(f_x[:, ~axial] - f_a[:, ~axial]) / _rms(f_a[:, ~axial]))


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
           "periodic steady state; along that revolution the same states are read by approach A and by "
           "the exact rod (`model=\"exact\"`: its declared outputs and its generated elastic kernel). "
           "Columns: the largest slope $|v_{,x}|$ (the ordering's $\\delta$); the RMS over the revolution "
           "of the exact element stretch less A's membrane strain, relative to the RMS of A's; the same "
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
