"""The map of a steady motion on its section, for shooting (steady.py) and continuation
(bifurcation/mechanism.py): one interface, two kinds of section, chosen by the declaration.

- TimeSection: a crank motion prescribed and periodic in the crank angle makes the system periodic
  in time.  The section is t = k T (T one crank revolution of steps_per_rev steps), the state there
  x = (d, v) (with generalized-alpha's algorithmic accelerations a: (d, v, a)); the map and its exact
  Jacobian come from engine.revolution, its marches from engine.march_state.  A batch of cases
  shares one engine batch.
- CrankSection: a driven motion (its crank angle a declared co-ordinate of the DOF map, records.
  Coordinate.crank) makes the system autonomous, its period unknown.  The section is the crank
  angle's passage through its start theta0 (mod 2 pi); the state there is the DOF map's without
  the crank angle: y = (x without theta, v, [a]) (the rates, the crank's speed among them, kept).
  The map marches until the crank angle passes theta0 + 2 pi, then takes the last step with the
  length tau that lands on it exactly (Newton on tau: the same time scheme, one step of another
  length); the revolution time is T = (steps before it) dt + tau.  Every declared co-ordinate that
  is an angle (units rad: a motor rotor's) turns with the crank and is brought back by the same
  2 pi.  Its Jacobian is differenced (central differences, one batch of 2 dim(y) marches, each
  step converged to 1e-12).  On the section the map has no trivial multiplier (the flow's monodromy
  matrix has the multiplier 1 of the motion along the orbit: `monodromy`, a diagnostic, shows it).
  A run from the start (theta0 at its initial speed) of `warmup` revolutions of the step period
  (no-load revolutions), repeated until the crank's mean speed settles, gives the starting point.

Both give: `start` (the states after the warm-up), `march` (revolutions of the map, no
linearization), `revolution` (the map and its Jacobian), `orbit` (the steps of one revolution,
for the result), `scales` (the natural size of each entry of the section state).
"""

import math

import numpy as np

from .. import engine
from ..discrete import kinematics as _kinematics
from .marching import coordinate_histories, crank_of, start_state

TWO_PI = 2.0 * math.pi
FD_STEP = 1e-6          # central differences: this times each component's natural size
MARCH_TOL = 1e-12       # a crank section's marches' Newton tolerance (scaled increments)
TAU_ITERATIONS = 8
WARMUP = 30             # the revolutions of its step period (no-load revolutions) a driven crank runs up first


def failure_text(res, b, dt, before=0, steps_per_rev=None):
    """The failure of case b in a march that started `before` steps into the run: the step counted
    from the start of the run (and its revolution)."""
    code = int(res.status[b])
    step = before + int(res.fail_step[b])
    where = f", revolution {(step - 1) // steps_per_rev + 1}" if steps_per_rev else ""
    return (f"{engine.STATUS_TEXT[code]} in step {step} of the run{where} (t* = {step * dt:.6g}), "
            f"residual norm {res.fail_residual[b]:.3e}")


