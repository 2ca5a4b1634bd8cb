"""The generated kernels, compiled one at a time when a case first needs them, and gathered into the
tables of first-class functions the engine calls (records.Kernels).

The engine itself is compiled once for every model: it receives the kernels as arguments (tables
of compiled functions with one signature per calling variant) and a case's `select` row says which
entry of each table to call.  A kernel no case of a batch needs is never compiled: its entries
hold a no-op of the same signature.  Each compiled kernel is cached on disk like the engine
(compiled.py), so a model's kernels are compiled once per machine.

Layout of `select` (per case): one slot per family acting on every element ("rod" families, in
the schema's order), one per family acting on the end node ("end"), then the guide and the crank
motion; a family slot holds the flat index of its selected variant in the part's tables (-1: the
family is absent).
"""

import numpy as np
from numba import types

from .. import newton as _newton
from .. import schema
from .._generated import elements as _elements
from .._generated import kinematics as _kinematics
from .._generated import schema as _table
from .compiled import jit
from .records import Kernels

_V = types.float64[::1]
_M = types.float64[:, ::1]
_F = types.float64
SIGNATURES = {
    "_add": types.void(_V, _V, _V, _V, _V, _V, _V, _M, _M, _M),
    "_printed_add": types.void(_V, _V, _V, _V, _V, _V, _V, _M, _M, _M),
    "_residual_add": types.void(_V, _V, _V, _V, _V, _V, _V),
    "_newmark_add": types.void(_V, _V, _V, _V, _V, _V, _F, _F, _V, _M),
    "end_map": types.void(_V, _V, _V, _M),
    "guide": types.void(_V, _V, _V),
    "motion": types.void(_F, _V, _V),
}

PARTS = ("rod", "end")
FAMILY_SLOTS = {part: [f for f in _table.FAMILIES if f[1] == part] for part in PARTS}
# flat variant tables per part: (family name, variant index, element kernel name)
VARIANTS = {part: [(f[0], k, v[1]) for f in FAMILY_SLOTS[part] for k, v in enumerate(f[5])] for part in PARTS}
GUIDE_NAMES = tuple(schema.GUIDES)
MOTION_NAMES = tuple(schema.MOTIONS)
N_ROD, N_END = len(FAMILY_SLOTS["rod"]), len(FAMILY_SLOTS["end"])
GUIDE_SLOT, MOTION_SLOT = N_ROD + N_END, N_ROD + N_END + 1
SELECT_SIZE = N_ROD + N_END + 2


def select_row(case):
    """The case's `select` row (module docstring)."""
    by_family = dict(zip((f[0] for f in _table.FAMILIES), case.selection.families))
    row = []
    for part in PARTS:
        for f in FAMILY_SLOTS[part]:
            k = by_family[f[0]]
            row.append(-1 if k < 0 else VARIANTS[part].index((f[0], k, f[5][k][1])))
    return row + [GUIDE_NAMES.index(case.guide), MOTION_NAMES.index(case.motion)]


# ---- no-ops: the entries of kernels no case needs ---------------------------------------------------

def _noop_add(q, qd, qdd, geo, coef, kin, r, K, C, M):
    pass


def _noop_residual(q, qd, qdd, geo, coef, kin, r):
    pass


def _noop_newmark(q, qd, qdd, geo, coef, kin, cv, cd, r, S):
    pass


def _noop3(x, y, z):
    pass


def _noop_end_map(send, kin, params, E):
    pass


def _noop_motion(t, params, crank):
    pass


_NOOP_SOURCE = {"_add": _noop_add, "_printed_add": _noop_add, "_residual_add": _noop_residual,
                "_newmark_add": _noop_newmark, "end_map": _noop_end_map, "guide": _noop3,
                "motion": _noop_motion}
_COMPILED = {}


def _noop(kind):
    kind = "_add" if kind == "_printed_add" else kind          # one signature
    key = ("noop", kind)
    if key not in _COMPILED:
        _COMPILED[key] = jit(_NOOP_SOURCE[kind], signature=SIGNATURES[kind],
                             name=f"noop{kind if kind.startswith('_') else '_' + kind}")
    return _COMPILED[key]


