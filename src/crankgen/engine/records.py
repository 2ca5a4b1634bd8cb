"""Named records the compiled engine passes around in place of positional vectors.

- Kernels: a model's compiled kernels as tables of native addresses (engine/kernels.py, called by
  engine/calls.py): per family slot the selected variant's lane function ("rod" families, acting
  on every element: schema.LANES elements a call) or one-element function ("end" families, acting
  on the rod's end node); a mode argument says what they add; a no-op for an absent family; and
  the guide's end map and kinematics and the crank motion (one-entry tables); a driven motion's
  co-ordinate equations (`coords`, coordinates_<motion>: a no-op for a prescribed motion).
- Cases: one row per case of a batch: `select` (the table index of each family's variant, -1 when
  absent, then the guide and the motion), `coef` (the element kernels' coefficients), `params`
  (the kinematic parameters), the time step, `p` (the parameter vector, for the engine's
  outputs), the Newton scheme code (newton.SCHEMES), whether the one-pass scheme iterates with the
  printed eq. (37) matrices, the natural size of every reduced DOF (`scales`), and the time
  scheme's (beta, gamma, alpha_m, alpha_f) (`integ`: crankgen.discrete.time_scheme; alpha_m = alpha_f = 0
  is Newmark), and a motor's torque curve (`curve`: its departure from the drive kernel's linear
  law at its first `curve_n` knots, rows (thetad, D, D'); count 0: none; crankgen.torque_curve).
- MeshData: the DOF map as the engine reads it: the element DOF map, bandwidth, element length,
  what the engine's outputs accumulate (schema.PRIMITIVES): for each point primitive its place in
  prims, its element and its shape functions there; for each integral its place and Gram matrix;
  and the state's layout: `n_rod` nodal co-ordinates (the band), then the motion's declared
  co-ordinates (records.Coordinate: `crank_index`, the index among them of the crank angle, -1
  none; `motor_index`, of the one a torque curve drives), and the crank pin's eliminated slots of element 0
  (`pin_slots`: its reaction, which the co-ordinates' equations read).
- Scheme: the Newton tolerance and iteration limit.
- Work: the scratch arrays of one case's Newmark steps (allocated once per case and reused).
Every record is a namedtuple of arrays and numbers: numba compiles them as such, and with
NUMBA_DISABLE_JIT=1 the same code runs as plain Python.
"""

from collections import namedtuple

import numpy as np

from ..declaration import schema
from .compiled import jit

NDOF = schema.ELEMENT_DOFS
LANES, LANE_SIZE = schema.LANES, schema.LANE_SIZE
N_KIN = len(schema.KINEMATICS)
# the components the DOF map's mapped constraints eliminate at their node (the guide's end, a
# flexible rocker's tip: the same k; their reduced co-ordinates m per mesh, MeshData.held_reduced)
_MAPPED = [c for c in schema.CONSTRAINTS if c.map is not None]
K_ELIM = len(_MAPPED[0].eliminated)
assert all(len(c.eliminated) == K_ELIM for c in _MAPPED)
N_OUTPUTS = len(schema.ENGINE_OUTPUTS)          # the engine's per-step outputs
N_PRIMITIVES = len(schema.PRIMITIVES)           # what it accumulates for them

Kernels = namedtuple("Kernels", [
    "rod", "end",                       # per family slot acting on every element (its lane function) /
                                        # on the end node (its one-element function)
    "end_map", "guide", "motion",       # (one entry each)
    "coords",                           # a driven motion's co-ordinate equations (coordinates_<motion>; a no-op)
])

Cases = namedtuple("Cases", ["select", "coef", "params", "dt", "p", "scheme", "printed", "scales", "integ", "curve",
                             "curve_n"])

MeshData = namedtuple("MeshData", ["dofs", "kb", "l", "point_slots", "point_elements", "point_weights",
                                   "gram_slots", "grams", "n_rod", "crank_index", "motor_index", "pin_slots",
                                   "bodies", "lengths", "frames", "held", "held_slots", "held_reduced"])

Scheme = namedtuple("Scheme", ["tol", "max_iter"])

