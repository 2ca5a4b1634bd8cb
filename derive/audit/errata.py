"""Verdicts on the transcription problems of the printed equations (docs/errata.md, same order), and
the conventions of the derivation that follow from eq. (7)."""

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from .. import symbols as s
from ..energies import moving_frame_velocity
from ..euler_lagrange import gradient
from ..groups import SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from ..shape_functions import N_U, N_V
from .densities import eq2_density, kinetic_parts, section_strain_energy
from .field_symbols import psid, u, u_x, ud, v, v_xx, v_xxx, vd, y
from .newmark import leading_order, newmark_defects, newmark_eq37_residual
from .residuals import printed_set, rod_T, slider_inertia
from .units import FORCE, dimensions


@dataclass(frozen=True)
class Evidence:
    label: str       # what was computed (plain text, may hold $...$ LaTeX)
    value: object    # SymPy expression, tuple of dimensions, bool or number


@dataclass(frozen=True)
class Verdict:
    item: str        # "eq. (1)", ...
    key: str         # identifier: "eq1", "B3", "eq29", "eq37", "eq39", "B15/B16"
    evidence: tuple
    verdict: str     # "confirmed", "refuted", "confirmed (typesetting only)"


def _verdict(ok):
    return "confirmed" if ok else "refuted"


def erratum_eq1():
    """Eq. (1): only the bending term -y v_xx reproduces eq. (2); -y v_xxx is not even a strain."""
    with_vxx = sp.expand(section_strain_energy(v_xx) - eq2_density())
    with_vxxx = sp.expand(section_strain_energy(v_xxx) - eq2_density())
    strain_dims, printed_dims = dimensions(u_x), dimensions(y * v_xxx)
    ok = with_vxx == 0 and with_vxxx != 0 and printed_dims != strain_dims and dimensions(y * v_xx) == strain_dims
    return Verdict("eq. (1)", "eq1", (
        Evidence(r"$\frac{E}{2}\int_A e_{xx}^2\,dA$ - eq. (2), bending term $-y v_{,xx}$", with_vxx),
        Evidence(r"$\frac{E}{2}\int_A e_{xx}^2\,dA$ - eq. (2), bending term $-y v_{,xxx}$ (as printed)", with_vxxx),
        Evidence(r"(M, L, T) exponents of $u_{,x}$ (a strain)", strain_dims),
        Evidence(r"(M, L, T) exponents of $y\,v_{,xxx}$", printed_dims),
    ), _verdict(ok))


def erratum_b3():
    """(B3): T's term linear in {qd} is the exact {m3}; its rotary part is -rho I phid {N_psi}."""
    exact_m3 = gradient(rod_T(), s.qd).xreplace({c: 0 for c in tuple(s.q) + tuple(s.qd)})
    d_corrected = (exact_m3 - printed_set(True)["m3"]).applyfunc(sp.expand)
    d_printed = (exact_m3 - printed_set(False)["m3"]).applyfunc(sp.expand)
    psid_coefficient = sp.expand(kinetic_parts()["m3"]).coeff(psid)
    rows_printed = tuple(dimensions(e) for e in printed_set(False)["m3"])
    rows_corrected = tuple(dimensions(e) for e in printed_set(True)["m3"])
    ok = (d_corrected == sp.zeros(s.ELEMENT_DOFS, 1) and d_printed != sp.zeros(s.ELEMENT_DOFS, 1)
          and all(len(r) <= 1 for r in rows_corrected) and any(len(r) > 1 for r in rows_printed))
    return Verdict("(B3)", "B3", (
        Evidence(r"coefficient of $\dot\psi$ in the kinetic energy density (terms linear in rates)", psid_coefficient),
        Evidence(r"exact $\{m_3\} = \partial T_i/\partial\{\dot q\}$ at $\{q\}=\{\dot q\}=0$, minus (B3) corrected", sp.ImmutableMatrix(d_corrected)),
        Evidence(r"exact $\{m_3\}$ minus (B3) as printed", sp.ImmutableMatrix(d_printed)),
        Evidence("(M, L, T) exponents of the rows of (B3) as printed", rows_printed),
        Evidence("(M, L, T) exponents of the rows of (B3) corrected", rows_corrected),
    ), _verdict(ok))


