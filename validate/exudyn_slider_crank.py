"""The crankgen slider-crank rebuilt in Exudyn, with the rod as geometrically exact ANCF cables.

Independent check of crankgen's steady midspan amplitude.  Nothing here imports crankgen: the
mechanism is set up from the dimensionless parameters alone.

Units are crankgen's (see src/crankgen/parameters.py): rod length L = 1, rho*A = 1,
E*I = 1/pi^4, E*A = 1/(pi^4 eps^2), so that the first pinned-pinned bending frequency is 1 and
time is t* = omega_b t.  Crank a*, slider mass ms*, crank speed Omega*.

Model
-----
- Rod: n_elements ObjectANCFCable2D elements on NodePoint2DSlope1 nodes (position and slope
  vector at each node; axial strain |r'| - 1, material curvature; Euler-Bernoulli, no rotary
  inertia).  Strain-rate (Kelvin-Voigt) damping: Exudyn's viscous virtual work is
  int (d_eps epsdot delta eps + d_K Kdot delta K) dx, so d_eps = mu* EA and d_K = mu* EI give the
  stresses N = EA (eps + mu* epsdot), M = EI (K + mu* Kdot), the same Rayleigh function as
  crankgen's damping="kelvin-voigt".
- Crank: rigid, constant speed; the crank pin A = a* (cos Omega t, sin Omega t) is prescribed on
  the position coordinates of the rod's first node by two CoordinateConstraints with a
  time-dependent offset (the slope there stays free: a pin joint).
- Slider: a MassPoint2D of mass ms* on the rod's last node; its Y coordinate is held at 0 by a
  CoordinateConstraint (slope free).
- Reference (stress-free) configuration: the straight rod from A(theta = 0) = (a*, 0) to the slider
  at (a* + 1, 0).  Initial velocities are those of the rigid mechanism at theta = 0 (rod turning at
  phidot = a* Omega about the slider), so the start is consistent with every constraint.
- Time integration: Exudyn's implicit generalized-alpha solver (index-3 constraints) with a fixed
  step, full Newton, spectral radius rho_inf = 0.9 (Exudyn's default).  With rho_inf = 1 (no
  numerical damping, like crankgen's trapezoidal Newmark) the index-3 multipliers oscillate
  undamped from step to step, Newton needs more and more iterations and eventually fails on long
  runs; where it still runs, the amplitude differs from rho_inf = 0.8 or 0.9 by about 1e-5.

Output
------
v* at the material midpoint (arc length 1/2 in the reference configuration), in the paper's
moving frame: v = (R_mid - R_A) . e_j, e_j = (sin phi, cos phi), sin phi = a* sin theta (the rigid
rod's direction), v* = v / eps.  Steady amplitude: max |v*| over the last crank revolution.

Run this file directly for the convergence checks of one case:
    python validate/exudyn_slider_crank.py --eps 0.01 --omega 0.8
"""

import argparse
import math
import time
from dataclasses import dataclass, field

import numpy as np

import exudyn as exu
from exudyn.itemInterface import (CoordinateConstraint, MarkerNodeCoordinate, MassPoint2D,
                                  NodePoint2DSlope1, NodePointGround, ObjectANCFCable2D,
                                  SensorNode)


PERIODIC_TOL = 1e-6     # relative change of v* between revolutions accepted as "repeats"


@dataclass
class ExudynRun:
    """One Exudyn run; arrays hold the last revolution (theta from 0 to 2 pi, both ends included)."""

    eps: float
    omega: float
    n_elements: int
    steps_per_rev: int
    revolutions: int
    amplitude: float              # max |v*(1/2)| over the last revolution
    half_peak_to_peak: float      # (max v* - min v*) / 2 over the last revolution
    status: str                   # "periodic", "period-2" or "not-periodic" (see PERIODIC_TOL)
    periodicity: float            # max |v*_last - v*_previous| / amplitude (last two revolutions)
    periodicity2: float           # the same against the revolution before the previous one
    constraint_error: float       # max |Y_slider| and |R_1 - R_A| over the run
    wall_time: float
    theta: np.ndarray = field(default=None, repr=False)
    v_mid: np.ndarray = field(default=None, repr=False)


def _crank_pin(a, omega, t):
    th = omega * t
    return a * np.cos(th), a * np.sin(th)


