"""The README's and the documentation's examples run as written: every ```python block of README.md
and of the Markdown pages of docs/ (in a temporary folder, with the
continuation, the Poincare sweep, the Campbell diagram, the two-parameter curves and the animations
made small: they take
minutes at the README's sizes), every
`crankgen ...` command line of the ```bash blocks parses, and the test command is the one .ci/run
runs."""

import re
import shlex
import textwrap
from pathlib import Path

import numpy as np
import pytest

import crankgen

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
# the pages of the documentation (what a build generates is not a page of the repository); the
# blocks a build runs itself ({crankgen-run}) are checked by tests/test_docs.py
PAGES = [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").rglob("*.md")
                                       if not {"_build", "_generated", "gallery"} & set(p.relative_to(ROOT / "docs").parts))


def _blocks(language):
    """[(where, code)] of every ```language block of the pages."""
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for k, code in enumerate(re.findall(rf"```{language}\n(.*?)```", text, flags=re.S)):
            out.append((f"{page.relative_to(ROOT)} {language} block {k + 1}", code))
    return out


PYTHON_BLOCKS = _blocks("python")
BASH_BLOCKS = [code for _, code in _blocks("bash")]


def _small(real, **overrides):
    """real(...) with the sizes of a test (the call as written otherwise)."""
    def call(*args, **kwargs):
        kwargs.update(overrides)
        if "values" in kwargs:
            kwargs["values"] = np.asarray(kwargs["values"])[::20]
        return real(*args, **kwargs)
    return call


def test_the_readme_and_the_docs_have_python_examples():
    assert re.search(r"```python\n", README)
    assert len(PYTHON_BLOCKS) >= 15 and any("continuation" in code for _, code in PYTHON_BLOCKS)


@pytest.mark.parametrize("k", range(len(PYTHON_BLOCKS)), ids=lambda k: PYTHON_BLOCKS[k][0])
def test_every_python_block_runs_as_written(k, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(crankgen, "continuation", _small(crankgen.continuation, n_elements=2,
                                                         steps_per_rev=30, max_period=2))
    monkeypatch.setattr(crankgen, "poincare", _small(crankgen.poincare, n_elements=2, steps_per_rev=30,
                                                     transient=3, samples=4))
    monkeypatch.setattr(crankgen, "campbell", _small(crankgen.campbell, n_elements=4, angles=8))
    monkeypatch.setattr(crankgen, "follow", _small(crankgen.follow, max_points=8))
    from crankgen.plots import animation
    monkeypatch.setattr(animation, "MAX_FRAMES", 6)          # a few frames of every animation
    where, code = PYTHON_BLOCKS[k]
    code = textwrap.dedent(code)                        # a block inside a list item is indented
    exec(compile(code, where, "exec"), {"__name__": "readme"})
    for name in re.findall(r"""(?:to_csv|plot)\("([^"]+)""", code):      # what it says it writes
        assert (tmp_path / name).exists(), name


def _command_lines():
    for block in BASH_BLOCKS:
        for line in block.splitlines():
            for part in line.split("&&"):
                words = shlex.split(part, comments=True)
                if words and words[0].endswith("crankgen"):
                    yield words[1:]


@pytest.mark.parametrize("argv", list(_command_lines()), ids=lambda a: " ".join(a)[:60])
def test_every_command_line_parses(argv):
    from crankgen.cli import build_parser
    args, extra = build_parser().parse_known_args(argv)
    assert extra == [] and callable(args.func)


def test_the_test_command_is_the_one_ci_runs():
    command = "python3 -m venv .venv && .venv/bin/pip install -e '.[test]' && .venv/bin/python -m pytest -q"
    assert command in README
    assert command in (ROOT / ".ci" / "run").read_text()