def erratum_eq29():
    """Eq. (29): the exact slider equations need -d/dt {m_s4}; -{m_s4} mixes momentum and force."""
    exact = slider_inertia("lagrange")
    d_corrected = (exact - slider_inertia("paper")).applyfunc(sp.expand)
    d_printed = (exact - slider_inertia("printed")).applyfunc(sp.expand)
    groups_corrected = tuple(group_vector(d_corrected, SLIDER_VARS, SLIDER_AXIAL_ROWS))
    rows_printed = tuple(dimensions(e) for e in slider_inertia("printed"))
    rows_corrected = tuple(dimensions(e) for e in slider_inertia("paper"))
    ok = (set(groups_corrected) <= {"gyroscopic", "phidd"} and "forcing" in group_vector(d_printed, SLIDER_VARS, SLIDER_AXIAL_ROWS)
          and all(r == (FORCE,) for r in rows_corrected) and any(len(r) > 1 for r in rows_printed))
    return Verdict("eq. (29)", "eq29", (
        Evidence("exact slider equations minus eqs. (27)-(29) with $-\\{\\dot m_{s4}\\}$", sp.ImmutableMatrix(d_corrected)),
        Evidence("groups of that difference", groups_corrected),
        Evidence("exact slider equations minus eqs. (27)-(29) as printed ($-\\{m_{s4}\\}$)", sp.ImmutableMatrix(d_printed)),
        Evidence("(M, L, T) exponents of the slider rows, as printed", rows_printed),
        Evidence("(M, L, T) exponents of the slider rows, corrected", rows_corrected),
    ), _verdict(ok))


def erratum_eq37():
    """Eq. (37) (brace aside) is the equation of motion at t_{m+1} under eqs. (38) and corrected (39)."""
    residual = newmark_eq37_residual("corrected")
    ok = residual == 0
    return Verdict("eq. (37)", "eq37", (
        Evidence(r"$M a + C v + K d - F$ at $t_{m+1}$ with $a$ from (37), $d$ from (38), $v$ from corrected (39)", residual),
    ), "confirmed (typesetting only)" if ok else "refuted")


def erratum_eq39():
    """Eq. (39): the printed corrector is inconsistent with eq. (37) and with the motion (defect O(dt))."""
    printed_residual = newmark_eq37_residual("printed")
    defects, h = newmark_defects()
    orders = {name: leading_order(d, h) for name, d in defects.items()}
    ok = (newmark_eq37_residual("corrected") == 0 and printed_residual != 0
          and orders["velocity, as printed"] <= 1 and orders["velocity, corrected"] >= 3)
    return Verdict("eq. (39)", "eq39", (
        Evidence(r"$M a + C v + K d - F$ at $t_{m+1}$ with the printed corrector $\tilde v_m + \gamma\Delta t\,a$", printed_residual),
        Evidence(r"local defect of the corrected velocity update ($\gamma = 1/2$; $d^{(k)}$ the $k$-th "
                 r"derivative of the motion at $t_m$, $h = \Delta t$)", defects["velocity, corrected"]),
        Evidence(r"local defect of the printed velocity update", defects["velocity, as printed"]),
        Evidence(r"local defect of the displacement update (35), (38) ($\beta = 1/4$)", defects["displacement, eq. (38)"]),
        Evidence("leading power of h in each defect", tuple(sorted(orders.items()))),
    ), _verdict(ok))


def erratum_b15_b16():
    """(B15)/(B16): the slider's (u, v) are the element's end-node values only at zeta = 1."""
    e_u, e_v = sp.zeros(s.ELEMENT_DOFS, 1), sp.zeros(s.ELEMENT_DOFS, 1)
    e_u[s.element_slots(1, ("u",))[0]], e_v[s.element_slots(1, ("v",))[0]] = 1, 1
    roots = sp.solve(list(N_U - e_u) + list(N_V - e_v), s.zeta, dict=True)
    end_abscissa = (s.x0 + s.l * s.zeta).subs({s.zeta: 1, s.x0: s.L - s.l})
    ok = roots == [{s.zeta: 1}] and end_abscissa == s.L
    return Verdict("(B15)/(B16)", "B15/B16", (
        Evidence(r"solutions $\zeta$ of $\{N_u\}(\zeta) = e_{u_{i+1}}$, $\{N_v\}(\zeta) = e_{v_{i+1}}$", tuple(r[s.zeta] for r in roots)),
        Evidence(r"$x_0 + l\zeta$ of element $n$ ($x_0 = L - l$) at $\zeta = 1$, the $L$ in (B15)-(B16)", end_abscissa),
    ), _verdict(ok))


