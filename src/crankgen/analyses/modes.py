"""Natural frequencies and mode shapes of the mechanism frozen at a crank angle.

The mechanism turns at crank speed Omega*; at crank angle theta its rigid motion loads the rod
axially (the inertia of the rod and of the end mass along the rod, and gravity's component
along it).  The frozen state is the rod straight and stretched by those loads: the axial rows of
the model's own quasi-static equations R(d, 0, 0) = 0 (eq. 30 with the state at rest in the
moving frame) solved for the axial displacements and the end co-ordinate, the transverse
displacements and slopes held at zero.  (The transverse loads of the rigid motion make the
forced response, not a change of stiffness, and are left out: so the state exists at any speed.)

The modes are those of the model's tangent at that state, from the generated kernels with the end
constraint applied (crankgen.discrete.system.Model: eq. 30's K and M, the projection of
crankgen.discrete.constraints): K phi = lambda M phi, frequency sqrt(lambda).  K holds what the derivation
gives at the state: the elastic stiffness, the geometric stiffness of the axial force (approaches
A and B, both formulations; approach C has none), the centrifugal softening of the rod's rotation
and the end map's terms; nothing is derived here.  The damping and gyroscopic (Coriolis) terms of
C are left out: these are the undamped natural frequencies.  lambda < 0 is a frozen state that
buckles (the axial force beyond the rod's buckling load): its frequency is reported as 0 and the
mode as divergent.

Units: frequencies in units of omega_b (rad per unit of crankgen's time; the pinned-pinned rod's
k-th bending frequency is k^2), or rad/s and Hz for a crankgen.SIMechanism (units="si", any guide).
"""

from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from ..discrete import kinematics as _kinematics
from ..declaration import schema
from ..declaration.cases import run_case
from ..errors import ConvergenceError, ParameterError
from ..discrete.constraints import tangents
from ..discrete.mesh import CHI, PSI, ROCKER, U, V
from ..discrete.system import Model
from ..declaration.si import SIMechanism
from ..declaration.units import Scales
from ..declaration.validation import angle, choice, finite_number, integer
from .blas import single_thread

UNITS = ("crankgen", "si")
AXIAL_SHARE = 0.5              # a mode whose kinetic energy is more than half axial is "axial"
NEWTON_TOL = 1e-12
NEWTON_ITERATIONS = 30


@dataclass(frozen=True)
class Modes:
    """The lowest natural frequencies and mode shapes of a mechanism frozen at crank angle theta
    (rad) and crank speed omega (Omega*).

    frequencies: (count,) in units of omega_b, ascending (0 for a divergent mode);
    omega_squared: (count,) the eigenvalues lambda (negative: the frozen state buckles);
    kinds: "bending" or "axial" (the larger share of the mode's kinetic energy);
    axial_share: (count,) that share; shapes: (count, n + 1, 3) u, v and the slope psi of every
    node (x* = i / n) in the moving frame of the rigid rod, scaled so that the largest |u| or |v|
    is 1 and positive; axial_force: (n,) N* = N L^2 / EI of each element in the frozen state;
    frozen: the frozen state's reduced displacements.  In SI (a crankgen.SIMechanism):
    frequencies_si (rad/s) and hz."""

    case: object
    theta: float
    omega: float
    frequencies: np.ndarray
    omega_squared: np.ndarray
    kinds: tuple
    axial_share: np.ndarray
    shapes: np.ndarray = field(repr=False)
    axial_force: np.ndarray = field(repr=False)
    frozen: np.ndarray = field(repr=False)
    scales: Optional[Scales] = field(default=None, repr=False)

    @property
    def divergent(self):
        return self.omega_squared < 0

    @property
    def frequencies_si(self):
        """rad/s (a mechanism given in SI)."""
        if self.scales is None:
            raise ParameterError("these modes were computed in crankgen's units: frequencies_si needs "
                                 "modes(crankgen.SIMechanism(...), units='si')")
        return self.frequencies * self.scales.omega_b

    @property
    def hz(self):
        return self.frequencies_si / (2 * np.pi)

    def table(self):
        """Rows {mode, kind, frequency, omega_squared, axial_share[, frequency_rad_per_s, frequency_Hz]}."""
        rows = []
        for j in range(len(self.frequencies)):
            row = dict(mode=j + 1, kind=self.kinds[j], frequency=float(self.frequencies[j]),
                       omega_squared=float(self.omega_squared[j]), axial_share=float(self.axial_share[j]))
            if self.scales is not None:
                row.update(frequency_rad_per_s=float(self.frequencies_si[j]), frequency_Hz=float(self.hz[j]))
            rows.append(row)
        return rows