class TimeSection:
    """The revolution map of cases with a prescribed periodic crank (module docstring)."""

    autonomous = False

    def __init__(self, cases, parallel=None):
        self.cases = list(cases)
        self.batch = engine.Batch(self.cases, entries=("march", "revolution"))
        self.parallel = parallel
        self.N = self.batch.N
        self.size = self.batch.state_size              # (d, v), or (d, v, a) for generalized-alpha
        self.generalized = self.size == 3 * self.N
        self.scales = np.concatenate([self.batch.scales] * (self.size // self.N), axis=1)
        self.steps_per_rev = self.batch.steps_per_rev

    def start(self, warmup, limit, active):
        """(states X (B, size) after `warmup` revolutions from the start of a run, status (B,), why
        per case ("" if it ran), revolutions taken (B,)): the warm-up of a steady state."""
        X = np.zeros((len(self.cases), 2 * self.N))
        X1, status, why = self.march(X, warmup, active, start=True)
        return X1, status, why, np.full(len(self.cases), warmup)

    def march(self, X, revolutions, active, start=False, before=None):
        """(X after `revolutions` revolutions, status (B,), why per case ("" if it ran)): start: from
        (d, v) alone (a run's start: generalized-alpha's first step is its starter); before: the
        revolutions each case ran before (for the failure's step count)."""
        b, spr = self.batch, self.steps_per_rev
        pre = np.where(active, engine.OK, engine.NOT_CONVERGED)
        res = engine.march_state(b, revolutions * spr, X, status=pre, parallel=self.parallel)
        why = [""] * len(self.cases)
        before = np.zeros(len(self.cases), dtype=int) if before is None else before
        for i in np.flatnonzero(active & (res.status != engine.OK)):
            why[i] = failure_text(res, i, float(b.dt[i]), int(before[i]) * spr, spr)
        return engine.join_state(res, self.generalized), res.status, why

    def revolution(self, X, active):
        """(P(X), dP/dX, status): the map and its exact Jacobian (engine.revolution)."""
        return engine.revolution(self.batch, X, active=active, parallel=self.parallel)

    def orbit(self, X, show):
        """(per shown case a dict of its revolution: t, theta, y, states, rates, accelerations (the
        nodal ones), and the engine's result for the failures) of the states X."""
        b, spr = self.batch, self.steps_per_rev
        pre = np.where(show, engine.OK, engine.NOT_CONVERGED)
        res = engine.march_state(b, spr, X, status=pre, parallel=self.parallel, keep_history=True)
        out = [None] * len(self.cases)
        for i, case in enumerate(self.cases):
            if show[i] and res.status[i] == engine.OK:
                t = float(b.dt[i]) * np.arange(spr + 1)
                out[i] = dict(t=t, theta=_kinematics.case_state(case, t).theta, y=res.y[i],
                              states=res.D_history[i], rates=res.V_history[i], accelerations=res.A_history[i])
        return out, (lambda i: failure_text(res, i, float(b.dt[i])))


class CrankSection:
    """The map of one case's autonomous motion on the section of its crank co-ordinate (module
    docstring)."""

    autonomous = True

    def __init__(self, case, tol=MARCH_TOL, max_chunks=40):
        self.case, self.tol, self.max_chunks = case, tol, max_chunks
        self.cases = [case]
        self.batch = engine.Batch([case])
        self.N = self.batch.N
        mesh = self.batch.mesh
        self.n_rod = mesh.n_rod
        self.c = mesh.n_rod + mesh.crank_coordinate        # the crank angle's place in the state
        self.keep = np.array([i for i in range(self.N) if i != self.c])
        self.turning = np.array([mesh.n_rod + j for j, co in enumerate(mesh.coordinates) if co.units == "rad"])
        self.dt = float(self.batch.dt[0])
        self.generalized = bool(self.batch.generalized[0])
        self.steps_per_rev = self.batch.steps_per_rev
        z0, _ = _kinematics.coordinates_start(case)
        self.theta_s = float(z0[mesh.crank_coordinate])
        speed = TWO_PI / _kinematics.step_period(case)              # the no-load speed: the rates' size
        scales = self.batch.scales[0].copy()
        rates = scales.copy()
        rates[mesh.n_rod:] = speed
        self.state_scales = np.concatenate([scales[self.keep], rates] + ([rates] if self.generalized else []))
        self.size = self.state_scales.size
        self.scales = self.state_scales[None]

    # ---- the state on the section and the DOF map's ----------------------------------------------
    def full(self, Y):
        """(X, V, G) (B, N) of section states Y (B, size): the crank at theta0; G None for Newmark."""
        Y = np.atleast_2d(Y)
        B, k = Y.shape[0], self.N - 1
        X = np.empty((B, self.N))
        X[:, self.keep] = Y[:, :k]
        X[:, self.c] = self.theta_s
        V = Y[:, k:k + self.N]
        G = Y[:, k + self.N:] if self.generalized else None
        return X, V, G

    def section(self, X, V, G):
        """Y of DOF-map states on the section (their crank angle dropped)."""
        parts = [X[:, self.keep], V] + ([G] if self.generalized else [])
        return np.concatenate(parts, axis=1)

    def _batch(self, B, dt=None):
        return engine.Batch([self.case] * B, dt=dt, like=self.batch)

    # ---- the map -----------------------------------------------------------------------------------
    def __call__(self, Y, keep=False):
        """(P(Y) (B, size), T (B,), status (B,), orbit): the map of section states Y (B, size), the
        revolution times, the engine's status per case; orbit (keep=True, case 0): the revolution's
        DOF-map states, times, engine outputs and co-ordinates."""
        X, V, G = self.full(Y)
        return self.to_angle(X, V, None, G, self.theta_s + TWO_PI, keep)

    def to_angle(self, X, V, A, G, target, keep=False):
        """March states (X, V, accelerations A (None: solved), G (None: a start)) until the crank
        angle reaches `target` (per case, or one for all), the last step landing on it: (Y there
        with the turning angles brought back to the section, the time taken, status, orbit)."""
        X = np.array(X, dtype=float)
        B, N, c = X.shape[0], self.N, self.c
        target = np.broadcast_to(np.asarray(target, dtype=float), (B,)).copy()
        batch = self._batch(B)
        status = np.zeros(B, dtype=np.int64)
        before = np.full((B, 4, N), np.nan)              # the state before the crossing: X, V, A, G
        steps = np.zeros(B, dtype=np.int64)              # full steps before the crossing
        crossed = np.zeros(B, dtype=bool)
        taken = 0
        orbit = {"X": [], "V": [], "A": [], "y": [], "Z": []} if keep else None
        n = self.steps_per_rev
        for _ in range(self.max_chunks):
            res = engine.march(batch, n, D0=X, V0=V, A0=A, G0=G, keep_history=True, tol=self.tol, status=status)
            theta = res.D_history[:, :, c]
            G_hist = res.A_history if res.G_history is None else res.G_history
            for b in np.flatnonzero(~crossed & (res.status == engine.OK)):
                hit = np.flatnonzero(theta[b, 1:] >= target[b])
                if hit.size:
                    k = int(hit[0])                       # the crossing lies in step k -> k + 1
                    before[b] = (res.D_history[b, k], res.V_history[b, k], res.A_history[b, k], G_hist[b, k])
                    steps[b] = taken + k
                    crossed[b] = True
                    if keep and b == 0:
                        self._keep(orbit, res, k + 1)
            if keep and not crossed[0]:
                self._keep(orbit, res, n)
            status = res.status.copy()
            status[crossed] = engine.NOT_CONVERGED            # done: not advanced further
            if not np.any(~crossed & (res.status == engine.OK)):
                break
            X, V, A, G = res.D, res.V, res.A, res.G
            taken += n
        ok = crossed.copy()
        T = np.full(B, np.nan)
        Y1 = np.full((B, self.size), np.nan)
        final_status = np.where(ok, engine.OK, np.where(res.status == engine.OK, engine.NOT_CONVERGED, res.status))
        if not ok.any():
            return Y1, T, final_status, orbit
        idx = np.flatnonzero(ok)
        Xb, Vb, Ab, Gb = (before[idx, j] for j in range(4))
        tau = np.clip((target[idx] - Xb[:, c]) / np.maximum(Vb[:, c], 1e-300), 0.0, 2.0 * self.dt)
        for _ in range(TAU_ITERATIONS):
            last = engine.march(self._batch(len(idx), dt=tau), 1, D0=Xb, V0=Vb, A0=Ab, G0=Gb, tol=self.tol)
            miss = target[idx] - last.D[:, c]
            if not np.all(last.status == engine.OK):
                break
            tau = tau + miss / last.V[:, c]
            if np.max(np.abs(miss)) < 1e-14 * TWO_PI:
                break
        last = engine.march(self._batch(len(idx), dt=tau), 1, D0=Xb, V0=Vb, A0=Ab, G0=Gb, tol=self.tol)
        good = last.status == engine.OK
        final_status[idx[~good]] = last.status[~good]
        Xe = last.D.copy()
        turns = (target[idx] - self.theta_s)[:, None]
        Xe[:, self.turning] -= turns
        Y1[idx] = self.section(Xe, last.V, last.G if self.generalized else None)
        T[idx] = steps[idx] * self.dt + tau
        if keep and ok[0]:
            orbit["X"].append(last.D[:1])                 # the orbit ends on the landed, unwrapped state
            orbit["V"].append(last.V[:1])
            orbit["A"].append(last.A[:1])
            orbit["y"].append(last.y[0, 1:2])
            orbit["Z"].append(last.Z[0, 1:2])
            orbit = {k: np.concatenate(v) for k, v in orbit.items()}
            orbit["t"] = np.append(self.dt * np.arange(len(orbit["X"]) - 1), T[0])
        Y1[~(final_status == engine.OK)] = np.nan
        return Y1, T, final_status, orbit

    @staticmethod
    def _keep(orbit, res, k):
        """The first k steps of case 0 of a march into the orbit being kept."""
        for key, h in (("X", res.D_history), ("V", res.V_history), ("A", res.A_history)):
            orbit[key].append(h[0, :k])
        orbit["y"].append(res.y[0, :k])
        orbit["Z"].append(res.Z[0, :k])

    def jacobian(self, Y):
        """dP/dY (size, size) at Y by central differences (module docstring); None if a march fails."""
        h = FD_STEP * self.state_scales
        E = np.diag(h)
        P, _, st, _ = self(np.concatenate([Y[None] + E, Y[None] - E]))
        if np.any(st != engine.OK):
            return None
        n = self.size
        return ((P[:n] - P[n:]) / (2.0 * h)[:, None]).T

    def change(self, Y, Y1):
        """Scaled change |P(y) - y|_s (steady.py's measure)."""
        s = self.state_scales
        return float(np.max(np.abs(Y1 - Y) / s) / (1.0 + np.max(np.abs(Y1) / s)))

    # ---- the interface of a section (module docstring) ---------------------------------------------
    def start(self, warmup, limit, active=None):
        """(Y (1, size) on the section after the run from the case's start, status (1,), why, the
        step-period revolutions taken (1,)): marched in chunks of `warmup` revolutions of the step
        period until the crank's mean speed over a chunk changes by less than 1 % from the last
        chunk's (a weak motor on a heavy crank takes long to settle), at most `limit`; then to the
        section.  A crank that does not turn forward is held back (its motor's torque below the
        load)."""
        Y, why, total = self.warm_start(warmup, limit)
        ok = Y is not None
        return (Y[None] if ok else np.full((1, self.size), np.nan), np.array([engine.OK if ok else engine.NOT_CONVERGED]),
                [why], np.array([total]))

    def warm_start(self, warmup, limit):
        """(the section state after the run-up from the case's start, why not, revolutions taken)."""
        c = self.c
        d0, v0 = start_state(self.case, np.zeros(self.n_rod), np.zeros(self.n_rod))
        X, V = d0[None], v0[None]
        theta0 = float(X[0, c])
        A = G = None
        steps = warmup * self.steps_per_rev
        previous, total = None, 0
        while True:
            res = engine.march(self.batch, steps, D0=X, V0=V, A0=A, G0=G, tol=self.tol)
            if res.status[0] != engine.OK:
                return None, (f"the run-up from the start failed: {engine.STATUS_TEXT[int(res.status[0])]} in step "
                              f"{total * self.steps_per_rev + int(res.fail_step[0])}"), total
            total += warmup
            mean = (res.D[0, c] - X[0, c]) / (steps * self.dt)
            X, V, A, G = res.D, res.V, res.A, res.G
            if previous is not None and abs(mean - previous) < 0.01 * abs(mean) or total >= limit:
                break
            previous = mean
        theta = X[0, c]
        if not (mean > 0 and theta > theta0 + TWO_PI):
            return None, (f"the crank turned {(theta - theta0) / TWO_PI:.3g} revolutions in the {total} no-load "
                          f"revolutions of the run-up (mean speed {mean:.3g} over the last {warmup}): it is held back "
                          "(stall torque below the load)"), total
        turns = math.floor((theta - self.theta_s) / TWO_PI) + 1
        Y, _, st, _ = self.to_angle(X, V, A, G, self.theta_s + TWO_PI * turns)
        if st[0] != engine.OK:
            return None, "the march to the section after the run-up failed", total
        return Y[0], "", total

    def march(self, Y, revolutions, active, start=False, before=None):
        """(Y after `revolutions` revolutions of the map, None, why (one per case))."""
        st = np.array([engine.OK])
        for _ in range(revolutions):
            Y, _, st, _ = self(Y)
            if st[0] != engine.OK:
                break
        why = [""] if st[0] == engine.OK else [f"a revolution failed: {engine.STATUS_TEXT[int(st[0])]}"]
        return Y, st, why

    def revolution(self, Y, active):
        """(P(Y), dP/dY, status) (B = 1)."""
        Y1, _, st, _ = self(Y)
        J = self.jacobian(Y[0]) if st[0] == engine.OK else None
        if st[0] == engine.OK and J is None:
            st = np.array([engine.NOT_CONVERGED])
        return Y1, (np.full((1, self.size, self.size), np.nan) if J is None else J[None]), st

    def orbit(self, Y, show):
        """(the revolution from the section state, as TimeSection.orbit, with the crank's history,
        every co-ordinate's and the revolution time)."""
        if not show[0]:
            return [None], (lambda i: "")
        _, T, st, orbit = self(Y[:1], keep=True)
        if st[0] != engine.OK:
            return [None], (lambda i: f"a revolution failed: {engine.STATUS_TEXT[int(st[0])]}")
        coords = coordinate_histories(self.case, orbit["Z"])
        crank = crank_of(self.case, coords)
        n_rod = self.n_rod
        return [dict(t=orbit["t"], theta=crank[:, 0], y=orbit["y"], states=orbit["X"][:, :n_rod],
                     rates=orbit["V"][:, :n_rod], accelerations=orbit["A"][:, :n_rod], crank=crank,
                     coordinates=coords, period=float(T[0]))], (lambda i: "")


def monodromy(section_map, Y, T):
    """The flow's monodromy matrix over the time T on the DOF map's state (x, v[, a]) at the section
    state Y, by central differences of marches of exactly T (the steps of the map and a last one of
    the remaining length): a diagnostic of the trivial multiplier 1."""
    m = section_map
    n_full = int(math.floor(T / m.dt + 1e-9))
    tau = T - n_full * m.dt
    X, V, G = m.full(Y)
    Z = np.concatenate([X[0], V[0]] + ([G[0]] if m.generalized else []))
    scales = m.batch.scales[0]
    rates = m.state_scales[m.N - 1:2 * m.N - 1]
    scale = np.concatenate([scales, rates] + ([rates] if m.generalized else []))
    h = FD_STEP * scale
    Zs = np.concatenate([Z[None] + np.diag(h), Z[None] - np.diag(h)])
    B, N = Zs.shape[0], m.N
    Xs, Vs = Zs[:, :N], Zs[:, N:2 * N]
    Gs = Zs[:, 2 * N:] if m.generalized else None
    res = engine.march(m._batch(B), n_full, D0=Xs, V0=Vs, G0=Gs, tol=m.tol)
    last = engine.march(m._batch(B, dt=np.full(B, tau)), 1, D0=res.D, V0=res.V, A0=res.A, G0=res.G, tol=m.tol)
    if np.any(last.status != engine.OK):
        return None
    out = np.concatenate([last.D, last.V] + ([last.G] if m.generalized else []), axis=1)
    n = Z.size
    return ((out[:n] - out[n:]) / (2.0 * h)[:, None]).T