@lru_cache(maxsize=None)
def errata_verdicts():
    """One Verdict per transcription problem of the printed equations (docs/errata.md, same order)."""
    return (erratum_eq1(), erratum_b3(), erratum_eq29(), erratum_eq37(), erratum_eq39(), erratum_b15_b16())


def convention_checks():
    """Conventions of the derivation (docs/errata.md): basis rates, eq. (7) from R = a e_r + xi e_i + eta e_j, the rigid rod
    angle sin phi = (a/L) sin theta and eq. (26), both from the slider staying on the X axis."""
    t = sp.Symbol("t", real=True)
    xi, eta, xid, etad = sp.symbols("xi eta xid etad", real=True)
    u_s, v_s = s.qs
    th, ph, xi_t, eta_t = (sp.Function(n, real=True)(t) for n in ("theta", "phi", "xi", "eta"))
    to_symbols = {th.diff(t): s.thetad, ph.diff(t): s.phid, xi_t.diff(t): xid, eta_t.diff(t): etad}
    to_plain = {th: s.theta, ph: s.phi, xi_t: xi, eta_t: eta}
    flat = lambda e: sp.simplify(sp.expand_trig(e.subs(to_symbols).subs(to_plain)))

    e_r = sp.Matrix([sp.cos(th), sp.sin(th)])
    e_i, e_j = sp.Matrix([sp.cos(ph), -sp.sin(ph)]), sp.Matrix([sp.sin(ph), sp.cos(ph)])
    basis_i = (e_i.diff(t) + ph.diff(t) * e_j).applyfunc(flat)
    basis_j = (e_j.diff(t) - ph.diff(t) * e_i).applyfunc(flat)

    R_dot = (s.a * e_r + xi_t * e_i + eta_t * e_j).diff(t)
    frame_i, frame_j = moving_frame_velocity(xi, eta, xid, etad)
    velocity = (flat((R_dot.T * e_i)[0] - frame_i), flat((R_dot.T * e_j)[0] - frame_j))

    eq7_i = -s.a * s.thetad * sp.sin(s.theta + s.phi) + ud + v * s.phid                 # eq. (7)
    eq7_j = s.a * s.thetad * sp.cos(s.theta + s.phi) - (s.L + u) * s.phid + vd
    slider_i, slider_j = moving_frame_velocity(s.L + u, v, ud, vd)
    eq7 = (sp.expand(slider_i - eq7_i), sp.expand(slider_j - eq7_j))

    slider_Y = (s.a * e_r + (s.L + u_s) * e_i + v_s * e_j)[1].subs(to_plain)
    rigid_Y = slider_Y.subs({u_s: 0, v_s: 0})
    rigid = sp.solve(rigid_Y, sp.sin(s.phi))
    flexible = sp.solve(sp.expand(slider_Y - rigid_Y), v_s)
    return (
        Evidence(r"$\dot e_i + \dot\phi\, e_j$", sp.ImmutableMatrix(basis_i)),
        Evidence(r"$\dot e_j - \dot\phi\, e_i$", sp.ImmutableMatrix(basis_j)),
        Evidence(r"$\dot R\cdot e_i$, $\dot R\cdot e_j$ of $R = a e_r + \xi e_i + \eta e_j$ minus the "
                 "derivation's moving-frame velocity", velocity),
        Evidence("derivation's slider velocity ($\\xi = L + u$, $\\eta = v$) minus eq. (7) as printed", eq7),
        Evidence(r"rigid rod, slider on the $X$ axis: $\sin\phi$", tuple(rigid)),
        Evidence(r"flexible rod, slider end on the $X$ axis: $v_{n+1}$ in terms of $u_{n+1}$ (eq. 26)",
                 tuple(flexible)),
    )
