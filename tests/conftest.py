"""The order in which the two pytest-xdist workers take the test files (pyproject.toml: `--dist
loadfile --no-loadscope-reorder`).

xdist's own order (files with the most tests first) leaves to the end the files whose few tests
are long (a derivation, a compilation from nothing, a Sphinx build): one worker then runs such a
file alone while the other has finished.  The files below go first, longest first (their time on
two cores from a cold compiled-code cache); every other file follows, the one with the most tests
first, as xdist would have it.

tests/test_generated.py opens the list: it regenerates generated/ with SymPy in a child process
and needs no compiled code, so it runs while the other worker compiles the engine (which every
other long file waits for on a cold cache)."""

FIRST = ("test_generated.py", "test_engine.py", "test_durability_battery4.py", "test_shared_install.py",
         "test_readme.py", "test_reproduce.py", "test_docs.py", "test_audit.py", "test_compile_cache.py",
         "test_chart.py", "test_reproduce_manifest.py", "test_figures.py", "test_independent_model.py")


def pytest_collection_modifyitems(items):
    files = {}
    for item in items:
        files.setdefault(item.path.name, []).append(item)
    rank = {name: i for i, name in enumerate(FIRST)}
    order = sorted(files, key=lambda name: (rank.get(name, len(FIRST)), -len(files[name])))
    items[:] = [item for name in order for item in files[name]]
