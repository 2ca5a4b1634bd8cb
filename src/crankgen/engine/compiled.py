"""Compilation with numba, cached on disk under a hash of the compiled code, and repaired when unreadable.

numba's own cache is keyed by the source file of each compiled function: a function that calls a
function of another file (the Newmark step) is not recompiled when only that other file changed,
so after `make derive` or an edit of the engine a stale engine would run.  Every crankgen function
is therefore cached in the folder of crankgen.engine.cache, named by CODE_HASH (the generated
kernels' specification and the engine's source), with that hash also in its source stamp: changed
kernels or engine code always get a fresh compilation.

The folder may be read-only (a shared installation): then what was compiled there is loaded and
the rest is compiled in memory for this run; saving never fails a run (a full disk, a read-only
folder: the code just stays in memory).  No home directory is needed.

A cache file that cannot be read (a truncated write, a disk fault, garbage) is removed where it is
loaded, with a one-line warning, and its function compiled again (`_Cache`): every compiled
artefact, the engine's and the kernels', is loaded through that one path.
"""

import sys
import types
import warnings
from pathlib import Path

from numba import njit
from numba.core import caching
from numba.core import types as _types
from numba.core.compiler import CompilerBase, DefaultPassBuilder
from numba.core.compiler_machinery import FunctionPass, register_pass
from numba.core.errors import NumbaExperimentalFeatureWarning
from numba.core.extending import intrinsic, overload
from numba.core.untyped_passes import TranslateByteCode

from .._generated import schema as _table
from .cache import CACHE, CODE_HASH, READ_ONLY, announce, is_warm  # noqa: F401

KERNELS_HASH = _table.KERNELS_HASH
_PACKAGE = Path(__file__).resolve().parent.parent
_GENERATED = Path(_table.__file__).resolve().parent
# numba labels some of what it compiles experimental (first-class function types, which the engine
# no longer uses but a user's own code may); the warning says nothing to a user of crankgen.
warnings.filterwarnings("ignore", category=NumbaExperimentalFeatureWarning)


class _KernelsHashLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """numba cache locator for crankgen's own files: CACHE, with the code hash in the stamp."""

    def __init__(self, py_func, py_file):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._cache_path = str(CACHE / Path(py_file).parent.name)

    def get_cache_path(self):
        return self._cache_path

    def ensure_cache_path(self):
        if READ_ONLY:                   # load what is there; saving is skipped (_Cache below)
            return
        super().ensure_cache_path()

    def get_source_stamp(self):
        return (super().get_source_stamp(), CODE_HASH)

    @classmethod
    def from_function(cls, py_func, py_file):
        path = Path(py_file).resolve()
        if not (path.is_relative_to(_PACKAGE) or path.is_relative_to(_GENERATED)):
            return None
        return super().from_function(py_func, py_file)


if _KernelsHashLocator not in caching.CacheImpl._locator_classes:
    caching.CacheImpl._locator_classes.insert(0, _KernelsHashLocator)


class _Cache(caching.FunctionCache):
    """numba's function cache that never fails a run, and the one place where compiled code is
    loaded from disk (the engine's entry points, everything they call, and every kernel alike):
    a folder that cannot be read loads nothing (the code is compiled), one that cannot be written
    (read-only, a full disk) saves nothing, and a damaged file (garbage, truncated or empty: any
    failure to unpickle or rebuild what it holds) is removed with a one-line warning, with the
    rest of this function's files, and the function is compiled again."""

    def load_overload(self, sig, target_context):
        try:
            return super().load_overload(sig, target_context)
        except OSError:
            return None
        except Exception as exc:
            self._remove_damaged(exc)
            return None

    def save_overload(self, sig, data):
        if READ_ONLY:
            return
        try:
            super().save_overload(sig, data)
        except OSError as exc:
            _note_unsaved(exc)
        except Exception as exc:                 # an index damaged since it was loaded
            self._remove_damaged(exc)
            try:
                super().save_overload(sig, data)
            except Exception as again:
                _note_unsaved(again)

    def _files(self):
        """This function's index file and data files in the cache folder."""
        index = Path(self._cache_file._index_path)
        pattern = self._cache_file._data_name_pattern.replace("{number:d}", "*")
        return [index] + sorted(index.parent.glob(pattern))

    def _remove_damaged(self, exc):
        removed = []
        if not READ_ONLY:
            for path in self._files():
                try:
                    path.unlink()
                    removed.append(path.name)
                except FileNotFoundError:
                    pass
                except OSError:
                    continue
        what = (f"removed {', '.join(removed)}" if removed else "left it (read-only)")
        warnings.warn(f"crankgen: damaged compiled code of {self._name} in {CACHE} "
                      f"({type(exc).__name__}: {str(exc)[:80]}); {what}, compiling it again",
                      RuntimeWarning, stacklevel=2)


