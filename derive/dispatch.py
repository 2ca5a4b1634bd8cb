"""Stage 6: the generated model table and element dispatch (generated/dispatch.py).

From the declaration (derive/model.py) and the element kernels (derive/kernels.py) this emits:
- the table the runtime reads: OPTIONS (choices, defaults, docs), PARAMETERS, COEFFICIENTS,
  FAMILIES with each variant's selecting option values, the switchable term groups each variant
  carries, OUTPUTS and the field kernel of each output by option values;
- `coefficients(...)`: the coefficient vector of the element kernels from the mechanism's
  parameters and the options (derive/model.COEFFICIENTS, printed as code);
- dispatch functions over the families of a model, `m[f]` being the index of family f's variant
  (-1: family absent): `rod_add`, `rod_residual_add`, `rod_newmark_add` for the families acting on
  every element and `end_add`, `end_residual_add`, `end_newmark_add` for those acting on the last
  element (the slider).  They are plain Python calling the element kernels by name; the compiled
  engine binds the same names to compiled kernels.  The runtime never names a family or a kernel.
"""

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from . import kernels as kn
from . import model
from . import symbols as s


def _printer():
    return PythonCodePrinter({"fully_qualified_modules": True, "inline": True})


def _with_printed_stiffness():
    return {k.name for k in kn.element_kernels() if any(o.name == "K_printed" for o in k.outputs)}


def _family_dispatch(part, variant_suffix, extra_args, out_args, doc, printed=False):
    """Source of one dispatch function over the families of `part`."""
    families = [(k, f) for k, f in enumerate(model.FAMILIES) if f.part == part]
    printed_arg = ["printed"] if printed else []
    args = ["m"] + printed_arg + ["q", "qd", "qdd", "geo", "coef", "kin"] + list(extra_args) + list(out_args)
    call_args = ", ".join(["q", "qd", "qdd", "geo", "coef", "kin"] + list(extra_args) + list(out_args))
    lines = [f"def {part}_{variant_suffix.strip('_') or 'add'}({', '.join(args)}):", f'    """{doc}"""']
    for k, family in families:
        lines.append(f"    f = m[{k}]                    # {family.name}")
        for j, variant in enumerate(family.variants):
            name = kn.element_kernel_name(family, variant)
            keyword = "if" if j == 0 else "elif"
            lines.append(f"    {keyword} f == {j}:")
            has_printed = name in _with_printed_stiffness()
            if printed and has_printed:
                lines.append("        if printed:")
                lines.append(f"            {name}_printed_add({call_args})")
                lines.append("        else:")
                lines.append(f"            {name}{variant_suffix}({call_args})")
            else:
                lines.append(f"        {name}{variant_suffix}({call_args})")
    return "\n".join(lines) + "\n"


def _coefficients_source():
    printer = _printer()
    args = ["eps", "ms", "mu", "gX", "gY", "with_rotary_inertia"] + [
        model.switched_off[g].name for g in s.SWITCHABLE_GROUPS]
    lines = [f"def coefficients({', '.join(args)}):",
             '    """The coefficient vector of the element kernels (COEFFICIENTS order, crankgen\'s units:',
             "    rho A = 1, E I = 1/pi^4, E A = 1/(pi^4 eps^2), rho I = eps^2 or 0 without rotary inertia,",
             '    term weights 1, or 0 for a switched-off group)."""',
             "    return ("]
    for sym, expr in model.COEFFICIENTS.items():
        lines.append(f"        float({printer.doprint(sp.sympify(expr))}),    # {sym.name}")
    lines.append("    )")
    return "\n".join(lines) + "\n"


