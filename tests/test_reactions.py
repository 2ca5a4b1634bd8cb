"""The forces a designer needs (torque; the joint forces crank_on_rod at A, rod_on_slider /
rod_on_tip at B, guide_on_slider / rocker_on_tip: Model.reactions through the declared outputs)
against independent truths.

1. Rigid limit.  As Omega* -> 0 (the rod stiff against the crank's pace) the flexible mechanism's
   reactions tend to the rigid mechanism's inverse dynamics, written out in tests/four_bar.py by
   Newton-Euler: a rigid rod of mass rho A L = 1 and moment of inertia 1/12 + rho I about its
   centre, the end mass ms at B, a massless crank, a frictionless guide (the slider's normal force
   along Y; the rocker's force along DB).  The flexible correction is the rod's quasi-static
   deflection, O(Omega*^2) relative (the inertia loads scale with Omega*^2, the deflection with
   the loads).  Measured on steady revolutions (a* = 0.3, eps = 0.01, 8 elements), largest error
   over the revolution relative to the rigid signal's largest value, at Omega* = 0.04 / 0.02:
   slider, constant crank 1.0e-3 / 2.6e-4 (torque) and up to 2.1e-3 / 5.3e-4 (guide force);
   slider, fluctuating crank (k = 0.3, j = 2: thetadd as large as the centripetal terms) up to
   1.7e-2 / 4.1e-3 (guide force); four-bar, constant 2.4e-3 / 6.0e-4; four-bar, fluctuating
   8e-3 / 2e-3.  Ratios 3.9 to 4.1; the slider's guide_on_slider_x is zero (< 1e-15).  The end
   mass's free-body balance: the rod's force on it at B plus the guide's (the rocker's) is ms times
   its acceleration, the rigid mechanism's in the limit (both to O(Omega*^2) as well).
2. Power over a steady revolution.  torque * crank_speed is the pin reaction's power F_pin . V_pin
   (pointwise, against energy_balance.py's own F_pin . V_pin, 1e-15).  Over a steady revolution
   E = T + U returns to its value (1e-12 of the work), so the balance of tests/energy_balance.py
   says  int torque thetad dt = int P_diss dt - int P_frame dt:  the driving work is the
   Kelvin-Voigt dissipation (energy_balance.py's quadrature of 2 D), less the work done through
   the prescribed frame angle phi(t) (the discrete strain energy is not invariant under the frame's
   rotation; with the element-mean membrane strain and 8 elements it is 0.2 % of the driving work
   for the slider, 0.5 % for the four-bar).  With the trapezoidal rule (the integrator's own
   quadrature) it closes at O(dt^2): 6.8e-6 / 1.7e-6 (slider, constant crank), 3.9e-5 / 9.8e-6
   (slider, fluctuating), 2.5e-5 / 6.1e-6 (four-bar), 1.1e-4 / 2.8e-5 (four-bar, fluctuating) of
   the driving work at 200 / 400 steps per revolution, while dropping the frame term leaves 3e-4
   to 1.4e-3.
"""

import numpy as np
import pytest

import crankgen
import energy_balance as eb
import four_bar as fb
from crankgen.declaration import schema
from crankgen.discrete.kinematics import case_state
from crankgen.discrete.system import Model

A = 0.3
GEOMETRY = {"line": dict(offset=0.1), "circle": dict(guide="circle", c=0.9, d=1.1, offset=0.2)}


def _crank(kind, omega):
    if kind == "constant":
        return dict(omega=omega)
    return dict(crank=crankgen.Fluctuation(omega=omega, amplitude=0.3, order=2))


def _rigid(st, guide):
    K = schema.KIN
    kin = case_state(st.case, st.t).vector
    th, thd, thdd = kin[:, K["theta"]], kin[:, K["thetad"]], kin[:, K["thetadd"]]
    g = GEOMETRY[guide]
    if guide == "circle":
        k = fb.four_bar(th, thd, thdd, A, g["c"], g["d"], g["offset"], 1)
    else:
        k = fb.slider_crank(th, thd, thdd, A, g["offset"])
    torque, pin, end = fb.inverse_dynamics(k, A, st.case.ms, st.case.eps**2)
    mass_accel = st.case.ms * fb.accelerations(k, A, 1.0)       # ms a_B of the rigid mechanism
    return torque, pin, end, mass_accel


NAMES = {"line": ("rod_on_slider", "guide_on_slider"), "circle": ("rod_on_tip", "rocker_on_tip")}


