"""The compiled engine's cache: keyed by the code it compiles, and repaired when unreadable."""

import os
import shutil
import subprocess
import sys

import pytest

from crankgen import compile_cache


def test_the_cache_folder_changes_with_the_kernels_and_the_engine_code(monkeypatch):
    """`make derive` changes KERNELS_HASH in generated/schema.py; an edit of the engine changes
    its source: either gives another CODE_HASH, hence another cache folder and source stamp, so a
    regenerated kernel is never run from a stale compilation."""
    base = compile_cache._code_hash()
    assert base == compile_cache.CODE_HASH
    monkeypatch.setattr(compile_cache, "_kernels_hash", lambda: "0123456789abcdef")
    assert compile_cache._code_hash() != base
    monkeypatch.undo()
    real_read = type(compile_cache._PACKAGE).read_bytes

    def edited(path):
        data = real_read(path)
        return data + b"\n# edited\n" if path.name == "step.py" else data
    monkeypatch.setattr(type(compile_cache._PACKAGE), "read_bytes", edited)
    assert compile_cache._code_hash() != base
    assert compile_cache.CACHE.name == f"numba-{base}"


def test_the_engine_locator_stamps_crankgen_functions_with_the_code_hash():
    from crankgen.engine import compiled, step
    locator = compiled._KernelsHashLocator.from_function(step.newmark_step.py_func,
                                                         step.newmark_step.py_func.__code__.co_filename)
    assert locator is not None
    assert locator.get_source_stamp()[1] == compile_cache.CODE_HASH
    assert str(compile_cache.CACHE) in locator.get_cache_path()


RUN = ("import crankgen; r = crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20, "
       "revolutions=1); print('ok', r.v_mid[-1])")


@pytest.mark.slow
def test_an_unreadable_cache_file_is_removed_and_recompiled_once(tmp_path):
    """A truncated file in the compiled-code cache: the run warns, removes the unreadable files,
    recompiles what they held and succeeds (numba alone fails on every later import)."""
    env = dict(os.environ, CRANKGEN_CACHE_DIR=str(tmp_path))
    subprocess.run([sys.executable, "-c", RUN], capture_output=True, check=True)      # warm cache
    shutil.copytree(compile_cache.CACHE, tmp_path / compile_cache.CACHE.name)         # its copy
    warm = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True)
    assert warm.returncode == 0, warm.stderr
    files = sorted((tmp_path / f"numba-{compile_cache.CODE_HASH}").rglob("*_march_cases*.nb[ic]"))
    assert files, "the run left no cache files of the marching loop"
    for path in files:
        path.write_bytes(path.read_bytes()[: max(1, path.stat().st_size // 3)])
    again = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True)
    assert again.returncode == 0, again.stderr
    assert "could not be read" in again.stderr
    assert again.stdout.split()[-1] == warm.stdout.split()[-1]
    clean = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True)
    assert clean.returncode == 0 and "could not be read" not in clean.stderr
