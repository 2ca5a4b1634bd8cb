"""Sphinx extension of crankgen's documentation.

- ``{crankgen-run}``: a block of Python run when the docs are built. The page shows the code, what
  it printed and every figure it drew; the blocks of one page share their names (a tutorial is one
  session) and run in a temporary folder. An exception is a build warning (an error under -W).
- Generated pages: at the start of a build, ``reference/_generated/cli.md`` (every command of
  ``crankgen``, from the argparse parser) and ``reference/_generated/columns.md`` (every CSV column
  with its unit and meaning, from the declaration) are written from the installed package.
- The API check: at the end of a build, every public name of ``crankgen`` (``crankgen.__all__``)
  must be documented in the reference; a missing one is a build warning.
- Docstrings: crankgen's docstrings are plain prose (equations such as ``v* = v/r``,
  ``|v| / L``); their reStructuredText specials are escaped before autodoc renders them, and
  backquoted spans are rendered as code.
"""

import argparse
import contextlib
import io
import os
import re
import shutil
import tempfile
import traceback
import warnings
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

GENERATED = "_generated"          # folders of generated sources and images (not committed)


# ---- {crankgen-run} ---------------------------------------------------------------------------

class RunBlock(SphinxDirective):
    """Run the block's Python; show the code, its printed output and its figures."""

    has_content = True
    option_spec = {"hide-code": directives.flag, "hide-output": directives.flag,
                   "caption": directives.unchanged, "figure-width": directives.unchanged}

    def run(self):
        import matplotlib.pyplot as plt

        code = "\n".join(self.content)
        env = self.env
        sessions = env.app.crankgen_sessions
        session = sessions.get(env.docname)
        if session is None:
            folder = Path(tempfile.mkdtemp(prefix="crankgen-docs-"))
            session = sessions[env.docname] = {"namespace": {"__name__": "__docs__"}, "folder": folder, "count": 0}
        session["count"] += 1
        out = []
        if "hide-code" not in self.options:
            block = nodes.literal_block(code, code)
            block["language"] = "python"
            out.append(block)
        plt.close("all")
        buffer = io.StringIO()
        cwd = os.getcwd()
        caught = []
        try:
            os.chdir(session["folder"])
            with contextlib.redirect_stdout(buffer), warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("default")
                exec(compile(code, f"{env.docname} block {session['count']}", "exec"), session["namespace"])
        except Exception:
            logger.warning("crankgen-run block %d of %s failed:\n%s", session["count"], env.docname,
                           traceback.format_exc(), location=(env.docname, self.lineno))
        finally:
            os.chdir(cwd)
        for w in caught:                     # a warning the user would see, shown as such
            print(f"{w.category.__name__}: {w.message}", file=buffer)
        printed = buffer.getvalue().rstrip()
        if printed and "hide-output" not in self.options:
            shown = nodes.literal_block(printed, printed)
            shown["language"] = "text"
            out.append(nodes.container("", shown, classes=["crankgen-output"]))
        images = Path(env.srcdir) / GENERATED / "run"
        images.mkdir(parents=True, exist_ok=True)
        for k, number in enumerate(plt.get_fignums()):
            name = f"{env.docname.replace('/', '-')}-{session['count']}-{k}.png"
            plt.figure(number).savefig(images / name, dpi=100)
            uri = f"/{GENERATED}/run/{name}"
            image = nodes.image(uri=uri, alt=self.options.get("caption", f"figure of {env.docname}"))
            if "figure-width" in self.options:
                image["width"] = self.options["figure-width"]
            figure = nodes.figure("", image)
            if "caption" in self.options:
                figure += nodes.caption(self.options["caption"], self.options["caption"])
            out.append(figure)
        plt.close("all")
        return out


def _end_sessions(app, env):
    for session in app.crankgen_sessions.values():
        shutil.rmtree(session["folder"], ignore_errors=True)
    app.crankgen_sessions.clear()


def _forget_session(app, env, docname):
    session = app.crankgen_sessions.pop(docname, None)
    if session:
        shutil.rmtree(session["folder"], ignore_errors=True)


# ---- generated reference pages ------------------------------------------------------------------

def _md_cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ").replace("*", "\\*").replace("_", "\\_") \
        .replace("<", "&lt;").replace(">", "&gt;")


def _code_cell(text):
    text = str(text).replace("|", "\\|")
    return f"`{text}`" if text else ""