def build(eps, omega, a=0.1, ms=0.5, mu=0.5, n_elements=16, reduced_integration=0):
    """Exudyn system of the mechanism; returns (SystemContainer, mbs, node list)."""
    if n_elements % 2:
        raise ValueError("n_elements must be even (the midpoint is read at a node)")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    rhoA = 1.0
    EI = 1.0 / math.pi**4
    EA = 1.0 / (math.pi**4 * eps**2)
    h = 1.0 / n_elements
    phid0 = a * omega                      # rigid rod's angular speed at theta = 0 (clockwise)

    nodes = []
    for i in range(n_elements + 1):
        x = i * h                          # arc length from the crank pin
        nodes.append(mbs.AddNode(NodePoint2DSlope1(
            referenceCoordinates=[a + x, 0.0, 1.0, 0.0],
            initialCoordinates=[0.0, 0.0, 0.0, 0.0],
            # rigid mechanism at theta = 0: pin moves (0, a Omega), slider at rest, e_i turns
            initialVelocities=[0.0, phid0 * (1.0 - x), 0.0, -phid0])))
    for i in range(n_elements):
        mbs.AddObject(ObjectANCFCable2D(
            nodeNumbers=[nodes[i], nodes[i + 1]], length=h, massPerLength=rhoA,
            bendingStiffness=EI, axialStiffness=EA,
            bendingDamping=mu * EI, axialDamping=mu * EA,
            useReducedOrderIntegration=reduced_integration))

    # slider: point mass on the last node, Y held at 0 (reference Y is 0)
    mbs.AddObject(MassPoint2D(mass=ms, nodeNumber=nodes[-1]))
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    m_sy = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[-1], coordinate=1))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, m_sy], offset=0.0))

    # crank pin: prescribed displacement of the first node's position (reference (a, 0));
    # CoordinateConstraint enforces q[m1] - q[m0] = offset(t), q the displacement coordinate
    def pin_x(mbs, t, item, off):
        return a * math.cos(omega * t) - a

    def pin_y(mbs, t, item, off):
        return a * math.sin(omega * t)

    m_ax = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=0))
    m_ay = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=1))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, m_ax], offsetUserFunction=pin_x))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, m_ay], offsetUserFunction=pin_y))
    mbs.Assemble()
    return SC, mbs, nodes


def settings(omega, steps_per_rev, n_steps, spectral_radius=0.9, newton_rtol=1e-8,
             linear_solver="dense"):
    """Exudyn's simulation settings of these runs: generalized-alpha (index 3) with a fixed step
    dt* = 2 pi / (steps_per_rev Omega*), full Newton (Jacobian computed and factorized at every
    iteration), no solution file, no printed statistics.  linear_solver: "dense" (Exudyn's
    default, EXUdense) or "sparse" (EigenSparse)."""
    dt = 2.0 * math.pi / omega / steps_per_rev
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.endTime = n_steps * dt
    ti.numberOfSteps = n_steps
    ti.verboseMode = 0
    ti.adaptiveStep = False
    ti.automaticStepSize = False
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.newton.useModifiedNewton = False
    ti.newton.relativeTolerance = newton_rtol
    ti.newton.absoluteTolerance = 1e-11
    ti.newton.maxIterations = 30
    ss.linearSolver.solverType = {"dense": exu.LinearSolverType.EXUdense,
                                  "sparse": exu.LinearSolverType.EigenSparse}[linear_solver]
    ss.solution.file.write = False
    # sensors are written at the end of a step once writePeriod has passed since the last write;
    # a period of exactly dt skips a step now and then by round-off (e.g. step 8731 of Omega* = 0.2)
    ss.solution.sensors.writePeriod = 0.5 * dt
    ss.show.statistics = False
    ss.show.computationTime = False
    return ss, dt


def midspan_vstar(position_mid, a, eps, omega, t):
    """v* at the midpoint from its position (x, y) at time t (see the module's Output)."""
    ax, ay = _crank_pin(a, omega, t)
    sphi = a * np.sin(omega * t)
    return ((position_mid[0] - ax) * sphi + (position_mid[1] - ay) * np.sqrt(1.0 - sphi**2)) / eps