def _table_source():
    out = []
    out.append("OPTIONS = (")
    for o in model.OPTIONS:
        out.append(f"    ({o.name!r}, {o.choices!r}, {o.default!r},\n     {o.doc!r}),")
    out.append(")")
    out.append("PARAMETERS = (")
    for p in model.PARAMETERS:
        out.append(f"    ({p.name!r}, {p.doc!r}, {p.default!r}, {p.low!r}, {p.high!r}),")
    out.append(")")
    out.append(f"COEFFICIENTS = {tuple(sym.name for sym in s.COEFFICIENTS)!r}")
    out.append(f"SWITCHABLE_GROUPS = {s.SWITCHABLE_GROUPS!r}")
    out.append("# family name, part ('rod': every element; 'end': the slider on the last element), doc,")
    out.append("# energy kind of its energy kernels, the coefficients whose vanishing leaves it out, variants:")
    out.append("# (name, element kernel, selecting option values, switchable groups it carries, energy kernel)")
    out.append("FAMILIES = (")
    for f in model.FAMILIES:
        out.append(f"    ({f.name!r}, {f.part!r}, {f.doc!r}, {f.energy_kind!r}, {f.vanishes_with!r}, (")
        for v in f.variants:
            when = dict(sorted(v.when.items()))
            out.append(f"        ({v.name!r}, {kn.element_kernel_name(f, v)!r}, {when!r}, {v.groups!r}, {v.energy!r}),")
        out.append("    )),")
    out.append(")")
    out.append("# output name, kind ('step' or 'field'), doc, extra arguments,")
    out.append("# field kernels: (selecting option values, kernel name)")
    out.append("OUTPUTS = (")
    for o in model.OUTPUTS:
        variants = []
        if o.kind == "field":
            for ap in ("A", "B", "C"):
                for membrane in ("pointwise", "averaged"):
                    options = {"approach": ap, "membrane": membrane}
                    variants.append((options, kn.field_kernel_name(o, options)))
        out.append(f"    ({o.name!r}, {o.kind!r}, {o.doc!r}, {o.arguments!r}, {tuple(variants)!r}),")
    out.append(")")
    out.append(f"GUIDE = {model.GUIDE!r}")
    out.append("# option values under which the one-pass scheme iterates with the printed eq. (37) matrices")
    out.append(f"PRINTED_ITERATION = {model.PRINTED_ITERATION!r}")
    return "\n".join(out) + "\n"


def emit_dispatch(derive_command, spec_hash):
    element_names = sorted({k.name for k in kn.element_kernels()})
    header = [
        '"""The model table and the element dispatch, generated from the declaration in derive/model.py.',
        "",
        f"Autogenerated by `{derive_command}` from derive/ -- do not edit by hand.",
        f"Element kernels specification sha256 {spec_hash}.",
        "The runtime reads OPTIONS, PARAMETERS, COEFFICIENTS, FAMILIES and OUTPUTS; the compiled engine",
        "binds the element kernel names below to compiled kernels and compiles the dispatch functions.",
        '"""',
        "",
        "import math",
        "",
        "from .elements import *  # noqa: F401,F403  (the element kernels the dispatch calls)",
        "",
        f"KERNELS_HASH = {spec_hash[:16]!r}",
        f"ELEMENT_KERNELS = {tuple(element_names)!r}",
        "",
    ]
    parts = [_table_source(), _coefficients_source()]
    for part in ("rod", "end"):
        where = "every element" if part == "rod" else "the last element (the slider)"
        parts.append(_family_dispatch(
            part, "_add", (), ("r", "K", "C", "M"),
            f"r, K, C, M += the terms of the families acting on {where} (printed: the stiffness of "
            "the printed eq. 37 where a variant declares one).", printed=True))
        parts.append(_family_dispatch(part, "_residual_add", (), ("r",),
                                      f"r += the residual of the families acting on {where}."))
        parts.append(_family_dispatch(part, "_newmark_add", ("cv", "cd"), ("r", "S"),
                                      f"r += residual, S += M + cv C + cd K of the families acting on {where}."))
    return "\n".join(header) + "\n" + "\n\n".join(parts)