def cli_markdown():
    """Every command of `crankgen`, its description and every option, from the parser."""
    from crankgen.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    lines = ["<!-- generated by docs/_ext/crankgen_docs.py from crankgen.cli.build_parser(); do not edit -->", ""]
    lines += [_md_cell(parser.description or ""), ""]
    lines += ["| command | what it does |", "|---|---|"]
    helps = {a.dest: a.help for a in sub._choices_actions}
    for name in sub.choices:
        lines.append(f"| [`crankgen {name}`](#crankgen-{name}) | {_md_cell(helps.get(name, ''))} |")
    lines.append("")
    for name, command in sub.choices.items():
        lines += [f"(crankgen-{name})=", f"## crankgen {name}", ""]
        usage = command.format_usage().replace("usage: ", "").strip()
        lines += ["```text", usage, "```", ""]
        if command.description:
            lines += [_md_cell(command.description), ""]
        for group in command._action_groups:
            actions = [a for a in group._group_actions if a.help != argparse.SUPPRESS]
            if not actions:
                continue
            lines += [f"**{_md_cell(group.title)}**", "", "| option | value | default | meaning |", "|---|---|---|---|"]
            for a in actions:
                flags = ", ".join(a.option_strings) or a.dest
                if a.choices:
                    value = "{" + ",".join(str(c) for c in a.choices) + "}"
                elif a.nargs == 0:
                    value = ""
                else:
                    value = a.metavar or a.dest.upper()
                    value = value if isinstance(value, str) else " ".join(value)
                default = "" if a.default in (None, argparse.SUPPRESS, False) or a.nargs == 0 else a.default
                lines.append(f"| {_code_cell(flags)} | {_code_cell(value)} | {_code_cell(default)} | "
                             f"{_md_cell(a.help or '')} |")
            lines.append("")
        if command.epilog:
            lines += [_md_cell(command.epilog), ""]
    return "\n".join(lines) + "\n"


def columns_markdown():
    """Every CSV column crankgen writes, with its unit (crankgen's and SI) and meaning, from the
    declaration: the per-step tables (simulation.csv, orbit.csv), the rows of steady.csv and
    sweep.csv, and the quantities of a continuation's branches.csv."""
    from crankgen.declaration import schema
    from crankgen.analyses.bifurcation import quantities as q
    from crankgen.results.exports import column
    from crankgen.results.steady_row import RESULTS, MOTOR_RESULTS, describe
    from crankgen.declaration.units import Scales

    def si(units):
        try:
            return Scales.si_name(units)
        except Exception:                    # a unit with no SI name: say the declared one
            return units

    lines = ["<!-- generated by docs/_ext/crankgen_docs.py from the declaration; do not edit -->", ""]
    lines += ["(columns-per-step)=", "## Per-step tables: simulation.csv, orbit.csv", "",
              "One row per time step. Each column is the quantity's name and its unit: crankgen's "
              "units (the default) or SI (`--si`, `result.si.to_csv`). The time and the crank angle "
              "come first (`t_per_omega_b, theta_deg`; in SI `t_s, theta_rad`), then every declared "
              "output the run gives, in this order (a guide's own outputs only on that guide), the "
              "field outputs at mid-span, and the range of the theory.", "",
              "| output | column (crankgen's units) | column (SI) | guides | meaning |", "|---|---|---|---|---|"]
    for name, o in schema.OUTPUTS.items():
        if o.kind not in ("step", "reduction", "field"):
            continue
        if o.kind == "field":
            own, si_col = f"{name}_at_0.5_" + column("x", o.units)[2:], f"{name}_at_<x>m_" + column("x", o.units, si=True)[2:]
        else:
            own, si_col = column(name, o.units), column(name, o.units, si=True)
        lines.append(f"| `{name}` ({o.kind}) | {_code_cell(own)} | {_code_cell(si_col)} | "
                     f"{', '.join(o.guides)} | {_md_cell(o.doc)} |")
    lines += ["", "The range of the theory per step: `deflection_over_L`, `axial_strain`, `beyond_theory` "
              "(an exact-model run also `fibre_strain`, `section_rotation_deg` and `range_note`), then "
              "`status`.", ""]

    lines += ["(columns-row)=", "## A steady state's row: steady.csv, sweep.csv", "",
              "One row per case (`SteadyState.row()`, `SweepTable`). In crankgen's units the columns keep "
              "the parameters' names so that a row reads back as a `Case`; `crankgen sweep` writes the "
              "same table as `sweep_columns.csv` beside its `sweep.csv`.", "",
              "| column | units | SI | meaning |", "|---|---|---|---|"]
    columns = list(schema.PARAMETERS)
    columns = [c for c in columns if c != "gravity"] + ["gravity_x", "gravity_y"]
    columns += ["model"] + list(schema.OPTIONS) + ["groups_off"]
    columns += [r[0] for r in RESULTS[:8]]
    loads = [n for n, o in schema.OUTPUTS.items() if o.kind == "step" and not o.engine
             and Scales.si_name(o.units) in ("N", "N m")]
    columns += ["peak_" + n for n in loads]
    columns += [r[0] for r in MOTOR_RESULTS] + [r[0] for r in RESULTS[8:]]
    si_units = {d["column"]: d["units"] for d in describe(columns, si=True)}
    for d in describe(columns):
        lines.append(f"| `{d['column']}` | {_code_cell(d['units'])} | {_code_cell(si_units[d['column']])} | "
                     f"{_md_cell(d['meaning'])} |")
    lines.append("")

    lines += ["(columns-branches)=", "## A continuation's branches: branches.csv", "",
              "Beside each point's parameter, amplitude, stability and multipliers, the quantities of its "
              "orbit (`Branch.quantities`, `crankgen continue`); with `--si` each column is named with its "
              "SI unit. A motor-driven crank's points add the motor's quantities.", "",
              "| column | units | SI | meaning |", "|---|---|---|---|"]
    meanings = _branch_meanings(q.__doc__)
    own, in_si = q.motor_units(section=True), q.motor_units(section=True, si=True)
    motor = set(q.MOTOR_QUANTITIES)
    for name, u in own.items():
        label = f"`{name}`" + (" (motor)" if name in motor else "")
        lines.append(f"| {label} | {_code_cell(u)} | {_code_cell(si(in_si[name].split(' (')[0]))} | {_md_cell(meanings.get(name, ''))} |")
    lines.append("")
    return "\n".join(lines) + "\n"


