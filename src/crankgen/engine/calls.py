"""Calling a compiled kernel by its address, from compiled code.

The engine is compiled once for every model; the kernels it calls differ from model to model.
They travel as tables of native function addresses (int64 arrays, records.Kernels), and
`call(table, k, args)` calls entry k with the argument tuple args:

- compiled, it is an indirect call with numba's own calling convention (the kernels' arguments
  passed exactly as between two compiled functions), emitted by the intrinsic `_call_address`;
- with numba switched off (NUMBA_DISABLE_JIT=1), the tables hold the Python functions and `call`
  is a plain call.

(numba's first-class function values would do the same, but every call site carries a fallback
through the Python interpreter for functions without a known address, which made the engine's
compiled code several times larger and its compilation slower.)  The kernels are compiled with
numba's "numpy" error model: they never raise, so the status code of the call is not inspected;
a division by zero gives an infinity, which the engine reports as a non-finite state.
"""

from numba import types
from numba.core import cgutils
from numba.core.extending import intrinsic, overload


def address(dispatcher, signature):
    """Native address of a dispatcher's compilation for signature (numba's calling convention)."""
    cres = dispatcher.overloads[signature.args]
    return cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name)


@intrinsic
def _call_address(typingctx, addr, args):
    """Call the compiled function at address addr (int64) with the arguments of the tuple args."""
    argtys = tuple(args.types)

    def codegen(context, builder, signature, llargs):
        fnty = context.call_conv.get_function_type(types.void, argtys)
        fn = builder.inttoptr(llargs[0], fnty.as_pointer())
        values = cgutils.unpack_tuple(builder, llargs[1], len(argtys))
        context.call_conv.call_function(builder, fn, types.void, argtys, values)
        return context.get_dummy_value()
    return types.void(addr, args), codegen


def call(table, k, args):
    """table[k](*args): the Python form, used when numba is switched off."""
    table[k](*args)


@overload(call, jit_options={"nogil": True})
def _call_overload(table, k, args):
    def impl(table, k, args):
        _call_address(table[k], args)
    return impl
