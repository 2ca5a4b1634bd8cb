"""The compiled engine's cache: keyed by the code it compiles, and repaired when unreadable."""

import os
import shutil
import subprocess
import sys

import pytest

from crankgen.engine import cache as compile_cache


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


# (function, file, damage) of every kind a warm run loads: kernels (generated/) and the engine's
# entry points and the no-op kernels of absent families (engine/); data (.nbc) and index (.nbi)
# files; garbage, truncated and empty
DAMAGE = [("elements.inertia_lagrange_lanes", ".nbc", lambda b: b"\x00garbage" * 40),
          ("elements.elastic_lagrange_A_averaged_lanes", ".nbi", lambda b: b[: len(b) // 3]),
          ("elements.slider_inertia_lagrange_element", ".nbc", lambda b: b""),
          ("kinematics.motion_constant_into", ".nbi", lambda b: b""),
          ("batch._march_cases", ".nbc", lambda b: b[: len(b) // 2]),
          ("batch._initial_accelerations", ".nbc", lambda b: b"\x80\x05garbage" * 9),
          ("kernels.noop_lanes", ".nbi", lambda b: b"\x80\x05garbage")]


def _damage(folder):
    """Damage the files of DAMAGE in a copy of a warm cache; returns their functions' file names."""
    damaged = []
    for function, suffix, how in DAMAGE:
        paths = [p for p in folder.rglob(f"{function}-*{suffix}")]
        assert paths, f"the warm run left no {suffix} file of {function}"
        paths[0].write_bytes(how(paths[0].read_bytes()))
        damaged.append(paths[0].name.split(".py")[0])
    return damaged


@pytest.mark.slow
def test_every_kind_of_damaged_cache_file_is_removed_with_a_warning_and_recompiled(tmp_path):
    """A copy of a real warm cache with a damaged file of every kind (kernels and engine; garbage,
    truncated and empty; data and index files): the run warns once per damaged function, removes
    its files, recompiles it and gives the undamaged run's numbers; the next run is clean.  (On
    main only the engine's files were repaired, and a damaged kernel failed every later run.)"""
    env = dict(os.environ, CRANKGEN_CACHE_DIR=str(tmp_path), CRANKGEN_BUILD_PROCESSES="1")
    subprocess.run([sys.executable, "-c", RUN], capture_output=True, check=True)      # warm cache
    shutil.copytree(compile_cache.CACHE, tmp_path / compile_cache.CACHE.name)         # its copy
    warm = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True)
    assert warm.returncode == 0 and "compiling" not in warm.stderr, warm.stderr
    damaged = _damage(tmp_path / compile_cache.CACHE.name)
    again = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True)
    assert again.returncode == 0, again.stderr
    warnings = [line for line in again.stderr.splitlines() if "damaged compiled code" in line]
    for name in damaged:
        assert any(name in line for line in warnings), (name, again.stderr)
    assert len(warnings) == len(damaged), again.stderr
    assert again.stdout.split()[-1] == warm.stdout.split()[-1]
    clean = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True)
    assert clean.returncode == 0 and "damaged" not in clean.stderr, clean.stderr
    assert clean.stdout.split()[-1] == warm.stdout.split()[-1]


def test_a_numba_upgrade_gets_a_cache_folder_of_its_own(monkeypatch):
    """An in-place numba upgrade changes CODE_HASH, so the new compilation is a first run with
    its progress lines (on main it reused the folder and its markers and recompiled silently)."""
    from importlib import metadata
    base = compile_cache._code_hash()
    real = metadata.version
    monkeypatch.setattr(metadata, "version", lambda name: "99.0" if name == "numba" else real(name))
    assert compile_cache._code_hash() != base


@pytest.mark.parametrize("kind", ["file", "dangling link", "under a file"])
def test_an_unusable_cache_folder_is_reported_as_what_it_is(tmp_path, kind):
    """CRANKGEN_CACHE_DIR that is a file, a dangling symbolic link or lies under a file: the note
    says so (main called each of them "read-only")."""
    target = tmp_path / "cache"
    if kind == "file":
        target.write_text("not a folder")
        expected = "a file, not a folder"
    elif kind == "dangling link":
        target.symlink_to(tmp_path / "nowhere")
        expected = "dangling symbolic link"
    else:
        (tmp_path / "file").write_text("x")
        target = tmp_path / "file" / "cache"
        expected = "a file, not a folder"
    code = ("import crankgen.engine.cache as c; print(c.READ_ONLY); print(c.READ_ONLY_NOTE)")
    out = subprocess.run([sys.executable, "-c", code], env=dict(os.environ, CRANKGEN_CACHE_DIR=str(target)),
                         capture_output=True, text=True, check=True).stdout
    assert out.splitlines()[0] == "True"
    assert expected in out and "is read-only" not in out, out