def _branch_meanings(doc):
    """{quantity: meaning} from the bullet list of crankgen.analyses.bifurcation.quantities' docstring."""
    out = {}
    items = re.split(r"\n- ", doc)
    for item in items[1:]:
        text = " ".join(item.split("\n\n")[0].split())
        head, _, meaning = text.partition(": ")
        if len(head.split()) > 6:           # no "name: meaning" item: the item is the meaning
            meaning = text
        meaning = meaning.rstrip(";")
        for name in re.findall(r"\b(?:peak|mean|rms|min|max|revolution)_\w+", head.split(" = ")[0] + " " + head):
            out.setdefault(name, meaning or text)
    return out


def _write_generated(app):
    folder = Path(app.srcdir) / "reference" / GENERATED
    folder.mkdir(parents=True, exist_ok=True)
    for name, make in (("cli.md", cli_markdown), ("columns.md", columns_markdown)):
        text = make()
        path = folder / name
        if not path.exists() or path.read_text(encoding="utf-8") != text:   # unchanged: no rebuild
            path.write_text(text, encoding="utf-8")


# ---- the API check ------------------------------------------------------------------------------

def _check_api(app, exception):
    if exception is not None or app.builder.name not in ("html", "dirhtml", "singlehtml"):
        return
    import crankgen

    documented = set(app.env.get_domain("py").objects)
    modules = set(app.env.domaindata["py"].get("modules", {}))
    for name in crankgen.__all__:
        full = f"crankgen.{name}"
        if full not in documented and full not in modules:
            logger.warning("the API reference does not document %s (public: crankgen.__all__)", full,
                           type="crankgen", subtype="api")


# ---- docstrings ---------------------------------------------------------------------------------

_SPAN = re.compile(r"(`[^`\n]+`)")


def _escape(text):
    """A prose line made safe for reStructuredText: * | _ and \\ as themselves."""
    text = text.replace("\\", "\\\\")
    text = re.sub(r"([*|])", r"\\\1", text)
    text = re.sub(r"_(?=\W|$)", r"\\_", text)          # a trailing underscore is a link otherwise
    text = re.sub(r"(?<=\W)_|^_", r"\\_", text)
    return text


def _prose_docstring(app, what, name, obj, options, lines):
    out = []
    for line in lines:
        parts = _SPAN.split(line)
        out.append("".join(f"``{p[1:-1]}``" if p.startswith("`") and p.endswith("`") else _escape(p)
                           for p in parts))
    # a list item's continuation lines are indented to the item's text; an indented line after a
    # paragraph line is a continuation of it (not a block quote)
    fixed = []
    for line in out:
        if fixed and line.strip() and line[:1] == " " and fixed[-1].strip() and not fixed[-1].lstrip().startswith("- "):
            indent = len(fixed[-1]) - len(fixed[-1].lstrip())
            line = " " * indent + line.lstrip()
        elif fixed and line.strip() and line[:1] == " " and fixed[-1].lstrip().startswith("- "):
            indent = len(fixed[-1]) - len(fixed[-1].lstrip()) + 2
            line = " " * indent + line.lstrip()
        fixed.append(line)
    lines[:] = fixed


def setup(app):
    app.crankgen_sessions = {}
    app.add_directive("crankgen-run", RunBlock)
    app.connect("builder-inited", _write_generated)
    app.connect("env-purge-doc", _forget_session)
    app.connect("env-updated", _end_sessions)
    app.connect("autodoc-process-docstring", _prose_docstring)
    app.connect("build-finished", _check_api)
    return {"version": "1", "parallel_read_safe": False, "parallel_write_safe": True}