def _axial_dofs(mesh):
    """Reduced indices of the axial unknowns: u of the interior nodes (and the exact rod's chi of
    every node) and the end co-ordinate."""
    idx = [mesh.reduced_index(node, U) for node in range(1, mesh.n_elements)] + [mesh.reduced_coordinates()[0]]
    idx += [mesh.reduced_index(node, CHI) for node in range(mesh.n_elements + 1)]
    if mesh.rocker_elements:                    # a flexible rocker's u and chi
        idx += [mesh.reduced_index((ROCKER.name, node), comp) for node in range(mesh.rocker_elements + 1)
                for comp in (U, CHI)]
    return np.array(sorted({i for i in idx if i is not None}), dtype=np.intp)


class FrozenModel:
    """The model of a case at many frozen crank angles at once (the first axis of every array)."""

    def __init__(self, case):
        self.case = case
        self.model = Model(case)
        self.mesh = self.model.mesh
        self.N = self.mesh.n_dofs
        self.axial = _axial_dofs(self.mesh)
        self.scales = self.mesh.dof_scales(case.natural_sizes, _kinematics.end_scale(case))

    def _assemble(self, kin, d):
        """(r (T, N), K (T, N, N), M (T, N, N)) at the states d (T, N), at rest in the moving frame."""
        zero = np.zeros_like(d)
        terms = self.model.element_terms(kin, d, zero, zero)
        T, N = d.shape[0], self.N
        r = np.zeros((T, N + 1))
        K = np.zeros((T, N + 1, N + 1))
        M = np.zeros((T, N + 1, N + 1))
        for e, dofs in enumerate(self.mesh.element_dofs):       # the dummy slot N collects nothing kept
            r[:, dofs] += terms.r[:, e]
            K[:, dofs[:, None], dofs[None, :]] += terms.K[:, e]
            M[:, dofs[:, None], dofs[None, :]] += terms.M[:, e]
        return r[:, :N], K[:, :N, :N], M[:, :N, :N]

    def frozen(self, theta):
        """(kin, d): the frozen states at the angles theta (T,): the axial rows of R(d) = 0 solved
        by Newton's method on the axial block of the tangent, the transverse unknowns at zero."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        kin = _kinematics.frozen_state(self.case, theta)
        d = np.zeros((theta.size, self.N))
        a = self.axial
        s = self.scales[a]
        for _ in range(NEWTON_ITERATIONS):
            r, K, _ = self._assemble(kin, d)
            step = -np.linalg.solve(K[:, a[:, None], a[None, :]], r[:, a, None])[..., 0]
            d[:, a] += step
            if not np.all(np.isfinite(d)):
                break
            size = np.max(np.abs(d[:, a]) / s, axis=1)
            if np.all(np.max(np.abs(step) / s, axis=1) <= NEWTON_TOL * (1 + size)):
                return kin, d
        raise ConvergenceError(f"the frozen state's axial equations did not converge at Omega* = "
                               f"{self.case.omega:g} (crank angles {np.degrees(theta).min():.4g} to "
                               f"{np.degrees(theta).max():.4g} degrees)")

    def eigen(self, theta):
        """(kin, d, lambda (T, N) ascending, vectors (T, N, N), M (T, N, N)) at the angles theta."""
        with single_thread():
            kin, d = self.frozen(theta)
            _, K, M = self._assemble(kin, d)
            lam, vec = np.linalg.eig(np.linalg.solve(M, K))
        order = np.argsort(lam.real, axis=1)
        lam = np.take_along_axis(lam.real, order, axis=1)
        vec = np.take_along_axis(vec.real, order[:, None, :], axis=2)
        return kin, d, lam, vec, M

    def axial_share(self, vec, M):
        """Share of each mode's kinetic energy x^T M x in its axial unknowns (T, N)."""
        a = self.axial
        total = np.einsum("tik,tij,tjk->tk", vec, M, vec)
        axial = np.einsum("tik,tij,tjk->tk", vec[:, a, :], M[:, a[:, None], a[None, :]], vec[:, a, :])
        return axial / total

    def shapes(self, kin, d, vectors):
        """Nodal (u, v, psi) of mode vectors (T, N, m) -> (T, m, n + 1, 3): the end node's (u, v)
        through the linearized end map, g_s ds."""
        mesh = self.mesh
        n = mesh.n_elements
        T, _, m = vectors.shape
        out = np.zeros((T, m, n + 1, 3))
        for node in range(n + 1):
            for comp in (U, V, PSI):
                idx = mesh.reduced_index(node, comp)
                if idx is not None and not (node == n and comp == U):
                    out[:, :, node, comp] = vectors[:, idx, :]
        S = list(mesh.reduced_coordinates())
        E = _kinematics.end_map(self.case, kin.vector, mesh.mapped_values(d))
        G = tangents(E, len(S))                                                  # (T, m_red, 2)
        s = vectors[:, S, :]                                                     # (T, m_red, m)
        out[:, :, n, U] = np.einsum("tj,tjm->tm", G[:, :, 0], s)
        out[:, :, n, V] = np.einsum("tj,tjm->tm", G[:, :, 1], s)
        big = np.max(np.abs(out[..., :2]), axis=(2, 3))
        flat = out[..., :2].reshape(T, m, -1)
        sign = np.sign(np.take_along_axis(flat, np.argmax(np.abs(flat), axis=2)[..., None], axis=2)[..., 0])
        return out / (big * np.where(sign == 0, 1.0, sign))[:, :, None, None]

    def axial_force(self, d, theta):
        """N* = N L^2 / EI per element of the states d (T, N) frozen at the angles theta (T,), from
        the declared output (element midpoints, where the approach's membrane strain is the
        element's own; the end node through the end map at each angle)."""
        from ..results.outputs import StateHistory
        mids = (np.arange(self.mesh.n_elements) + 0.5) / self.mesh.n_elements
        return np.array([StateHistory(replace(self.case, theta0=float(th)), np.zeros(1), d[k:k + 1])
                         .field("axial_force", mids)[0] for k, th in enumerate(np.atleast_1d(theta))])


