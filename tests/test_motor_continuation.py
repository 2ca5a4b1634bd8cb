"""Continuation of a motor-driven crank's steady motion in a motor parameter (bifurcation/mechanism.py, AutonomousMap)
against independent steady states at the branch's points."""

import warnings

import numpy as np
import pytest

import crankgen
from crankgen.notices import BeyondTheoryWarning

MOTOR = dict(stall_torque=0.05, inertia=0.05)


@pytest.mark.slow
def test_a_branch_in_the_no_load_speed_is_the_steady_motions():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondTheoryWarning)
        d = crankgen.continuation(parameter="no_load_speed", start=0.7, stop=0.9, dp_max=0.05, max_period=1,
                                  crank=crankgen.Motor(no_load_speed=0.7, **MOTOR), n_elements=2)
    br = d.branches[0]
    assert br.stop_reason.startswith("reached") and br.parameter[-1] == pytest.approx(0.9)
    speed = br.quantities["mean_speed"]
    assert np.all(np.diff(speed) > 0) and np.all(speed < br.parameter)    # below the no-load speed
    for k in (0, len(br) - 1):
        s = crankgen.steady_state(crank=crankgen.Motor(no_load_speed=float(br.parameter[k]), **MOTOR), n_elements=2)
        assert speed[k] == pytest.approx(s.mean_speed, rel=1e-7)
        assert br.quantities["revolution_time"][k] == pytest.approx(s.period, rel=1e-7)
        assert br.stable[k] == (s.multiplier < 1.0)
        assert abs(br.multipliers[k][0]) == pytest.approx(s.multiplier, rel=1e-5)