def _source(kind, name):
    """The generated one-element function of a kernel for a calling variant."""
    if kind in ("end_map", "guide", "motion"):
        return getattr(_kinematics, f"{kind}_{name}_into")
    fn = getattr(_elements, name + kind, None)
    if fn is None and kind == "_printed_add":        # no printed iteration matrix: the exact tangent
        fn = getattr(_elements, name + "_add")
    return fn


def compiled(kind, name):
    """The compiled kernel `name` in calling variant `kind` (compiled on first use, cached on disk;
    engine/build.py compiles a run's kernels ahead, on two processes)."""
    key = (kind, name)
    if key not in _COMPILED:
        _COMPILED[key] = jit(_source(kind, name), signature=SIGNATURES[kind])
    return _COMPILED[key]


def needed(rows, printed):
    """{(kind, kernel name)} that the cases with these select rows call (printed: per case, whether
    the one-pass scheme iterates with the printed eq. (37) matrices)."""
    out = set()
    for row, uses_printed in zip(rows, printed):
        for part, offset, count in (("rod", 0, N_ROD), ("end", N_ROD, N_END)):
            for k in range(count):
                i = row[offset + k]
                if i < 0:
                    continue
                name = VARIANTS[part][i][2]
                kinds = ("_add", "_residual_add") + (("_newmark_add",) if part == "rod" else ())
                out.update((kind, name) for kind in kinds)
                if uses_printed:
                    out.add(("_printed_add", name))
        out.add(("end_map", GUIDE_NAMES[row[GUIDE_SLOT]]))
        out.add(("guide", GUIDE_NAMES[row[GUIDE_SLOT]]))
        out.add(("motion", MOTION_NAMES[row[MOTION_SLOT]]))
    return out


def tables(rows, printed):
    """records.Kernels for cases with these select rows and printed flags (see needed): their
    kernels compiled, no-ops elsewhere."""
    need = needed(rows, printed)

    def entry(kind, name):
        return compiled(kind, name) if (kind, name) in need else _noop(kind)

    def part_table(part, kind):
        return tuple(entry(kind, name) for _, _, name in VARIANTS[part])

    return Kernels(
        part_table("rod", "_add"), part_table("rod", "_printed_add"), part_table("rod", "_residual_add"),
        part_table("rod", "_newmark_add"), part_table("end", "_add"), part_table("end", "_printed_add"),
        part_table("end", "_residual_add"),
        tuple(entry("end_map", g) for g in GUIDE_NAMES), tuple(entry("guide", g) for g in GUIDE_NAMES),
        tuple(entry("motion", m) for m in MOTION_NAMES))


def noop_tables():
    """records.Kernels with a no-op in every entry (the engine's types, nothing compiled)."""
    def part_table(part, kind):
        return tuple(_noop(kind) for _ in VARIANTS[part])
    return Kernels(
        part_table("rod", "_add"), part_table("rod", "_printed_add"), part_table("rod", "_residual_add"),
        part_table("rod", "_newmark_add"), part_table("end", "_add"), part_table("end", "_printed_add"),
        part_table("end", "_residual_add"), tuple(_noop("end_map") for _ in GUIDE_NAMES),
        tuple(_noop("guide") for _ in GUIDE_NAMES), tuple(_noop("motion") for _ in MOTION_NAMES))


def build_items(rows, printed):
    """The build items (engine/build.py) of the kernels these cases call."""
    return [f"kernel:{kind}:{name}" for kind, name in sorted(needed(rows, printed))]


def all_build_items():
    """The build items of every kernel of every model (crankgen compile)."""
    items = set()
    for part in PARTS:
        for _, _, name in VARIANTS[part]:
            kinds = ("_add", "_residual_add") + (("_newmark_add",) if part == "rod" else ())
            items.update((kind, name) for kind in kinds)
            if hasattr(_elements, name + "_printed_add"):
                items.add(("_printed_add", name))
    items.update(("end_map", g) for g in GUIDE_NAMES)
    items.update(("guide", g) for g in GUIDE_NAMES)
    items.update(("motion", m) for m in MOTION_NAMES)
    return [f"kernel:{kind}:{name}" for kind, name in sorted(items)]


def select_rows(cases):
    return np.array([select_row(c) for c in cases], dtype=np.int64)


# Newton-Newmark decisions, the same code as the NumPy reference's (crankgen/newton.py)
extrapolation_weight = jit(_newton.extrapolation_weight)
next_iteration = jit(_newton.next_iteration)
