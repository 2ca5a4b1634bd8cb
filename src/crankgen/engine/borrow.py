"""Borrowed arrays: the hot loops of the engine without atomic reference counting.

numba counts references to the memory of every array: each array a compiled function receives or
binds (every member of a record of arrays, every view, every argument of a kernel call) costs an
atomic increment and decrement.  A borrowed array is the same array (data, shape, strides) without
its memory owner, so that the counting does nothing.

A borrowed array does not keep its memory alive: the owner must outlive it.  The engine borrows
only (a) arrays passed in from Python (the caller holds them for the whole call) and (b) the Work
arrays of a case, whose owning record stays bound until the case is done (`keep(w)` after the last
use of the borrowed ones)."""

from numba.core import types
from numba.core.extending import intrinsic, overload
from numba.np.arrayobj import make_array, populate_array

from .compiled import jit
from .records import Cases, Kernels, MeshData, Work


def borrowed(a):
    """The array a without its memory owner (module docstring); with numba switched off
    (NUMBA_DISABLE_JIT=1), a itself."""
    return a


@intrinsic
def _borrowed(typingctx, a):
    if not isinstance(a, types.Array):
        return None

    def codegen(context, builder, signature, args):
        src = make_array(a)(context, builder, value=args[0])
        out = make_array(a)(context, builder)
        populate_array(out, data=src.data, shape=src.shape, strides=src.strides, itemsize=src.itemsize,
                       meminfo=None)
        return out._getvalue()

    return a(a), codegen


@overload(borrowed, jit_options={"nogil": True})
def _borrowed_overload(a):
    if isinstance(a, types.Array):
        return lambda a: _borrowed(a)


@jit(python=False)
def borrowed_work(w):
    return Work(
        borrowed(w.rE), borrowed(w.SE), borrowed(w.KE), borrowed(w.CE), borrowed(w.ME), borrowed(w.R),
        borrowed(w.rhs), borrowed(w.W), borrowed(w.piv), borrowed(w.ext), borrowed(w.F), borrowed(w.diag),
        borrowed(w.kin), borrowed(w.crank), borrowed(w.q), borrowed(w.qd), borrowed(w.qdd), borrowed(w.geo),
        borrowed(w.send), borrowed(w.E), borrowed(w.r1), borrowed(w.S1), borrowed(w.K1), borrowed(w.C1),
        borrowed(w.M1), borrowed(w.lanes), borrowed(w.prims), borrowed(w.q_end), borrowed(w.mapped),
        borrowed(w.held), borrowed(w.held_slots), borrowed(w.held_reduced), borrowed(w.qc), borrowed(w.qdc),
        borrowed(w.qddc), borrowed(w.Ec), borrowed(w.px), borrowed(w.pr),
        borrowed(w.bodies), borrowed(w.lengths), borrowed(w.frames), borrowed(w.kinb),
        borrowed(w.dp), borrowed(w.vp), borrowed(w.zin), borrowed(w.pin), borrowed(w.geq), borrowed(w.geq1),
        borrowed(w.R0), borrowed(w.Yb), borrowed(w.Cb), borrowed(w.Sm), borrowed(w.gz))


@jit(python=False)
def borrowed_cases(c):
    return Cases(borrowed(c.select), borrowed(c.coef), borrowed(c.params), borrowed(c.dt), borrowed(c.p),
                 borrowed(c.scheme), borrowed(c.printed), borrowed(c.scales), borrowed(c.integ), borrowed(c.curve),
                 borrowed(c.curve_n))


@jit(python=False)
def borrowed_mesh(m):
    return MeshData(borrowed(m.dofs), m.kb, m.l, borrowed(m.point_slots), borrowed(m.point_elements),
                    borrowed(m.point_weights), borrowed(m.gram_slots), borrowed(m.grams), m.n_rod, m.crank_index, m.motor_index,
                    borrowed(m.pin_slots), borrowed(m.bodies), borrowed(m.lengths), borrowed(m.frames),
                    borrowed(m.held), borrowed(m.held_slots), borrowed(m.held_reduced))


@jit(python=False)
def borrowed_kernels(k):
    return Kernels(borrowed(k.rod), borrowed(k.end), borrowed(k.end_map), borrowed(k.guide), borrowed(k.motion),
                   borrowed(k.coords))


@jit(python=False)
def keep(owner):
    """A use of owner (an array or a record of arrays): it stays bound, and its memory alive, up to
    here."""
    return 0