def timed_solve(eps, omega, a=0.1, ms=0.5, mu=0.5, n_elements=16, steps_per_rev=400, revolutions=20,
                spectral_radius=0.9, linear_solver="dense", profile=False):
    """Wall seconds of Exudyn's dynamic solve alone (the model is built before the clock starts),
    with no sensors and no solution file (nothing is written while it runs).  Returns a dict:
    seconds, steps, newton_iterations and jacobians (counts over the run, from Exudyn's solver),
    vstar_end (v* at the midpoint at the last step) and, with profile=True, Exudyn's own timer
    (seconds per part of the solve; the timer adds a little to `seconds`)."""
    SC, mbs, nodes = build(eps, omega, a, ms, mu, n_elements)
    n_steps = steps_per_rev * revolutions
    ss, dt = settings(omega, steps_per_rev, n_steps, spectral_radius, linear_solver=linear_solver)
    ss.displayComputationTime = bool(profile)
    start = time.perf_counter()
    exu.SolveDynamic(mbs, ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    seconds = time.perf_counter() - start
    solver = mbs.sys["dynamicSolver"]
    it = solver.it
    if it.currentStepIndex - 1 != n_steps or abs(it.currentTime - n_steps * dt) > 1e-9 * n_steps * dt:
        raise RuntimeError(f"Exudyn stopped early at t* = {it.currentTime:.6g} (expected {n_steps * dt:.6g})")
    mid = mbs.GetNodeOutput(nodes[n_elements // 2], exu.OutputVariableType.Position)
    out = dict(seconds=seconds, steps=n_steps, newton_iterations=int(it.newtonStepsCount),
               jacobians=int(it.newtonJacobiCount),
               vstar_end=float(midspan_vstar(mid, a, eps, omega, n_steps * dt)))
    if profile:
        timer = solver.timer
        out["timer"] = {k: float(getattr(timer, k)) for k in dir(timer)
                        if not k.startswith("_") and isinstance(getattr(timer, k), float)}
    return out


def run(eps, omega, a=0.1, ms=0.5, mu=0.5, n_elements=16, steps_per_rev=400, revolutions=30,
        spectral_radius=0.9, reduced_integration=0, newton_rtol=1e-8):
    """Integrate `revolutions` crank revolutions; returns an ExudynRun (steady = last revolution)."""
    start = time.perf_counter()
    SC, mbs, nodes = build(eps, omega, a, ms, mu, n_elements, reduced_integration)
    n_steps = steps_per_rev * revolutions
    ss, dt = settings(omega, steps_per_rev, n_steps, spectral_radius, newton_rtol)

    # node positions (reference + displacement), stored by the solver at every step
    P = exu.OutputVariableType.Position
    s_mid = mbs.AddSensor(SensorNode(nodeNumber=nodes[n_elements // 2], outputVariableType=P,
                                     storeInternal=True, writeToFile=False))
    s_pin = mbs.AddSensor(SensorNode(nodeNumber=nodes[0], outputVariableType=P,
                                     storeInternal=True, writeToFile=False))
    s_sl = mbs.AddSensor(SensorNode(nodeNumber=nodes[-1], outputVariableType=P,
                                    storeInternal=True, writeToFile=False))
    mbs.Assemble()
    exu.SolveDynamic(mbs, ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)

    mid = mbs.GetSensorStoredData(s_mid)
    pin = mbs.GetSensorStoredData(s_pin)
    sl = mbs.GetSensorStoredData(s_sl)
    t = mid[:, 0]
    # the sensor time grid is k*dt (k = 0..n_steps); rebuild it exactly from the step count
    k = np.rint(t / dt).astype(int)
    if k[-1] != n_steps:
        raise RuntimeError(f"Exudyn stopped early at t* = {t[-1]:.6g} (expected {n_steps * dt:.6g})")
    if not np.array_equal(k, np.arange(n_steps + 1)):
        raise RuntimeError("sensor samples are not one per time step")
    t = k * dt
    ax, ay = _crank_pin(a, omega, t)
    theta = omega * t
    sphi = a * np.sin(theta)
    cphi = np.sqrt(1.0 - sphi**2)
    v = (mid[:, 1] - ax) * sphi + (mid[:, 2] - ay) * cphi
    vstar = v / eps
    cerr = max(np.max(np.abs(sl[:, 2])), np.max(np.hypot(pin[:, 1] - ax, pin[:, 2] - ay)))

    def rev(j):                        # v* over revolution `revolutions - j` (j = 0: the last)
        end = len(t) - j * steps_per_rev
        return vstar[end - steps_per_rev - 1:end]

    vl = rev(0)
    amp = float(np.max(np.abs(vl)))
    scale = max(amp, 1e-300)
    per = float(np.max(np.abs(vl - rev(1))) / scale)
    per2 = float(np.max(np.abs(vl - rev(2))) / scale) if revolutions >= 3 else math.nan
    status = ("periodic" if per < PERIODIC_TOL else
              "period-2" if per2 < PERIODIC_TOL else "not-periodic")
    return ExudynRun(eps, omega, n_elements, steps_per_rev, revolutions, amp,
                     float((vl.max() - vl.min()) / 2), status, per, per2, float(cerr),
                     time.perf_counter() - start,
                     theta=2.0 * math.pi * np.arange(steps_per_rev + 1) / steps_per_rev,
                     v_mid=vl.copy())


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--eps", type=float, default=0.01)
    p.add_argument("--omega", type=float, default=0.8)
    p.add_argument("--elements", type=int, nargs="+", default=[8, 16])
    p.add_argument("--steps", type=int, nargs="+", default=[200, 400])
    p.add_argument("--revolutions", type=int, default=30)
    p.add_argument("--rho", type=float, default=0.9, help="generalized-alpha spectral radius")
    p.add_argument("--reduced", type=int, default=0, help="useReducedOrderIntegration")
    args = p.parse_args()
    for ne in args.elements:
        for spr in args.steps:
            r = run(args.eps, args.omega, n_elements=ne, steps_per_rev=spr,
                    revolutions=args.revolutions, spectral_radius=args.rho,
                    reduced_integration=args.reduced)
            print(f"eps={r.eps:g} Omega*={r.omega:g} elements={ne:3d} steps/rev={spr:5d} "
                  f"revs={r.revolutions}: amplitude={r.amplitude:.6f} "
                  f"half p-p={r.half_peak_to_peak:.6f} {r.status} (change/rev {r.periodicity:.1e}) "
                  f"constraint={r.constraint_error:.1e} ({r.wall_time:.1f} s)")


if __name__ == "__main__":
    main()