@pytest.mark.parametrize("motion", ["constant", "fluctuation"])
@pytest.mark.parametrize("guide", ["line", "circle"])
def test_reactions_tend_to_the_rigid_mechanism_inverse_dynamics(guide, motion):
    errors = []
    for omega in (0.04, 0.02):
        mech = crankgen.Mechanism(a=A, eps=0.01, ms=0.5, mu=0.5, **GEOMETRY[guide])
        st = crankgen.steady_state(mech, n_elements=8, steps_per_rev=200, **_crank(motion, omega))
        assert st.ok, st.message
        torque, pin, end, mass_accel = _rigid(st, guide)
        rod_on, guide_on = (np.stack([st.quantity(f"{name}_{c}") for c in "xy"], -1) for name in NAMES[guide])
        # the end mass's free body: the rod's force at B and the guide's give it ms a_B
        # (the flexible mass's acceleration differs from the rigid one by O(Omega*^2) and by the
        # step's O((2 pi / steps_per_rev)^2), about 1e-4 here: to 1e-3, without a convergence rate)
        balance = np.hypot(*(rod_on + guide_on - mass_accel).T)
        assert np.max(balance) < 1e-3 * np.max(np.hypot(*mass_accel.T)), np.max(balance)
        pairs = [(st.torque, torque), (st.crank_on_rod_x, pin[:, 0]), (st.crank_on_rod_y, pin[:, 1]),
                 (guide_on[:, 1], end[:, 1]), (rod_on[:, 0], (mass_accel - end)[:, 0]),
                 (rod_on[:, 1], (mass_accel - end)[:, 1])]
        if guide == "circle":
            pairs.append((guide_on[:, 0], end[:, 0]))
        else:   # the slider's guide pushes along Y only (no friction): exactly, not in the limit
            assert np.max(np.abs(guide_on[:, 0])) < 1e-9 * np.max(np.abs(end[:, 1]))
        errors.append([np.max(np.abs(got - want)) / np.max(np.abs(want)) for got, want in pairs])
    errors = np.array(errors)
    assert np.all(errors[1] < 5e-3), errors
    assert np.all((errors[0] / errors[1] > 3.5) & (errors[0] / errors[1] < 4.5)), errors   # O(Omega*^2)


def test_the_rocker_force_is_along_the_rocker_and_the_slider_force_normal_to_the_guide():
    """A dynamic run (Omega* = 0.8, the rod vibrating): the rocker, a massless two-force member,
    pushes along DB; the frictionless guide along Y (to the Newton tolerance: the component along
    the end's path is the reduced residual of the end's co-ordinate, measured 5e-9 relative)."""
    for guide in ("line", "circle"):
        mech = crankgen.Mechanism(a=0.2, **GEOMETRY[guide])
        r = crankgen.simulate(mech, omega=0.8, n_elements=4, steps_per_rev=100, revolutions=2)
        name = NAMES[guide][1]
        F = np.stack([r.quantity(f"{name}_x"), r.quantity(f"{name}_y")], -1)
        if guide == "circle":
            g = GEOMETRY[guide]
            DB = np.stack([r.slider_position - g["d"], r.end_height - g["offset"]], -1)
            along = np.abs(DB[:, 0] * F[:, 1] - DB[:, 1] * F[:, 0]) / np.hypot(*DB.T)
        else:
            along = np.abs(F[:, 0])
        assert np.max(along) < 1e-7 * np.max(np.abs(F)), guide


@pytest.mark.parametrize("motion", ["constant", "fluctuation"])
@pytest.mark.parametrize("guide", ["line", "circle"])
def test_driving_work_over_a_steady_revolution_is_the_dissipation_less_the_frame_work(guide, motion):
    defects = []
    geometry = GEOMETRY[guide] if guide == "circle" else {}     # (with offset 0.1 the slider's
    for spr in (200, 400):                                      # O(dt^2) term nearly cancels)
        mech = crankgen.Mechanism(a=0.1, eps=0.01, ms=0.5, mu=0.5, **geometry)
        st = crankgen.steady_state(mech, n_elements=8, steps_per_rev=spr, tol=1e-10, **_crank(motion, 0.8))
        assert st.ok, st.message
        p = eb.power_history(Model(st.case), st.t, st.states, st.rates, st.accelerations, averaged=True)
        power = st.torque * st.crank_speed
        np.testing.assert_allclose(power, p["P_pin"], rtol=0, atol=1e-12 * np.max(np.abs(power)))
        W = {k: eb.cumulative(st.t, x)[-1] for k, x in (("pin", power), ("diss", p["P_diss"]),
                                                         ("frame", p["P_frame"]))}
        scale = eb.cumulative(st.t, np.abs(power))[-1]
        assert abs(p["E"][-1] - p["E"][0]) < 1e-10 * scale                    # a steady revolution
        assert W["pin"] > 0.1 * scale and W["diss"] > 0.1 * scale
        defects.append(abs(W["pin"] - W["diss"] + W["frame"]) / scale)
        without_frame = abs(W["pin"] - W["diss"]) / scale
    assert defects[1] < 5e-5, defects
    assert 3.5 < defects[0] / defects[1] < 4.5, defects                       # O(dt^2)
    assert without_frame > 10 * defects[1], (without_frame, defects)
