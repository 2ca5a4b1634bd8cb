"""The generated kernels, compiled: every element kernel variant that the generated dispatch calls,
the dispatch functions themselves (bound to the compiled kernels), the kinematics kernel and the
shared Newton-Newmark decisions.  Nothing here names a term family: the list of kernels and the
dispatch come from generated/dispatch.py."""

from .. import newton as _newton
from .._generated import dispatch as _dispatch
from .._generated import elements as _elements
from .._generated import guide as _guide
from .compiled import jit

_VARIANTS = ("_add", "_printed_add", "_residual_add", "_newmark_add")

# every accumulating variant of every element kernel, compiled, under its generated name
COMPILED_KERNELS = {}
for _kernel in _dispatch.ELEMENT_KERNELS:
    for _suffix in _VARIANTS:
        _fn = getattr(_elements, _kernel + _suffix, None)
        if _fn is not None:
            COMPILED_KERNELS[_kernel + _suffix] = jit(_fn)

# dispatch over the families of a model (m: variant index per family, -1 absent)
rod_add = jit(_dispatch.rod_add, namespace=COMPILED_KERNELS)
rod_residual_add = jit(_dispatch.rod_residual_add, namespace=COMPILED_KERNELS, inline="always")
rod_newmark_add = jit(_dispatch.rod_newmark_add, namespace=COMPILED_KERNELS, inline="always")
end_add = jit(_dispatch.end_add, namespace=COMPILED_KERNELS)
end_residual_add = jit(_dispatch.end_residual_add, namespace=COMPILED_KERNELS, inline="always")
end_newmark_add = jit(_dispatch.end_newmark_add, namespace=COMPILED_KERNELS, inline="always")

# kin = (a, theta, thetad, phi, phid, phidd) at time t (derive/guide.py)
crank_kinematics_into = jit(_guide.crank_kinematics_into)

# Newton-Newmark decisions, the same code as the NumPy reference's (crankgen/newton.py)
extrapolation_weight = jit(_newton.extrapolation_weight)
next_iteration = jit(_newton.next_iteration)
