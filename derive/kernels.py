"""Stage 7: kernel specifications (name, ordered inputs, outputs, expressions), made from the model
representation (derive/representation.py) alone, grouped by generated module.

One calling convention per kernel kind:
- element kernels (one per family variant, module `elements`):
      name(q, qd, qdd, geo, coef, kin) -> r, K, C, M [, K_printed]
  q, qd, qdd: the element's nodal vector and rates (eq. 14); geo = (l, x0); coef = the coefficients
  (rho A, rho I, E A, E I, mu, m_s, gX, gY, the term weights); kin = the kinematics vector (a,
  theta, thetad, phi, phid, phidd, thetadd, beta, betad, betadd).  r is the element residual, K, C,
  M its exact derivatives with respect to q, qd, qdd; K_printed, where a variant declares one, is
  the stiffness the printed one-pass scheme of eq. (37) iterates with.
- energy kernels (module `energy`): name(q, qd, geo, coef, kin) -> scalar.
- output kernels (module `fields`): step_<name>(inputs) and field_<name>[_<case>](inputs) -> value,
  the inputs being those the output's record names (representation.OUTPUT_INPUTS order).
- kinematics kernels (module `kinematics`): motion_<m>(t, params) -> crank = (theta, thetad,
  thetadd); guide_<g>(crank, params) -> kin; end_map_<g>(send, kin, params) -> E (8, 2) with
  send = (s, sd, sdd) (rows: guides.END_MAP_ROWS); rigid_end_<g>(kin, params) -> (X, Y);
  margins_<g>(params); end_scale_<g>(eps, params); period_<m>(params), step_period_<m>(params);
  coordinates_<m>(kin, z, pin, params) -> (m, 3 m + 3) for a driven motion: each co-ordinate's equation
  and its derivatives (representation.coordinate_equations); start_<m>(params) -> (2, m) their start.
  params is the kinematic parameter vector (representation.kinematic_parameters).
- shape kernels (module `shape`): shape functions and the slope Gram matrix.
- audit group kernels (module `groups`): the consistent model's element forces split by kind, in
  the element convention (used by the audit to weigh each group along trajectories).
"""

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import guides as gd
from . import representation as ir
from . import symbols as s
from .euler_lagrange import jacobian


@dataclass(frozen=True)
class Input:
    name: str
    symbols: tuple      # the SymPy symbols it carries: one for a scalar, n for a trailing axis of n


@dataclass(frozen=True)
class Output:
    name: str
    expr: sp.Matrix     # column (vector output), square matrix, or 1x1 (scalar output)
    doc: str


@dataclass(frozen=True)
class Solve:
    """A scalar unknown a kernel finds before its outputs: Newton on residual(unknown) = 0 from
    `guess`, with `slope` = d residual / d unknown (derive/emit.py), then the `bound` symbols
    ((symbol, expression), ...) from it; the outputs may read the unknown and the bound symbols."""

    unknown: sp.Symbol
    guess: sp.Expr
    residual: sp.Expr
    slope: sp.Expr
    bound: tuple = ()


@dataclass(frozen=True)
class Kernel:
    name: str
    doc: str
    inputs: tuple
    outputs: tuple
    cse: bool = True             # False: each output printed as it stands (no common subexpressions)
    solve: Solve = None          # a numerical closure solved at run time before the outputs
    definitions: tuple = ()      # stages of ((symbol, expression in the inputs), ...): computed before the outputs


def scalar(sym):
    return Input(sym.name, (sym,))


def vector(name, column):
    return Input(name, tuple(column))


Q, QD, QDD = vector("q", s.q), vector("qd", s.qd), vector("qdd", s.qdd)
GEO = vector("geo", s.GEOMETRY)
COEF = vector("coef", ir.COEFFICIENT_SYMBOLS)
KIN = vector("kin", s.KINEMATICS)
PARAMS = vector("params", ir.KINEMATIC_SYMBOLS)
# the same vector beside kin, which already carries a: its slot holds an unused stand-in
PARAMS_BESIDE_KIN = vector("params", tuple(sp.Symbol("a_param") if sym == s.a else sym
                                           for sym in ir.KINEMATIC_SYMBOLS))
CRANK = vector("crank", ir.CRANK_SYMBOLS)
SEND = vector("send", ir.END_COORDINATES)
PIN = vector("pin", tuple(ir.outputs.pin))
ELEMENT_INPUTS = (Q, QD, QDD, GEO, COEF, KIN)
OUTPUT_INPUT = {name: (vector(name, syms) if len(syms) > 1 else scalar(syms[0]))
                for name, syms in ir.OUTPUT_INPUTS}


def _residual_outputs(r, printed_stiffness="exact", tangents=None):
    """r and its tangents: differentiated here, or those derived with r (`tangents`: K, C, M)."""
    K, C, M = tangents if tangents is not None else (jacobian(r, s.q), jacobian(r, s.qd), jacobian(r, s.qdd))
    outs = [Output("r", r, "element residual"), Output("K", K, "d r / d q"),
            Output("C", C, "d r / d qd"), Output("M", M, "d r / d qdd")]
    if not (isinstance(printed_stiffness, str) and printed_stiffness == "exact"):
        Kp = sp.zeros(s.ELEMENT_DOFS, s.ELEMENT_DOFS) if isinstance(printed_stiffness, str) else printed_stiffness
        outs.append(Output("K_printed", Kp.applyfunc(sp.expand), "stiffness of the printed eq. (37)"))
    return tuple(outs)


