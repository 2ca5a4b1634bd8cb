"""A steady state's row (results/steady_row.py) in SI on the rod of an SIMechanism: the rod's
fields, every parameter and result with a unit by its SI name, in its SI unit."""

from ..declaration import schema
from ..declaration.units import ROD, Scales, same_in_si
from ..errors import ParameterError
from .exports import column, suffix
from .steady_row import meaning, units_of
from .tables import PAIRS


def _row_columns(row, rod):
    """[(SI column, value in SI, SI unit, meaning)] of a steady state's row on a rod (row_in_si)."""
    scales = rod.scales
    for unit, name in schema.UNIT_PARAMETERS.items():         # the row must be of this rod
        value = row.get(name)
        own = scales.base[unit] / scales.L
        if value is not None and abs(float(value) / own - 1) > 1e-9:
            raise ParameterError(f"the row's {schema.PARAMETERS[name].label} = {float(value):g} is not the rod's "
                                 f"({own:g}, from its L, A and I): its SI form needs its own SIMechanism")
    out = [(f"{name}_{suffix(unit)}", getattr(rod, name), unit, f"{what} (of the rod)") for name, unit, what in ROD]
    for key, value in row.items():
        units = units_of(key)
        if units is None or same_in_si(units):
            continue
        p = schema.PARAMETERS.get(key)
        name = (p.si or p.name) if p is not None else key
        f, unit = scales.factor(units), Scales.si_name(units)
        what = f"{meaning(key)}; in SI: the value times {units}, in {unit}"
        if p is not None and p.kind == "pair":
            for k, part in enumerate(PAIRS[key]):
                x = None if value is None else value[k]
                out.append((column(name + part[len(key):], units, True), None if x is None else x * f, unit,
                            f"{what} ({'XY'[k]} component)"))
        else:
            out.append((column(name, units, True), None if value is None else value * f, unit, what))
    return out

def row_in_si(row, si_mechanism):
    """The SI columns of a steady state's row (crankgen.results.steady_row) on the rod of an SIMechanism
    (its L, E, rho, A, I; the row's slenderness must be the rod's): the rod's fields (L_m, E_Pa,
    ...), every parameter with a unit by its SI name (a_m, slider_mass_kg, gravity_x_m_per_s2,
    crank_speed_rad_per_s, ...) and every result with a unit (amplitude_m, peak_torque_N_m, ...),
    each named with its SI unit; None stays None."""
    return {c: v for c, v, _, _ in _row_columns(row, si_mechanism)}

def describe_row_in_si(row, si_mechanism):
    """[{column, units, meaning}] of the SI columns row_in_si adds."""
    return [{"column": c, "units": u, "meaning": m} for c, _, u, m in _row_columns(row, si_mechanism)]
