"""The generated kernels, compiled one at a time when a case first needs them, and gathered into the
tables of native addresses the engine calls (records.Kernels, engine/calls.py), one table per model: for each
term family slot the selected variant's lane function `<name>_lanes(mode, b, ...)` (families acting
on every element of the rod: schema.LANES elements a call, their loop vectorized) or one-element
function `<name>_element(mode, ...)` (families acting on the end node), a no-op for an absent
family (derive/emit.py: the mode says whether they add the residual and tangents, the printed
iteration matrix, the residual only, or the Newmark iteration matrix); the guide's end map and
kinematics; the crank motion.

The engine itself is compiled once for every model: it receives the kernels as arguments (tables
of the addresses of compiled functions, one signature per kind); a batch whose cases differ in
model runs each model's cases with that model's table.  A kernel no case of a batch needs is never compiled: its entries
hold a no-op of the same signature.  Each compiled kernel is cached on disk like the engine
(compiled.py), so a model's kernels are compiled once per machine.

Layout of `select` (per case): one slot per family acting on every element ("rod" families, in
the schema's order), one per family acting on the end node ("end"), then the guide, the crank
motion and the end map (END_MAP_NAMES: the guide's, or a flexible rocker's); a family slot holds the flat index of its selected variant in the part's tables (-1: the
family is absent).
"""

import functools

import numpy as np
from numba import types
from numba.core import config

from ..discrete import newton as _newton
from ..discrete.mesh import rocker_of
from ..declaration import schema
from .._generated import elements as _elements
from .._generated import kinematics as _kinematics
from .calls import address
from .compiled import jit
from .records import Kernels

_V = types.float64[::1]
_M = types.float64[:, ::1]
_F = types.float64
SIGNATURES = {
    # name_element(mode, q, qd, qdd, geo, coef, kin, cv, cd, r, K, C, M, S): derive/emit.py
    "element": types.void(types.int64, _V, _V, _V, _V, _V, _V, _F, _F, _V, _M, _M, _M, _M),
    # name_lanes(mode, b, coef, kin, cv, cd): the same for schema.LANES elements of the lane buffer b
    "lanes": types.void(types.int64, _V, _V, _V, _F, _F),
    "end_map": types.void(_V, _V, _V, _M),
    "guide": types.void(_V, _V, _V),
    "motion": types.void(_F, _V, _V),
    # coordinates_<m>_into(kin, z, pin, params, g): a driven motion's co-ordinate equations and derivatives
    "coordinates": types.void(_V, _V, _V, _V, _M),
}

PARTS = ("rod", "end")
PART_KIND = {"rod": "lanes", "end": "element"}      # the rod's families run on lanes of elements
FAMILY_SLOTS = {part: [f for f in schema.FAMILIES if f.part == part] for part in PARTS}
# flat variant tables per part: (family name, variant index, element kernel name)
VARIANTS = {part: [(f.name, k, v.kernel) for f in FAMILY_SLOTS[part] for k, v in enumerate(f.variants)]
            for part in PARTS}
GUIDE_NAMES = tuple(schema.GUIDES)
MOTION_NAMES = tuple(schema.MOTIONS)
DRIVEN = tuple(name for name, m in schema.MOTIONS.items() if m.driven)     # motions with a coordinates_ kernel
N_ROD, N_END = len(FAMILY_SLOTS["rod"]), len(FAMILY_SLOTS["end"])
# the end maps: each guide's, then a flexible rocker's for a guide whose end a link carries
# (end_map_<guide>_flexible: the rod's end held by the rocker's tip)
END_MAP_NAMES = GUIDE_NAMES + tuple(f"{g}_flexible" for g in GUIDE_NAMES if schema.GUIDES[g].pivot)
GUIDE_SLOT, MOTION_SLOT, END_MAP_SLOT = N_ROD + N_END, N_ROD + N_END + 1, N_ROD + N_END + 2
SELECT_SIZE = N_ROD + N_END + 3


def select_row(case):
    """The case's `select` row (module docstring)."""
    return list(_select_row(case.selection.families, case.guide_record.name, case.motion_record.name,
                            rocker_of(case)[0] > 0))


@functools.lru_cache(maxsize=256)
def _select_row(families, guide, motion, flexible=False):
    by_family = dict(zip((f.name for f in schema.FAMILIES), families))
    row = []
    for part in PARTS:
        for f in FAMILY_SLOTS[part]:
            k = by_family[f.name]
            row.append(-1 if k < 0 else VARIANTS[part].index((f.name, k, f.variants[k].kernel)))
    end_map = END_MAP_NAMES.index(f"{guide}_flexible" if flexible else guide)
    return tuple(row + [GUIDE_NAMES.index(guide), MOTION_NAMES.index(motion), end_map])


# ---- no-ops: the entries of kernels no case needs ---------------------------------------------------

def _noop_element(mode, q, qd, qdd, geo, coef, kin, cv, cd, r, K, C, M, S):
    pass


def _noop_lanes(mode, b, coef, kin, cv, cd):
    pass


def _noop3(x, y, z):
    pass


def _noop_end_map(send, kin, params, E):
    pass


def _noop_motion(t, params, crank):
    pass