_unsaved = []


def _note_unsaved(exc):
    if not _unsaved:
        _unsaved.append(exc)
        try:
            print(f"crankgen: could not save compiled code in {CACHE} ({exc}); it is kept in memory "
                  "for this run", file=sys.stderr, flush=True)
        except (OSError, ValueError):
            pass


def _with_cache(dispatcher):
    """A dispatcher made with cache=False, given crankgen's cache."""
    if hasattr(dispatcher, "py_func") and hasattr(dispatcher, "_cache"):
        try:
            dispatcher._cache = _Cache(dispatcher.py_func)
        except (RuntimeError, OSError) as exc:       # no usable folder: compile in memory
            _note_unsaved(exc)
    return dispatcher


@register_pass(mutates_CFG=False, analysis_only=True)
class _ArgumentsDoNotAlias(FunctionPass):
    """Marks the compiled function's pointer arguments (the arrays' data among them) noalias."""
    _name = "crankgen_arguments_do_not_alias"

    def __init__(self):
        FunctionPass.__init__(self)

    def run_pass(self, state):
        state.flags.noalias = True
        return False


class _NoAliasCompiler(CompilerBase):
    """numba's nopython pipeline for a function whose array arguments never share memory: the
    compiler may then vectorize its loops without checking at run time that they do not."""

    def define_pipelines(self):
        pm = DefaultPassBuilder.define_nopython_pipeline(self.state)
        pm.add_pass_after(_ArgumentsDoNotAlias, TranslateByteCode)
        pm.finalize()
        return [pm]


def jit(fn=None, name=None, namespace=None, inline="never", signature=None, error_model="python", python=True,
        noalias=False):
    """fn compiled with numba (nopython, releasing the GIL, cached as above).  name: compile a copy
    under another name (numba's cache is keyed by the qualified name); namespace: globals to bind in
    the copy; inline="always" inlines fn into its callers at numba's IR level (small functions
    called per element); signature: compile now, for exactly this signature (the kernels the engine
    calls by address); error_model: numba's ("numpy": never raise, e.g. x / 0 is inf); python:
    False for a function only compiled code calls (no Python wrapper is compiled for it: less
    compile time); noalias: the function's array arguments never share memory (the lane kernels:
    their loops are vectorized only so).  No function is used as a numba first-class function (no
    cfunc wrapper).  As a decorator: @jit or @jit(python=False)."""
    if fn is None:
        return lambda f: jit(f, name, namespace, inline, signature, error_model, python, noalias)
    if name is not None or namespace is not None:
        glob = dict(fn.__globals__)
        glob.update(namespace or {})
        copy = types.FunctionType(fn.__code__, glob, name or fn.__name__, fn.__defaults__, fn.__closure__)
        copy.__qualname__ = name or fn.__qualname__
        copy.__doc__ = fn.__doc__
        copy.__module__ = fn.__module__
        fn = copy
    options = dict(pipeline_class=_NoAliasCompiler) if noalias else {}
    dispatcher = _with_cache(njit(nogil=True, inline=inline, error_model=error_model, no_cfunc_wrapper=True,
                                  no_cpython_wrapper=not python, **options)(fn))
    if signature is not None and hasattr(dispatcher, "compile"):
        dispatcher.compile(signature)
        dispatcher.disable_compile()
    return dispatcher


def plain(x):
    """x, typed as a plain value in compiled code: numba compiles a function called with a constant
    (a literal) once more for that constant; through plain, every call shares one compilation."""
    return x


@intrinsic
def _plain(typingctx, x):
    plain_type = _types.unliteral(x)

    def codegen(context, builder, signature, args):
        return context.cast(builder, args[0], x, plain_type)
    return plain_type(x), codegen


@overload(plain, jit_options={"nogil": True})
def _plain_overload(x):
    return lambda x: _plain(x)


def call(fn, *args):
    """fn(*args), after saying once that a read-only cache cannot keep what is compiled (a
    damaged cache file is repaired where it is loaded: _Cache)."""
    announce()
    return fn(*args)