@lru_cache(maxsize=None)
def element_kernels():
    kernels = []
    for family in ir.representation().families:
        for variant in family.variants:
            kernels.append(Kernel(variant.record.kernel, f"{family.record.doc}: {variant.record.doc}.", ELEMENT_INPUTS,
                                  _residual_outputs(variant.residual, variant.printed_stiffness, variant.tangents),
                                  definitions=variant.definitions))
    return tuple(kernels)


def energy_kernels():
    inputs = (Q, QD, GEO, COEF, KIN)
    name_of = {"rod_kinetic_energy": "T", "rod_kinetic_energy_exact": "T", "slider_kinetic_energy": "T"}
    out = []
    for e in ir.representation().energies:
        label = name_of.get(e.name) or ("V" if "potential" in e.name else "U" if "strain" in e.name else "D")
        out.append(Kernel(e.name, e.doc, inputs, (Output(label, sp.Matrix([e.expr]), e.doc),)))
    return tuple(out)


def output_kernels():
    kernels = {}
    for form in ir.representation().outputs:
        o = form.record
        if o.engine:
            continue
        inputs = tuple(OUTPUT_INPUT[name] for name in o.inputs)
        for v in form.variants:
            if v.kernel not in kernels:
                where = " (at zeta = x / l of the element)" if o.kind == "field" else ""
                kernels[v.kernel] = Kernel(v.kernel, f"{o.doc}{where}.", inputs,
                                           (Output("value", sp.Matrix([v.expr]), o.name),))
    return tuple(kernels.values())


def kinematics_kernels():
    rep = ir.representation()
    t = scalar(s.t)
    out = []
    for form in rep.motions:
        m = form.record
        out.append(Kernel(f"motion_{m.name}", f"Crank angle, speed and acceleration at time t: {m.doc}.",
                          (t, PARAMS), (Output("crank", form.crank, "(theta, thetad, thetadd)"),)))
        period = form.period if form.period is not None else sp.Integer(0)
        out.append(Kernel(f"period_{m.name}", "Time of one crank revolution (0: not periodic).", (PARAMS,),
                          (Output("T", sp.Matrix([period]), "period"),)))
        out.append(Kernel(f"step_period_{m.name}", "The time steps_per_rev steps divide.", (PARAMS,),
                          (Output("T", sp.Matrix([form.step_period]), "step period"),)))
        if form.equations is not None:
            Z = vector("z", form.inputs)
            names = ", ".join(c.name for c in m.coordinates)
            out.append(Kernel(f"coordinates_{m.name}", f"The equations of the co-ordinates ({names}) of the driven "
                              "motion and their derivatives, row per co-ordinate: (g, dg/dz, dg/dzd, dg/dzdd, "
                              "dg/dpin_i, dg/dpin_j); the crank's co-ordinate is the kinematics' theta.",
                              (KIN, Z, PIN, PARAMS_BESIDE_KIN), (Output("g", form.equations, "equations"),)))
            out.append(Kernel(f"start_{m.name}", "The co-ordinates' values and rates at t = 0.", (PARAMS,),
                              (Output("z0", form.start, "start"),)))
    for form in rep.guides:
        g = form.record
        solve = None if form.closure is None else Solve(*form.closure)
        how = "" if solve is None else " (its closure by Newton at run time, the generated derivatives)"
        out.append(Kernel(f"guide_{g.name}", f"Rigid kinematics kin of the {g.name} guide{how}: {g.doc}.",
                          (CRANK, PARAMS), (Output("kin", form.kinematics, "kinematics vector"),), solve=solve))
        if solve is not None:
            out.append(Kernel(f"closure_{g.name}", f"The {g.name} guide's closure at the crank angle: "
                              "(beta, phi, its residual, its slope d residual / d beta).", (CRANK, PARAMS),
                              (Output("closure", sp.Matrix([s.beta, s.phi, solve.residual, solve.slope]),
                                      "beta, phi, residual, slope"),), solve=solve))
        out.append(Kernel(f"end_map_{g.name}", f"End map of the {g.name} guide: (u, v) of the rod's end "
                          "and its rates and derivatives in (s, sd, sdd) (rows guides.END_MAP_ROWS).",
                          (SEND, KIN, PARAMS_BESIDE_KIN), (Output("E", form.end_map, "end map"),)))
        if form.pivot is not None:          # a link carrying the end (a rocker), which may be flexible
            flexible = vector("send", gd.TIP + gd.TIP_RATES + gd.TIP_ACCELERATIONS)
            out.append(Kernel(f"end_map_{g.name}_flexible", f"End map of the {g.name} guide with a flexible rocker: the "
                              "rod's end (u, v) from the rocker tip's (u_r, v_r), equal positions at B, with its "
                              "rates and derivatives (rows guides.map_rows, m = 2).",
                              (flexible, KIN, PARAMS_BESIDE_KIN),
                              (Output("E", gd.flexible_rocker_end_map(), "end map"),)))
        out.append(Kernel(f"rigid_end_{g.name}", f"(X, Y) of the rigid end point on the {g.name} guide.",
                          (KIN, PARAMS_BESIDE_KIN), (Output("X", form.rigid_end, "rigid end point"),)))
        if g.margins:
            out.append(Kernel(f"margins_{g.name}", "Full-turn margins (each > 0 iff the crank turns a full "
                              "revolution): " + "; ".join(g.margins) + ".", (PARAMS,),
                              (Output("m", form.margins, "margins"),)))
        out.append(Kernel(f"end_scale_{g.name}", "Natural size of the end map's reduced co-ordinate.",
                          (scalar(s.eps), PARAMS), (Output("scale", sp.Matrix([form.end_scale]), "scale"),)))

    return tuple(out)