Work = namedtuple("Work", [
    "rE", "SE", "KE", "CE", "ME",       # element residuals, iteration and tangent matrices
    "R", "rhs",                         # assembled residual, right-hand side / solution (n_rod + kb, 1)
    "W", "piv", "ext",                  # pivoted band LU storage
    "F", "diag",                        # fixed-bandwidth LU storage (n_rod + kb, 2 kb + 1) (banded.py)
    "kin", "crank",                     # kinematics vector; (theta, thetad, thetadd)
    "q", "qd", "qdd", "geo",            # one element's nodal vectors and (l, x0)
    "send", "E",                        # the end map's (s, sd, sdd) and its (8, 2) values
    "r1", "S1", "K1", "C1", "M1",       # one element's residual and matrices (the element loop's scratch)
    "lanes",                            # lane buffers of the elements, schema.LANES a buffer
    "prims", "q_end",                   # the primitives of the engine's outputs; the mapped node's eliminated components
    "mapped", "held", "held_slots", "held_reduced",    # the DOF map's condensation: `condensation`
    "qc", "qdc", "qddc", "Ec",          # per holding element: its mapped nodal state and map values
    "px", "pr",                         # the projection's scratch: eliminated entries (3, K_ELIM), reduced (3, m)
    "bodies", "lengths", "frames", "kinb",   # the flexible bodies: element ranges, element lengths, frame maps, kinematics
    "dp", "vp",                         # a step's predictors (N)
    # the border of the declared co-ordinates (m of them; the state is the n_rod nodal co-ordinates, then them)
    "zin", "pin", "geq", "geq1",        # the co-ordinate kernel's z (3 m) and pin force (2); its rows (m, 3 m + 3)
    "R0", "Yb", "Cb", "Sm", "gz",       # residual (n_rod); S^-1 B (m, n_rod); C^T (m, n_rod); Schur complement (m, m); dz
])


def condensation(n, holders, m):
    """The DOF map's condensation on n elements (every flexible body's), from the mapped constraint's
    holders (crankgen.discrete.mesh.Mesh.holders: element, eliminated slots, reduced slots) and its m
    reduced co-ordinates: (held (h,): the holding elements; held_slots (h, K_ELIM): the eliminated
    components' places in each; held_reduced (h, m): the places of the reduced co-ordinates there)."""
    held = np.array([e for e, _, _ in holders], dtype=np.int64)
    slots = np.array([list(s) for _, s, _ in holders], dtype=np.int64).reshape(len(holders), K_ELIM)
    reduced = np.array([list(r) for _, _, r in holders], dtype=np.int64).reshape(len(holders), m)
    return held, slots, reduced


def _make_work(mesh, N):
    """Work arrays for the mesh's elements (every flexible body's), N reduced DOFs of which n_rod
    nodal ones (the rest the declared co-ordinates), its bandwidth and mapped constraint."""
    n, kb, n_rod = mesh.dofs.shape[0], mesh.kb, mesh.n_rod
    held, held_slots, held_reduced = mesh.held, mesh.held_slots, mesh.held_reduced
    mapped = np.full(n, -1, dtype=np.int64)
    for i in range(held.shape[0]):
        mapped[held[i]] = i
    m = N - n_rod
    h = held.shape[0]
    mr = held_reduced.shape[1]
    rows = 3 + 4 * mr + mr * mr                 # the map's rows (crankgen.discrete.constraints.map_rows)
    nb = mesh.bodies.shape[0]
    return Work(np.zeros((n, NDOF)), np.zeros((n, NDOF, NDOF)), np.zeros((n, NDOF, NDOF)),
                np.zeros((n, NDOF, NDOF)), np.zeros((n, NDOF, NDOF)), np.zeros(n_rod), np.zeros((n_rod + kb, 1)),
                np.zeros((n_rod, 3 * kb + 1)), np.zeros(n_rod, dtype=np.int64), np.zeros(n_rod, dtype=np.int64),
                np.zeros((n_rod + kb, 2 * kb + 1)), np.zeros(n_rod), np.zeros(N_KIN), np.zeros(3),
                np.zeros(NDOF), np.zeros(NDOF), np.zeros(NDOF), np.zeros(2), np.zeros(3 * mr),
                np.zeros((rows, K_ELIM)),
                np.zeros(NDOF), np.zeros((NDOF, NDOF)), np.zeros((NDOF, NDOF)), np.zeros((NDOF, NDOF)),
                np.zeros((NDOF, NDOF)), np.zeros(((n + LANES - 1) // LANES + nb, LANE_SIZE)), np.zeros(N_PRIMITIVES),
                np.zeros(K_ELIM), mapped, held.copy(), held_slots.copy(), held_reduced.copy(), np.zeros((h, NDOF)),
                np.zeros((h, NDOF)), np.zeros((h, NDOF)), np.zeros((h, rows, K_ELIM)), np.zeros((3, K_ELIM)),
                np.zeros((3, mr)), mesh.bodies.copy(), mesh.lengths.copy(), mesh.frames.copy(), np.zeros((nb, N_KIN)),
                np.zeros(N), np.zeros(N),
                np.zeros(3 * m), np.zeros(2), np.zeros((m, 3 * m + 3)), np.zeros((m, 3 * m + 3)),
                np.zeros(n_rod), np.zeros((m, n_rod)), np.zeros((m, n_rod)), np.zeros((m, m)), np.zeros(m))


make_work = jit(_make_work, python=False)       # inside compiled code
new_work = _make_work                           # the same arrays, from Python
