"""The compiled engine on a shared installation: a cache that cannot be written (read-only, or no
folder at all), no home directory, a cache filled once and loaded by others, and two processes
compiling a model's kernels into it at once.

The suite runs as root, for whom permissions do not stop a write; a folder that cannot be created
(its parent is a file) stands for one that cannot be written, and a read-only cache shared by an
administrator is loaded by a process told it may not write there (the child's first lines)."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from crankgen.engine import cache as compile_cache

RUN = ("import crankgen; r = crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20, "
       "revolutions=1, model='paper', approach='C'); print('ok', repr(r.v_mid[-1]))")
READ_ONLY_CHILD = """
import sys
import crankgen.engine.cache as cc
cc._writable = lambda folder: False          # this process may not write the shared cache
cc.CACHE, cc.READ_ONLY = cc.cache_folder()
assert cc.READ_ONLY, cc.CACHE
""" + RUN.replace("; ", "\n")


def _env(**changes):
    env = {k: v for k, v in os.environ.items() if k not in ("CRANKGEN_CACHE_DIR", "HOME", "XDG_CACHE_HOME")}
    env.update({k: v for k, v in changes.items() if v is not None})
    return env


def _run(code, env, timeout=900):
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          timeout=timeout)


def test_the_cache_folder_needs_no_home(monkeypatch, tmp_path):
    """Without HOME the shared folder is used when writable, read-only when it is not; a user cache
    is used only where a home (or XDG_CACHE_HOME) exists."""
    monkeypatch.delenv("CRANKGEN_CACHE_DIR", raising=False)
    monkeypatch.delenv("HOME", raising=False)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.setattr(Path, "home", classmethod(lambda cls: (_ for _ in ()).throw(RuntimeError("no home"))))
    # an installation of its own: the real package's cache may already hold a compiled engine
    monkeypatch.setattr(compile_cache, "_PACKAGE", tmp_path / "site-packages" / "crankgen")
    shared = compile_cache._PACKAGE / "__pycache__" / f"numba-{compile_cache.CODE_HASH}"
    monkeypatch.setattr(compile_cache, "_writable", lambda folder: False)
    assert compile_cache.cache_folder() == (shared, True)
    user = tmp_path / "xdg"
    monkeypatch.setenv("XDG_CACHE_HOME", str(user))
    monkeypatch.setattr(compile_cache, "_writable", lambda folder: str(folder).startswith(str(user)))
    assert compile_cache.cache_folder() == (user / "crankgen" / shared.name, False)
    # once an administrator compiled the engine into the shared folder, it is loaded read-only
    marker = shared / "kernels" / "entry-march.ok"
    marker.parent.mkdir(parents=True)
    marker.touch()
    assert compile_cache.cache_folder() == (shared, True)


@pytest.fixture(scope="module")
def shared_cache(tmp_path_factory):
    """A cache an administrator filled, and what the run printed: the run on this installation's
    own cache (compiled at most once for the whole suite), copied into a folder of this module's
    (the two tests below compile from nothing themselves: one cold compilation less)."""
    folder = tmp_path_factory.mktemp("admin")
    admin = _run(RUN, _env())
    assert admin.returncode == 0, admin.stderr
    shutil.copytree(compile_cache.CACHE, folder / "shared" / compile_cache.CACHE.name)
    return folder / "shared", admin.stdout


@pytest.mark.slow
def test_an_unwritable_cache_compiles_in_memory_and_the_run_succeeds(tmp_path, shared_cache):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("a file where the cache folder would go")
    out = _run(RUN, _env(CRANKGEN_CACHE_DIR=str(blocker / "cache")))
    assert out.returncode == 0, out.stderr
    assert "which is a file, not a folder: compiling in memory" in out.stderr and "Traceback" not in out.stderr
    assert out.stdout == shared_cache[1]


@pytest.mark.slow
def test_a_shared_cache_is_loaded_read_only(shared_cache):
    """A user who may not write the administrator's cache loads the compiled code: no
    compilation, nothing written, the same numbers."""
    cache, expected = shared_cache
    before = {p: p.stat().st_mtime_ns for p in cache.rglob("*") if p.is_file()}
    user = _run(READ_ONLY_CHILD, _env(CRANKGEN_CACHE_DIR=str(cache)))
    assert user.returncode == 0, user.stderr
    assert "compiling" not in user.stderr and user.stdout == expected
    assert {p: p.stat().st_mtime_ns for p in cache.rglob("*") if p.is_file()} == before


@pytest.mark.slow
def test_a_cache_without_the_models_kernels_is_filled_by_two_processes_sharing_the_work(tmp_path, shared_cache):
    """Two runs started together on a cache that holds the compiled engine but none of the model's
    kernels (what a second model finds): both succeed with the same numbers as before, each kernel
    is compiled once in all (per-item locks), and the cache is whole afterwards (a third run
    compiles nothing).  The engine's entry points go through the same per-item lock as the
    kernels (engine/build.py); the test above compiles the engine from nothing, once."""
    cache = tmp_path / "cache"
    shutil.copytree(shared_cache[0], cache)
    folder = cache / compile_cache.CACHE.name
    removed = [p for p in folder.rglob("*") if p.is_file() and (
        p.parent.name == "generated" or p.name.startswith("kernel-"))]       # the kernels' files and markers
    for path in removed:
        path.unlink()
    assert any(p.parent.name == "generated" for p in removed) and (folder / "kernels" / "entry-march.ok").exists()
    env = _env(CRANKGEN_CACHE_DIR=str(cache), CRANKGEN_BUILD_LOG=str(tmp_path / "log"))
    procs = [subprocess.Popen([sys.executable, "-c", RUN], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) for _ in range(2)]
    outs = [p.communicate(timeout=900) for p in procs]
    assert all(p.returncode == 0 for p in procs), [o[1] for o in outs]
    assert outs[0][0] == outs[1][0] == shared_cache[1]
    compiled = (tmp_path / "log").read_text().split()
    assert len(compiled) == len(set(compiled))                      # nothing compiled twice
    assert len(compiled) > 2 and all(item.startswith("kernel:") for item in compiled), compiled
    third = _run(RUN, env)
    assert third.returncode == 0 and "compiling" not in third.stderr and third.stdout == shared_cache[1]