def _noop_coordinates(kin, z, pin, params, g):
    pass


_NOOP_SOURCE = {"element": _noop_element, "lanes": _noop_lanes, "end_map": _noop_end_map, "guide": _noop3,
                "motion": _noop_motion, "coordinates": _noop_coordinates}
_COMPILED = {}


def _noop(kind):
    key = ("noop", kind)
    if key not in _COMPILED:
        _COMPILED[key] = jit(_NOOP_SOURCE[kind], signature=SIGNATURES[kind], name=f"noop_{kind}",
                             error_model="numpy", python=False)
    return _COMPILED[key]


def _source(kind, name):
    """The generated function of a kernel of this kind (lane, one-element or `_into`)."""
    if kind in ("element", "lanes"):
        return getattr(_elements, f"{name}_{kind}")
    return getattr(_kinematics, f"{kind}_{name}_into")


def compiled(kind, name):
    """The compiled kernel `name` of this kind (compiled on first use, cached on disk;
    engine/build.py compiles a run's kernels ahead, on two processes).  The lane kernels' arrays
    never share memory (noalias: their loop over the elements is vectorized)."""
    key = (kind, name)
    if key not in _COMPILED:
        _COMPILED[key] = jit(_source(kind, name), signature=SIGNATURES[kind], error_model="numpy", python=False,
                             noalias=kind == "lanes")
    return _COMPILED[key]


def _entry(kind, dispatcher):
    """A table entry: the kernel's native address (calls.py), or the function itself when numba
    is switched off."""
    if config.DISABLE_JIT:
        return dispatcher
    return address(dispatcher, SIGNATURES[kind])


def _addresses(kind, dispatchers):
    entries = [_entry(kind, d) for d in dispatchers]
    return tuple(entries) if config.DISABLE_JIT else np.array(entries, dtype=np.int64)


def needed(rows):
    """{(kind, kernel name)} that the cases with these select rows call."""
    out = set()
    for row in rows:
        for part, offset, count in (("rod", 0, N_ROD), ("end", N_ROD, N_END)):
            for k in range(count):
                i = row[offset + k]
                if i >= 0:
                    out.add((PART_KIND[part], VARIANTS[part][i][2]))
        out.add(("end_map", END_MAP_NAMES[row[END_MAP_SLOT]]))
        out.add(("guide", GUIDE_NAMES[row[GUIDE_SLOT]]))
        out.add(("motion", MOTION_NAMES[row[MOTION_SLOT]]))
        if MOTION_NAMES[row[MOTION_SLOT]] in DRIVEN:
            out.add(("coordinates", MOTION_NAMES[row[MOTION_SLOT]]))
    return out


def tables(row):
    """records.Kernels of the cases with this select row: per family slot its variant's compiled
    lane (rod) or one-element (end) function (a no-op for an absent family), and the case's end
    map, guide and motion."""
    def slots(part, offset, count):
        kind = PART_KIND[part]
        return _addresses(kind, [compiled(kind, VARIANTS[part][row[offset + k]][2])
                                 if row[offset + k] >= 0 else _noop(kind) for k in range(count)])
    guide, motion = GUIDE_NAMES[row[GUIDE_SLOT]], MOTION_NAMES[row[MOTION_SLOT]]
    return Kernels(slots("rod", 0, N_ROD), slots("end", N_ROD, N_END),
                   _addresses("end_map", [compiled("end_map", END_MAP_NAMES[row[END_MAP_SLOT]])]), _addresses("guide", [compiled("guide", guide)]),
                   _addresses("motion", [compiled("motion", motion)]),
                   _addresses("coordinates", [compiled("coordinates", motion) if motion in DRIVEN
                                              else _noop("coordinates")]))


def noop_tables():
    """records.Kernels with a no-op in every entry (the engine's types, nothing compiled)."""
    return Kernels(_addresses("lanes", [_noop("lanes")] * N_ROD), _addresses("element", [_noop("element")] * N_END),
                   _addresses("end_map", [_noop("end_map")]), _addresses("guide", [_noop("guide")]),
                   _addresses("motion", [_noop("motion")]), _addresses("coordinates", [_noop("coordinates")]))


def build_items(rows):
    """The build items (engine/build.py) of the kernels these cases call."""
    return [f"kernel:{kind}:{name}" for kind, name in sorted(needed(rows))]


def all_build_items():
    """The build items of every kernel of every model (crankgen compile)."""
    items = {(PART_KIND[part], name) for part in PARTS for _, _, name in VARIANTS[part]}
    items.update(("end_map", g) for g in END_MAP_NAMES)
    items.update(("guide", g) for g in GUIDE_NAMES)
    items.update(("motion", m) for m in MOTION_NAMES)
    items.update(("coordinates", m) for m in DRIVEN)
    return [f"kernel:{kind}:{name}" for kind, name in sorted(items)]


def select_rows(cases):
    return np.array([select_row(c) for c in cases], dtype=np.int64)


# Newton-Newmark decisions, the same code as the NumPy reference's (crankgen/newton.py)
extrapolation_weight = jit(_newton.extrapolation_weight, python=False)
next_iteration = jit(_newton.next_iteration, python=False)
