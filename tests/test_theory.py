"""crankgen.analyses.theory against the derivation: the approach it calls ill-posed is the one whose strain
energy (derive/, the densities the kernels are generated from) is unbounded below; the flags."""

import math

import pytest
import sympy as sp

from crankgen.analyses import theory


@pytest.mark.parametrize("approach", ["A", "B", "C"])
def test_ill_posed_is_the_approach_whose_strain_energy_is_unbounded_below(approach):
    from crankgen._derive.audit import densities as d
    membrane = d.strain_density(approach).subs(d.v_xx, 0)      # the part that can be negative
    EA = [s for s in membrane.free_symbols if s.name == "EA"][0]
    stationary = sp.solve(sp.diff(membrane, d.u_x), d.u_x)
    least = sp.expand(membrane.subs(d.u_x, stationary[0])) if stationary else membrane
    unbounded = sp.limit(least.subs(EA, 1), d.v_x, sp.oo) == -sp.oo
    assert theory.ill_posed(approach) == unbounded
    assert theory.strain_energy(approach) == ("unbounded below (ill-posed)" if unbounded else "bounded below")


def test_flags():
    assert theory.beyond(0.05, 0.005) == "no"
    assert theory.beyond(0.15, 0.005) == "yes" and theory.beyond(0.05, 0.02) == "yes"
    assert theory.beyond(math.nan, 0.02) == "yes" and theory.beyond(0.05, math.nan) == "no"
    assert theory.beyond() == ""
    assert theory.deflection_over_L(0.01, -20.0) == pytest.approx(0.2)
    assert math.isnan(theory.deflection_over_L(0.01, None))
    assert "axial strain 0.02 > 0.01" in theory.reasons(0.05, 0.02)
