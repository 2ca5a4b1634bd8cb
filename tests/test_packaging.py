"""The package list in pyproject.toml ships every package of the source tree.

setuptools installs only the packages it is told of; a subpackage missing from
``[tool.setuptools] packages`` works in an editable install (the tests' own) and
breaks a plain ``pip install .`` at import time. This test reads the list and
the source tree and compares them.
"""
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _configured():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    return set(config["packages"]), config["package-dir"]


def _source_dir(package, package_dir):
    """The folder setuptools reads `package` from (the longest mapped prefix)."""
    parts = package.split(".")
    for cut in range(len(parts), 0, -1):
        prefix = ".".join(parts[:cut])
        if prefix in package_dir:
            return ROOT / package_dir[prefix] / Path(*parts[cut:])
    return ROOT / Path(*parts)


def test_every_source_package_is_shipped():
    packages, package_dir = _configured()
    on_disk = set()
    for package, folder in package_dir.items():
        base = ROOT / folder
        for init in base.rglob("__init__.py"):
            rel = init.parent.relative_to(base)
            on_disk.add(".".join((package, *rel.parts)))
    missing = sorted(on_disk - packages)
    assert not missing, f"packages on disk but not in pyproject.toml's [tool.setuptools] packages: {missing}"


def test_every_shipped_package_exists():
    packages, package_dir = _configured()
    absent = sorted(p for p in packages if not (_source_dir(p, package_dir) / "__init__.py").is_file())
    assert not absent, f"pyproject.toml lists packages with no __init__.py: {absent}"
