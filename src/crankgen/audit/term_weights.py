"""Weight of each term group of the consistent model along real steady trajectories (audit §4).

The consistent model (lagrange formulation, approach A, Kelvin-Voigt damping) is split by kind of
term with the symbolic audit's classification (generated/groups.py).  Along one steady revolution
each group's generalized force is assembled on the reduced DOFs (constraint applied) and its RMS
over the revolution is compared with that of the total elastic force dU/dq, separately for the
axial DOFs (u of every node and the slider co-ordinate s) and the transverse ones (v, psi).
A second measure switches each group off alone and reports the change of the steady amplitude.
"""

from dataclasses import dataclass

import numpy as np

from .. import engine
from ..declaration import ingredients
from .._generated import groups as _groups
from ..declaration.cases import Case
from ..discrete.constraints import project_residual
from ..discrete.mesh import NDOF, U
from ..discrete.system import Model
from ..analyses.steady import steady_states

ELASTIC_GROUPS = ("stiffness", "cubic_axial", "cubic_transverse", "quartic")
KINETIC_GROUPS = ("inertia", "gyroscopic", "phidd", "centrifugal", "forcing")
DAMPING_GROUPS = ("damping_linear", "damping_q1", "damping_q2")
ALL_GROUPS = KINETIC_GROUPS + ELASTIC_GROUPS + DAMPING_GROUPS


def consistent_case(eps, omega, n_elements=8, **kw):
    """The consistent model of the audit: lagrange, A, Kelvin-Voigt, element-mean membrane strain."""
    return Case(eps=eps, omega=omega, approach="A", model="consistent", n_elements=n_elements, **kw)


@dataclass(frozen=True)
class GroupWeights:
    case: Case
    amplitude: float
    transverse: dict          # group -> RMS |F_g| / RMS |F_elastic| on v, psi DOFs
    axial: dict               # same on u, s DOFs
    balance: float            # RMS |sum of all groups| / RMS |F_elastic| (Newton residual: ~0)


def _kernel(source, group, averaged):
    name = f"{source}{'_averaged' if averaged and source in ('rod_elastic_A', 'kelvin_voigt_A') else ''}__{group}"
    return getattr(_groups, name, None)


def group_weights(case, steady):
    """GroupWeights of one periodic steady state (steady.state must be set)."""
    averaged = case.membrane == "averaged"
    model = Model.from_case(case)
    mesh, N = model.mesh, model.n_dofs
    geo, coef = model.geometry, model.coefficients
    batch = engine.Batch([case])
    res = engine.march_state(batch, case.steps_per_rev, steady.state[None], keep_history=True)
    axial = np.zeros(N, dtype=bool)
    for node in range(1, mesh.n_elements + 1):
        axial[mesh.reduced_index(node, U)] = True
    sums = {g: np.zeros(2) for g in ALL_GROUPS}
    elastic_sum, balance_sum = np.zeros(2), np.zeros(2)
    steps = case.steps_per_rev
    for k in range(steps):             # one revolution (the last point repeats the first)
        t = k * float(batch.dt[0])
        kin = model.kinematics(t)
        q, qd, qdd, E = model.nodal_state(kin, res.D_history[0, k], res.V_history[0, k],
                                          res.A_history[0, k])
        element = (q, qd, qdd, geo, coef, kin.vector)
        held = mesh.holders()
        e = held[0][0]                  # the element whose node the end mass sits on
        last = (q[e], qd[e], qdd[e], geo[e], coef, kin.vector)
        vectors = {}
        for g in ALL_GROUPS:
            r = np.zeros((mesh.n_elements, NDOF))
            if g in KINETIC_GROUPS:
                r += _kernel("rod_inertia", g, averaged)(*element)[0]
                slider = _kernel("slider_inertia", g, averaged)
                if slider is not None:
                    r[e] += slider(*last)[0]
            elif g in ELASTIC_GROUPS:
                r += _kernel("rod_elastic_A", g, averaged)(*element)[0]
            else:
                r += _kernel("kelvin_voigt_A", g, averaged)(*element)[0]
            for h, slots, reduced in held:
                r[h] = project_residual(E, r[h], slots, reduced)
            vectors[g] = model.assembler.vector(r)
        elastic = sum(vectors[g] for g in ELASTIC_GROUPS)
        total = sum(vectors.values())
        for g, vec in vectors.items():
            sums[g] += [np.sum(vec[~axial] ** 2), np.sum(vec[axial] ** 2)]
        elastic_sum += [np.sum(elastic[~axial] ** 2), np.sum(elastic[axial] ** 2)]
        balance_sum += [np.sum(total[~axial] ** 2), np.sum(total[axial] ** 2)]
    ref = np.sqrt(elastic_sum)
    ratio = {g: np.sqrt(v) / ref for g, v in sums.items()}
    return GroupWeights(case, steady.amplitude,
                        transverse={g: float(r[0]) for g, r in ratio.items()},
                        axial={g: float(r[1]) for g, r in ratio.items()},
                        balance=float(np.max(np.sqrt(balance_sum) / ref)))


def weights_table(eps_values=(0.01, 0.1), omegas=(0.1, 0.2, 0.4, 0.6, 0.8, 1.0), n_elements=8):
    """GroupWeights for every (eps, Omega*) of the audit (non-periodic cases are skipped, listed)."""
    cases = [consistent_case(e, w, n_elements) for e in eps_values for w in omegas]
    out, skipped = [], []
    for case, st in zip(cases, steady_states(cases)):
        if st.ok:
            out.append(group_weights(case, st))
        else:
            skipped.append((case, st.status, st.message))
    return out, skipped


def switch_off_table(eps_values=(0.01, 0.1), omegas=(0.1, 0.2, 0.4, 0.6, 0.8, 1.0), n_elements=8):
    """{(eps, Omega*): {group: SteadyState}} with each switchable group removed alone ("" = none)."""
    groups = ("",) + ingredients.SWITCHABLE_GROUPS
    cases = [consistent_case(e, w, n_elements, groups_off=g)
             for e in eps_values for w in omegas for g in groups]
    results = steady_states(cases)
    table = {}
    for case, st in zip(cases, results):
        table.setdefault((case.eps, case.omega), {})[case.groups_off] = st
    return table
