"""Field symbols of the audit (u, v, psi, their rates and x-derivatives, the abscissa x, the
section co-ordinate y, the axial force P), their LaTeX names, and the split of an expression by order."""

import sympy as sp

from .. import symbols as s
from ..groups import _degree, _terms


APPROACHES = ("A", "B", "C")


# ---------------------------------------------------------------------------------------------
# Field symbols
# ---------------------------------------------------------------------------------------------
u, v, psi = sp.symbols("u v psi", real=True)
ud, vd, psid = sp.symbols("ud vd psid", real=True)
udd, vdd, psidd = sp.symbols("udd vdd psidd", real=True)
u_x, v_x, v_xx, v_xxx = sp.symbols("u_x v_x v_xx v_xxx", real=True)
ud_x, vd_x, vd_xx = sp.symbols("ud_x vd_x vd_xx", real=True)
x = sp.Symbol("x", real=True)      # abscissa along the undeformed rod: x0 + l zeta in an element
y = sp.Symbol("y", real=True)      # cross-section co-ordinate of eq. (1)
P = sp.Symbol("P", real=True)      # axial force of eq. (3) and (B9)

COORDS, RATES, ACCELS = (u, v, psi), (ud, vd, psid), (udd, vdd, psidd)
GRADIENTS, GRADIENT_RATES = (u_x, v_x, v_xx), (ud_x, vd_x, vd_xx)
RATE_OF = dict(zip(COORDS + GRADIENTS, RATES + GRADIENT_RATES))

_NODES = (("u", "i"), ("v", "i"), (r"\psi", "i"), ("u", "{i+1}"), ("v", "{i+1}"), (r"\psi", "{i+1}"))
_SLIDER_NODES = (("u", "{n+1}"), ("v", "{n+1}"))


def _node_names(syms, nodes, accent):
    """LaTeX names of nodal symbols, e.g. accent 'dot' -> \\dot{u}_{i+1}."""
    return {sym: (rf"\{accent}{{{base}}}" if accent else base) + "_" + index
            for sym, (base, index) in zip(syms, nodes)}


FIELD_LATEX_NAMES = {
    s.rhoA: r"\rho A", s.rhoI: r"\rho I", s.EA: "EA", s.EI: "EI", s.mu: r"\mu", s.ms: "m_s",
    s.L: "L", s.l: "l", s.x0: "x_0", s.a: "a", s.zeta: r"\zeta",
    s.theta: r"\theta", s.thetad: r"\dot{\theta}", s.phi: r"\phi", s.phid: r"\dot{\phi}",
    s.phidd: r"\ddot{\phi}",
    u: "u", v: "v", psi: r"\psi", ud: r"\dot{u}", vd: r"\dot{v}", psid: r"\dot{\psi}",
    udd: r"\ddot{u}", vdd: r"\ddot{v}", psidd: r"\ddot{\psi}",
    u_x: "u_{,x}", v_x: "v_{,x}", v_xx: "v_{,xx}", v_xxx: "v_{,xxx}",
    ud_x: r"\dot{u}_{,x}", vd_x: r"\dot{v}_{,x}", vd_xx: r"\dot{v}_{,xx}", x: "x", y: "y", P: "P",
}
for _syms, _nodes in ((s.q, _NODES), (s.qs, _SLIDER_NODES)):
    FIELD_LATEX_NAMES.update(_node_names(_syms, _nodes, ""))
for _syms, _nodes in ((s.qd, _NODES), (s.qsd, _SLIDER_NODES)):
    FIELD_LATEX_NAMES.update(_node_names(_syms, _nodes, "dot"))
for _syms, _nodes in ((s.qdd, _NODES), (s.qsdd, _SLIDER_NODES)):
    FIELD_LATEX_NAMES.update(_node_names(_syms, _nodes, "ddot"))


def order_split(expr, variables):
    """{total degree in `variables`: part of expr}, ascending degree (terms of each order)."""
    parts = {}
    for term in _terms(expr):
        k = _degree(term, variables)
        parts[k] = parts.get(k, sp.Integer(0)) + term
    return dict(sorted(parts.items()))