def per_step_kernels():
    """The engine's outputs (Output.engine) from its primitives: per_step(prims, q_end, parameters),
    every output printed as it stands (the engine's arithmetic: v / eps, u / eps**2, ...), and the
    Gram matrix of each integral primitive."""
    rep = ir.representation()
    engine = [form for form in rep.outputs if form.record.engine]
    values = sp.Matrix([form.variants[0].expr for form in engine])
    inputs = tuple(vector(name, syms) for name, syms in ir.ENGINE_INPUTS)
    out = [Kernel("per_step", "The outputs the engine computes at every step, in the order of the schema's "
                  "engine outputs: " + ", ".join(form.record.name for form in engine) + ".", inputs,
                  (Output("out", values, "the engine's outputs"),), cse=False)]
    for g in rep.grams:
        out.append(Kernel(g.name, "Gram matrix G of an integral over the rod: its element part is q^T G q.",
                          (scalar(s.l),), (Output("G", g.matrix, "Gram matrix"),)))
    return tuple(out)


def geometry_kernels():
    """The mechanism's geometry for figures: the crank pin, each guide's curve C(beta) and the pivot
    of a link carrying the end."""
    from .guides import PIN
    out = [Kernel("crank_pin", "(X, Y) of the crank pin A = a (cos theta, sin theta).", (KIN,),
                  (Output("X", PIN, "crank pin"),))]
    for form in ir.representation().guides:
        g = form.record
        out.append(Kernel(f"curve_{g.name}", f"(X, Y) of the {g.name} guide's curve C(beta).",
                          (scalar(s.beta), PARAMS), (Output("X", form.curve, "point of the curve"),)))
        if form.pivot is not None:
            out.append(Kernel(f"pivot_{g.name}", "(X, Y) of the ground pivot of the link carrying the end.",
                              (PARAMS,), (Output("X", form.pivot, "pivot"),)))
    return tuple(out)


def shape_kernels():
    shapes = ir.SHAPES
    return (
        Kernel("shape_functions", "Shape functions N_u, N_v, N_psi of Appendix A at zeta = x / l, and the exact "
               "rod's cubic N_u (in u and chi).",
               (scalar(s.zeta), scalar(s.l)),
               (Output("N_u", shapes["N_u"], "eq. (11)"), Output("N_v", shapes["N_v"], "eq. (12)"),
                Output("N_psi", shapes["N_psi"], "eq. (13)"), Output("N_u_cubic", shapes["N_u_cubic"], "exact rod"))),
        Kernel("slope_gram", "int_0^l {B_v}{B_v}^T dx, so that int v_x^2 dx = q^T G q (eq. 40).",
               (scalar(s.l),), (Output("G", shapes["slope_gram"], "slope Gram matrix"),)),
    )


def group_kernels():
    return tuple(Kernel(g.name, f"The '{g.group}' part of {g.source} (consistent model, approach A).",
                        ELEMENT_INPUTS, _residual_outputs(g.residual)) for g in ir.audit_groups())


MODULES = {
    "shape": ("Shape functions of Appendix A.", shape_kernels),
    "kinematics": ("Rigid kinematics: the crank motions, the guides' closures and end maps.", kinematics_kernels),
    "elements": ("Element kernels of every term family variant declared in derive/declaration.py.", element_kernels),
    "energy": ("Element energies T_i, T_s, U_i, V_i and the Kelvin-Voigt dissipation function.", energy_kernels),
    "fields": ("The declared outputs: step quantities, fields along the rod, reductions over it.", output_kernels),
    "per_step": ("The outputs the engine computes at every step, from what it accumulates.", per_step_kernels),
    "geometry": ("The guides' geometry, for figures: their curves and the pivots of links.", geometry_kernels),
    "groups": ("Element forces of the consistent model split by kind (symbolic audit).", group_kernels),
}
# modules whose element kernels also get the accumulating one-element variants (emit.py)
ACCUMULATING = ("elements",)
# modules whose kernels also get a one-element `_into` variant (the engine compiles those of
# motion_, guide_ and end_map_)
SCALAR = ("kinematics", "per_step")
