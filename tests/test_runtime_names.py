"""Nothing in the runtime names a parameter, a guide or a motion: they are declared once
(derive/declaration.py) and reach the runtime through the generated schema.

A scan of the runtime's source (src/crankgen, every module but the paper's study, experiments/,
and the symbolic audit's report, audit/, which are studies of given parameter values like the
examples) for string constants equal to the name of a parameter that enters the equations (one
with slots in the parameter vector: a, eps, ms, mu, gravity, offset, omega, ...), the name of a
guide or motion, or the class name of its record.  The kind words "guide" and "motion" (the
records' vocabulary) and the run's own settings (n_elements, steps_per_rev, integrator) are not
names of this kind.  Neither is a file-mode string of open() ("a": append) or a format
specification (":d"), nor the homonyms listed in HOMONYMS (a word of the runtime's own that a
parameter shares).
"""

import ast
from pathlib import Path

import crankgen
from crankgen.declaration import schema

ROOT = Path(crankgen.__file__).resolve().parent
STUDIES = ("experiments", "audit")
# (module, word): what the word means there
HOMONYMS = {("analyses/bifurcation/diagram.py", "branch"): "a branch of periodic orbits of a continuation (a CSV column), "
                                                   "not the four-bar's closure",
            ("declaration/parameters.py", "a"): "the SI crank length in metres, a field of SIMechanism (its a* = a / L is "
                                    "the parameter)",
            ("plots/animation.py", "branch"): "a branch of periodic orbits of a continuation",
            ("analyses/bifurcation/diagram_files.py", "branch"): "a branch of periodic orbits of a continuation (a "
                                                        "CSV column and JSON key), not the four-bar's closure",
            ("analyses/campbell.py", "order"): "a crank order (k Omega) of a Campbell diagram (a CSV column)",
            ("declaration/sections.py", "circle"): "a circular cross-section of the rod"}


def forbidden():
    names = {p.name for p in schema.PARAMETERS.values() if p.slots}
    names |= set(schema.GUIDES) | set(schema.MOTIONS)
    names |= {g.title for g in schema.GUIDES.values()} | {m.title for m in schema.MOTIONS.values()}
    return names


def _not_names(tree):
    """ids of the string constants that are no names: the mode argument of an open() call, the
    parts of a format specification."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "id", getattr(node.func, "attr", None)) == "open":
            args = node.args[1:2] + [k.value for k in node.keywords if k.arg == "mode"]
            out.update(id(a) for a in args if isinstance(a, ast.Constant))
        if isinstance(node, ast.FormattedValue) and node.format_spec is not None:
            out.update(id(n) for n in ast.walk(node.format_spec) if isinstance(n, ast.Constant))
    return out


def named(source, names, module=""):
    """[(line, text)] of the string constants of `source` equal to one of `names`."""
    tree = ast.parse(source)
    skip = _not_names(tree)
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in names
            and id(node) not in skip and (module, node.value) not in HOMONYMS]


def runtime_modules():
    return sorted(p for p in ROOT.rglob("*.py")
                  if not any(part in STUDIES for part in p.relative_to(ROOT).parts))


def test_no_runtime_module_names_a_parameter_a_guide_or_a_motion():
    names = forbidden()
    assert {"eps", "omega", "offset", "line", "circle", "constant", "Circle"} <= names
    found = {str(p.relative_to(ROOT)): hits for p in runtime_modules()
             if (hits := named(p.read_text(), names, str(p.relative_to(ROOT))))}
    assert found == {}, f"the runtime names parameters, guides or motions: {found}"


def test_the_scan_finds_a_name():
    """The scan above can fail: it sees a parameter, a guide and a record class by string."""
    names = forbidden()
    source = ('x = case["eps"]\nif guide == "circle":\n    cls = getattr(m, "Circle")\nopen(f, "a")\n'
              'print(f"{n:d}")\n')
    assert [text for _, text in named(source, names)] == ["eps", "circle", "Circle"]
    assert len(runtime_modules()) > 40