def frozen_case(mech=None, omega=None, *, model=None, case=None, units="crankgen", **fields):
    """(case, scales) of a frozen mechanism: a Mechanism (or a crankgen.SIMechanism with
    units="si": its crank speed the frozen speed unless omega, in rad/s, is given) and the run's
    fields, or case=."""
    choice("units", units, UNITS)
    scales = None
    if units == "si":
        if not isinstance(mech, SIMechanism):
            raise ParameterError(f"units='si' needs the mechanism as a crankgen.SIMechanism, got "
                                 f"{type(mech).__name__}")
        if case is not None:
            raise ParameterError("with units='si' give the SIMechanism, not case=")
        scales = mech.scales
        if omega is None:
            fields = dict(fields, crank=mech.crank)
        else:
            omega = finite_number("omega (rad/s)", omega) / scales.omega_b
        mech = mech.mechanism
    elif isinstance(mech, SIMechanism):
        raise ParameterError("a crankgen.SIMechanism needs units='si' (or use its .mechanism and .omega)")
    c = run_case(mech, case, model=model, omega=omega, **fields)
    steady = schema.PARAMETERS[schema.SELECTOR["motion"]].default          # the constant crank speed
    if c.motion_record.name != steady:
        raise ParameterError(f"modes freeze the mechanism at a constant crank speed; the crank motion "
                             f"is {c.motion_record.name!r}: give a Mechanism and {schema.CRANK_SPEED} (the "
                             f"speed to freeze at)")
    return c, scales


def modes(mech=None, omega=None, theta=0.0, *, count=6, model=None, case=None, units="crankgen", **fields):
    """The `count` lowest natural frequencies and mode shapes of the mechanism frozen at crank
    angle theta (rad) turning at crank speed omega (Omega*; rad/s with units="si", default the
    SIMechanism's crank speed), linearized about its rigid motion (module docstring).

    The case as in simulate: a Mechanism and the run's fields (n_elements, the model options,
    model=), or case=Case(...).  omega = 0: the mechanism at rest (the pinned-pinned rod's bending
    frequencies k^2 in units of omega_b at theta = 0, where the rod lies along its guide).
    Returns a Modes."""
    c, scales = frozen_case(mech, omega, model=model, case=case, units=units, **fields)
    theta = angle("theta (crank angle, rad)", theta)
    fm = FrozenModel(c)
    count = min(integer("count", count, 1), fm.N)
    kin, d, lam, vec, M = fm.eigen([theta])
    share = fm.axial_share(vec[:, :, :count], M)[0]
    lam = lam[0, :count]
    return Modes(case=replace(c, theta0=theta), theta=theta, omega=c.omega,
                 frequencies=np.sqrt(np.maximum(lam, 0.0)), omega_squared=lam,
                 kinds=tuple("axial" if x > AXIAL_SHARE else "bending" for x in share), axial_share=share,
                 shapes=fm.shapes(kin, d, vec[:, :, :count])[0], axial_force=fm.axial_force(d, [theta])[0],
                 frozen=d[0], scales=scales)
