"""Stage 5: emit kernel specifications as straight-line Python source, in several variants.

- `name(...)`: vectorized NumPy, for every kernel.  Array arguments broadcast against each other;
  vector inputs carry their components on the trailing axis.  Leading axes (elements, and an
  optional batch of parameter sets) pass straight through: an output has shape
  broadcast(inputs) + (6,) or (6, 6).
- `name_into(..., out1, out2, ...)` (modules in derive/kernels.SCALAR): one element, scalar
  arguments, results written into preallocated arrays (every entry, zeros included).  Plain Python
  with `math`, written so that the runtime can compile it with numba for the hot path.
Element kernels (outputs r and its tangents K = dr/dq, C = dr/dqd, M = dr/dqdd) get one accumulating
one-element function instead, the engine's calling convention,
`name_element(mode, q, qd, qdd, geo, coef, kin, cv, cd, r, K, C, M, S)`, whose mode (ELEMENT_MODES)
says what it adds:
- "full": r += residual, K += K, C += C, M += M;
- "printed": the same with K_printed in place of K (kernels with a K_printed output; the others
  add their exact K), the iteration matrix of the printed one-pass scheme, eq. (37);
- "residual": r += residual (no tangents, for iterations that reuse a factorization);
- "newmark": r += residual and S += M + cv C + cd K, the element part of the iteration matrix of
  eq. (37) (cv = gamma dt, cd = beta dt^2).
One function per kernel keeps the engine's tables and the compilations per model few; each mode's
branch is the straight-line code of its own common-subexpression elimination.  Structural zeros are
skipped.  Beside it, `name_lanes(mode, b, coef, kin, cv, cd)` does the same for LANES elements at
once: their q, qd, qdd, geo and r, K, C, M, S are rows of LANES values in one flat buffer b
(`lane_rows`), every row at a constant offset, so that the compiler turns the loop over the
elements into vector instructions; each element's statements are those of `name_element`, its
numbers the same to the last bit.  (The engine runs the rod's families through their lane
functions and the end node's through their one-element functions.)
Every variant comes from the same specification and a common-subexpression elimination with a fixed
prefix and canonical order, so the same derivation always gives byte-identical source.
"""

import hashlib
from functools import lru_cache

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.pycode import PythonCodePrinter

GENERATOR_VERSION = "6"
ELEMENT_MODES = ("full", "printed", "residual", "newmark")
ELEMENT_ARGUMENTS = ("mode", "q", "qd", "qdd", "geo", "coef", "kin", "cv", "cd", "r", "K", "C", "M", "S")
LANE_ARGUMENTS = ("mode", "b", "coef", "kin", "cv", "cd")
LANES = 8                       # elements per call of a lane function (one 512-bit vector of doubles)
LANE_BLOCKS = ("q", "qd", "qdd", "geo", "r", "K", "C", "M", "S")     # the lane buffer's blocks, in order
TANGENTS = ("K", "C", "M")   # d r / d q, d r / d qd, d r / d qdd
CSE_PREFIX = "_c"


class KernelSpecError(ValueError):
    """A kernel specification is inconsistent (a free symbol that is not an input, ...)."""


class _Printer(NumPyPrinter):
    def __init__(self):
        super().__init__({"fully_qualified_modules": True, "inline": True})


class _ScalarPrinter(PythonCodePrinter):
    def __init__(self):
        super().__init__({"fully_qualified_modules": True, "inline": True})


def _definitions(kernel):
    """The kernel's definitions, flat: ((symbol, expression), ...) in the order of their stages."""
    return tuple(pair for stage in getattr(kernel, "definitions", ()) for pair in stage)


def _validate(kernel):
    declared = {}
    for inp in kernel.inputs:
        for sym in inp.symbols:
            if sym in declared:
                raise KernelSpecError(f"{kernel.name}: symbol {sym} declared twice")
            declared[sym] = inp.name
    for sym, expr in _definitions(kernel):
        if sym in declared:
            raise KernelSpecError(f"{kernel.name}: symbol {sym} declared twice")
        missing = expr.free_symbols - set(declared)
        if missing:
            raise KernelSpecError(f"{kernel.name}: definition of {sym} uses symbols not among the inputs: "
                                  f"{', '.join(sorted(map(str, missing)))}")
        declared[sym] = "definition"
    solve = getattr(kernel, "solve", None)
    if solve is not None:
        for expr in (solve.guess, solve.residual, solve.slope):
            missing = sp.sympify(expr).free_symbols - set(declared) - {solve.unknown}
            if missing:
                raise KernelSpecError(f"{kernel.name}: the solve reads symbols not among the inputs: {missing}")
        declared[solve.unknown] = "solve"
        for sym, _ in solve.bound:
            declared[sym] = "solve"
    for out in kernel.outputs:
        missing = out.expr.free_symbols - set(declared)
        if missing:
            names = ", ".join(sorted(str(m) for m in missing))
            raise KernelSpecError(f"{kernel.name}.{out.name}: free symbols not among the inputs: {names}")


def spec_hash(kernels):
    """sha256 of the specification: names, ordered inputs and output expressions."""
    h = hashlib.sha256(GENERATOR_VERSION.encode())
    for k in kernels:
        h.update(_spec_text(k))
    return h.hexdigest()


def _spec_text(kernel):
    """What a kernel adds to the specification hash (its name, inputs, definitions and outputs),
    kept on the kernel: the modules' hashes and the schema's read it again."""
    text = kernel.__dict__.get("_spec_text")
    if text is None:
        parts = [kernel.name]
        parts += [f"{inp.name}:{','.join(map(str, inp.symbols))};" for inp in kernel.inputs]
        # a kernel with definitions (derived at quadrature points) prints its expressions in
        # SymPy's stored order: sorting the terms of its large trees costs seconds and adds nothing
        order = {"order": "none"} if kernel.__dict__.get("definitions") else {}
        parts += [f"{sym}:={sp.srepr(expr, **order)};" for sym, expr in _definitions(kernel)]
        parts += [f"{out.name}={sp.srepr(out.expr, **order)};" for out in kernel.outputs]
        solve = getattr(kernel, "solve", None)
        if solve is not None:
            solved = (solve.unknown, solve.guess, solve.residual, solve.slope) + tuple(e for pair in solve.bound for e in pair)
            parts.append("solve:" + ";".join(sp.srepr(sp.sympify(e)) for e in solved))
        text = "".join(parts).encode()
        object.__setattr__(kernel, "_spec_text", text)
    return text


def _output_shape(expr):
    rows, cols = expr.shape
    if (rows, cols) == (1, 1):
        return ()
    if cols == 1:
        return (rows,)
    return (rows, cols)


def _entries(expr):
    """(index tuple, expression) of every entry, row-major."""
    shape = _output_shape(expr)
    rows, cols = expr.shape
    for i in range(rows):
        for j in range(cols):
            idx = () if not shape else ((i,) if len(shape) == 1 else (i, j))
            yield idx, expr[i, j]


def _cse(kernel):
    """(assignments, reduced expressions, inputs used) of all outputs of a kernel (_staged_cse); a
    kernel whose outputs are printed as they stand (cse False) has no assignments."""
    flat = []
    for out in kernel.outputs:
        flat.extend(e for _, e in _entries(out.expr))
    if not getattr(kernel, "cse", True):
        return (), tuple(flat), set().union(*(e.free_symbols for e in flat))
    # the zeros take no part in the elimination: without them, an element kernel's shares the
    # cached one of its accumulating function's "full" branch (_reduced)
    assignments, reduced, used = _staged_cse(tuple(e for e in flat if e != 0),
                                             tuple(getattr(kernel, "definitions", ())))
    values = iter(reduced)
    return assignments, tuple(e if e == 0 else next(values) for e in flat), used


@lru_cache(maxsize=64)
def _staged_cse(exprs, stages):
    """Common subexpressions (canonical order, fixed prefix) of expressions written in a kernel's
    inputs and, where it has them, its definitions: stages of (symbol, expression) pairs, each
    stage's expressions in the inputs and the earlier stages' symbols.  Returns the assignments
    ((symbol, expression), ...) in the order to compute them (per stage the definitions the
    expressions need: their common subexpressions, then the definitions; then the expressions'
    common subexpressions), the reduced expressions, and the inputs' symbols used.  The one-element
    and the lane functions share the result (cached)."""
    symbols = sp.numbered_symbols(CSE_PREFIX)
    chosen = []
    if stages:
        need = set().union(*(e.free_symbols for e in exprs))
        for stage in reversed(stages):
            pick = tuple((sym, e) for sym, e in stage if sym in need)
            need |= set().union(*(e.free_symbols for _, e in pick))
            chosen.insert(0, pick)
    assignments = []
    for pick in chosen:
        if pick:
            replacements, reduced = sp.cse([e for _, e in pick], symbols=symbols, order="canonical")
            assignments += list(replacements) + [(sym, e) for (sym, _), e in zip(pick, reduced)]
    replacements, reduced = sp.cse(list(exprs), symbols=symbols, order="canonical")
    assignments += replacements
    # the inputs used: the free symbols of the (small) reduced expressions, less those assigned
    own = {sym for sym, _ in assignments}
    used = set().union(*(e.free_symbols for _, e in assignments), *(e.free_symbols for e in reduced)) - own
    return tuple(assignments), tuple(reduced), used


def _is_vector(inp):
    return len(inp.symbols) > 1


NEWTON_ITERATIONS = 50        # a solve's Newton iterations at most
NEWTON_TOL = 1e-12            # ... stopping one iteration after the step is this small (relative)


def _solve_used(kernel):
    """The input symbols a kernel's solve reads (bound before it)."""
    solve = getattr(kernel, "solve", None)
    if solve is None:
        return set()
    return set().union(*(sp.sympify(e).free_symbols for e in (solve.guess, solve.residual, solve.slope)))


def _solve_lines(kernel, printer, vectorized):
    """A kernel's solve: the unknown by Newton from its guess (one more iteration after the step falls
    below NEWTON_TOL relative: quadratic convergence leaves it at round-off), then the bound symbols."""
    solve = getattr(kernel, "solve", None)
    if solve is None:
        return []
    x = solve.unknown.name
    absolute = "numpy.abs" if vectorized else "abs"
    small = (f"numpy.all({absolute}(_step) <= {NEWTON_TOL!r} * (1.0 + {absolute}({x})))" if vectorized
             else f"{absolute}(_step) <= {NEWTON_TOL!r} * (1.0 + {absolute}({x}))")
    lines = [f"    {x} = {printer.doprint(solve.guess)}" + (" + numpy.zeros(shape)" if vectorized else ""),
             "    _last = False",
             f"    for _newton in range({NEWTON_ITERATIONS}):",
             f"        _step = ({printer.doprint(solve.residual)}) / ({printer.doprint(solve.slope)})",
             f"        {x} = {x} - _step",
             "        if _last:",
             "            break",
             f"        _last = {small}"]
    lines += [f"    {sym.name} = {printer.doprint(expr)}" for sym, expr in solve.bound]
    return lines


def _scalar_prologue(kernel, used, assignments, printer):
    """Body lines of a one-element variant: the used components of vector inputs, a solve, then the
    assignments (definitions and common subexpressions)."""
    lines = []
    used = set(used) | _solve_used(kernel)
    for inp in kernel.inputs:
        if _is_vector(inp):
            for k, sym in enumerate(inp.symbols):
                if sym in used:
                    lines.append(f"    {sym.name} = {inp.name}[{k}]")
    lines += _solve_lines(kernel, printer, vectorized=False)
    for sym, expr in assignments:
        lines.append(f"    {sym} = {printer.doprint(expr)}")
    return lines


def emit_scalar_kernel(kernel):
    """Python source of the one-element variant `<name>_into` (numba-compilable)."""
    _validate(kernel)
    printer = _ScalarPrinter()
    replacements, reduced, used = _cse(kernel)
    args = [inp.name for inp in kernel.inputs] + [out.name for out in kernel.outputs]
    lines = [f"def {kernel.name}_into({', '.join(args)}):",
             f'    """{kernel.name} for one element: scalars in, outputs written into '
             f'{", ".join(out.name for out in kernel.outputs)}."""']
    lines += _scalar_prologue(kernel, used, replacements, printer)
    position = 0
    for out in kernel.outputs:
        for idx, _ in _entries(out.expr):
            value = reduced[position]
            position += 1
            index = ", ".join(str(i) for i in idx) if idx else "0"
            lines.append(f"    {out.name}[{index}] = {printer.doprint(sp.Float(value) if value.is_number else value)}")
    return "\n".join(lines) + "\n"


def is_residual_kernel(kernel):
    """A kernel whose outputs are a residual r and (some of) its exact tangents K, C, M."""
    names = [out.name for out in kernel.outputs]
    return names[0] == "r" and "K" in names and all(n in TANGENTS or n in ("r", "K_printed") for n in names)


def _reduced(kernel, entries):
    """The (out name, idx, expr) entries whose expression is not identically zero, the assignments
    (definitions and common subexpressions, _staged_cse), the reduced expressions and the inputs'
    symbols used."""
    entries = tuple((o, idx, e) for o, idx, e in entries if e != 0)
    assignments, reduced, used = _staged_cse(tuple(e for _, _, e in entries),
                                             tuple(getattr(kernel, "definitions", ())))
    return entries, assignments, reduced, used


def _mode_branches(kernel):
    """(mode label, (out name, idx, expr) entries it adds, ELEMENT_MODES indices it serves) of an
    element kernel: "full" r, K, C, M; "printed" the same with K_printed (a kernel without one
    serves it with "full"); "residual" r; "newmark" r and S = M + cv C + cd K (eq. 37)."""
    by_name = {out.name: out.expr for out in kernel.outputs}
    r = [("r", idx, e) for idx, e in _entries(by_name["r"])]

    def tangents(stiffness):
        return [(t, idx, e) for t in TANGENTS for idx, e in _entries(by_name[stiffness if t == "K" else t])]
    S = by_name["M"] + sp.Symbol("cv") * by_name["C"] + sp.Symbol("cd") * by_name["K"]
    printed = _has_printed(kernel)
    branches = [("full", r + tangents("K"), (0,) if printed else (0, 1))]
    if printed:
        branches.append(("printed", r + tangents("K_printed"), (1,)))
    return branches + [("residual", r, (2,)), ("newmark", r + [("S", idx, e) for idx, e in _entries(S)], (3,))]


def _by_mode(head, branches, statements):
    """Source of a function dispatching on `mode`: the lines of head (def line and docstring), then
    one if/elif/else branch per (label, entries, modes) of branches with the lines statements(entries)."""
    lines = list(head)
    for k, (label, entries, modes) in enumerate(branches):
        test = f"mode == {modes[0]}" if len(modes) == 1 else f"mode <= {modes[-1]}"
        keyword = "if" if k == 0 else ("elif" if k < len(branches) - 1 else "else")
        lines.append(f"    {keyword}{' ' + test if keyword != 'else' else ''}:    # {label}")
        lines += ["        " + line for line in statements(entries) or ["pass"]]
    return "\n".join(lines) + "\n"


def emit_kernel(kernel):
    """Python source of one kernel function."""
    _validate(kernel)
    printer = _Printer()
    replacements, reduced, used = _cse(kernel)

    arg_names = [inp.name for inp in kernel.inputs]
    lines = [f"def {kernel.name}({', '.join(arg_names)}):"]
    doc = [f'    """{kernel.doc}', ""]
    doc.append("    Inputs (broadcast against each other; vector inputs on the trailing axis):")
    for inp in kernel.inputs:
        size = f" (..., {len(inp.symbols)})" if _is_vector(inp) else ""
        doc.append(f"        {inp.name}{size}")
    doc.append("    Returns:")
    for out in kernel.outputs:
        shape = ", ".join(str(n) for n in _output_shape(out.expr))
        doc.append(f"        {out.name} (...{', ' + shape if shape else ''}): {out.doc}")
    doc.append('    """')
    lines += doc

    shape_terms = []
    used_or_solved = used | _solve_used(kernel)
    for inp in kernel.inputs:
        if _is_vector(inp):
            for k, sym in enumerate(inp.symbols):
                if sym in used_or_solved:
                    lines.append(f"    {sym.name} = {inp.name}[..., {k}]")
            shape_terms.append(f"numpy.shape({inp.name})[:-1]")
        else:
            shape_terms.append(f"numpy.shape({inp.name})")
    lines.append(f"    shape = numpy.broadcast_shapes({', '.join(shape_terms)})")
    lines += _solve_lines(kernel, printer, vectorized=True)

    for sym, expr in replacements:
        lines.append(f"    {sym} = {printer.doprint(expr)}")

    position = 0
    names = []
    for out in kernel.outputs:
        oshape = _output_shape(out.expr)
        lines.append(f"    {out.name} = numpy.zeros(shape + {oshape!r})")
        for idx, _ in _entries(out.expr):
            value = reduced[position]
            position += 1
            if value == 0:
                continue
            index = ", ".join(["..."] + [str(i) for i in idx])
            lines.append(f"    {out.name}[{index}] = {printer.doprint(value)}")
        names.append(out.name)
    lines.append(f"    return {', '.join(names)}")
    return "\n".join(lines) + "\n"


def emit_module(title, kernels, derive_command, accumulating=False, scalar=False):
    """Source of a generated module: header, import, kernels (with the accumulating variants of
    residual kernels if accumulating, the `_into` variant if scalar)."""
    header = [
        f'"""{title}',
        "",
        f"Autogenerated by `{derive_command}` from derive/ -- do not edit by hand.",
        f"Generator version {GENERATOR_VERSION}, SymPy {sp.__version__}, "
        f"specification sha256 {spec_hash(kernels)}.",
        '"""',
        "",
        "import math",
        "",
        "import numpy",
        "",
        f"__all__ = {[n for k in kernels for n in _names(k, accumulating, scalar)]!r}",
        "",
    ]
    body = "\n\n".join(_sources(k, accumulating, scalar) for k in kernels)
    return "\n".join(header) + "\n" + body


def _has_printed(kernel):
    return any(out.name == "K_printed" for out in kernel.outputs)


def _element_statements(kernel, entries):
    """One element's statements: its inputs, the common subexpressions, then out[idx] += expr."""
    printer = _ScalarPrinter()
    entries, replacements, reduced, used = _reduced(kernel, entries)
    lines = [line[4:] for line in _scalar_prologue(kernel, used, replacements, printer)]
    for (out, idx, _), value in zip(entries, reduced):
        index = ", ".join(str(i) for i in idx) if idx else "0"
        lines.append(f"{out}[{index}] += {printer.doprint(value)}")
    return lines


def emit_element(kernel):
    """`<name>_element(mode, ...)`: one function whose branches add an element's terms by mode (the
    module docstring); every argument of ELEMENT_ARGUMENTS is taken, each branch uses its own."""
    printed = _has_printed(kernel)
    head = [f"def {kernel.name}_element({', '.join(ELEMENT_ARGUMENTS)}):",
            f'    """{kernel.name} for one element, by mode (ELEMENT_MODES {ELEMENT_MODES}): 0 r, K, C, M '
            f'+= (exact K); 1 the same with the printed eq. (37) K{"" if printed else " (here: the exact K)"}; '
            '2 r only; 3 r and S += M + cv C + cd K."""']
    return _by_mode(head, _mode_branches(kernel), lambda entries: _element_statements(kernel, entries))


def lane_rows(ndof, ngeo):
    """{block: first row} of the lane buffer (rows of LANES values) and its number of rows: q, qd,
    qdd (ndof rows each), geo (ngeo), r (ndof), K, C, M, S (ndof * ndof each, row-major)."""
    sizes = {"q": ndof, "qd": ndof, "qdd": ndof, "geo": ngeo, "r": ndof,
             "K": ndof * ndof, "C": ndof * ndof, "M": ndof * ndof, "S": ndof * ndof}
    rows, at = {}, 0
    for block in LANE_BLOCKS:
        rows[block] = at
        at += sizes[block]
    return rows, at


class _LanePrinter(_ScalarPrinter):
    """x**(-n) printed 1/x**n: the same number (numba computes x**(-n) as 1.0 / x**n), but without
    the call that keeps a loop from being vectorized."""

    def _print_Pow(self, expr, rational=False):
        if expr.exp.is_Integer and expr.exp < -1:
            power = sp.Pow(expr.base, -expr.exp, evaluate=False)
            return f"1/{self.parenthesize(power, PRECEDENCE['Pow'])}"
        return super()._print_Pow(expr, rational=rational)


def _lane_statements(kernel, entries, rows):
    """The statements of _element_statements in a loop over the elements e < LANES of the lane
    buffer b: the inputs from their rows of b (coef and kin shared), the outputs added into theirs."""
    printer = _LanePrinter()
    entries, replacements, reduced, used = _reduced(kernel, entries)
    ndof = len(next(inp for inp in kernel.inputs if inp.name == "q").symbols)

    def at(row):
        return f"b[{row * LANES} + e]" if row else "b[e]"
    lines = [f"for e in range({LANES}):"]
    for inp in kernel.inputs:
        for k, sym in enumerate(inp.symbols):
            if sym in used:
                where = at(rows[inp.name] + k) if inp.name in rows else f"{inp.name}[{k}]"
                lines.append(f"    {sym.name} = {where}")
    for sym, expr in replacements:
        lines.append(f"    {sym} = {printer.doprint(expr)}")
    for (out, idx, _), value in zip(entries, reduced):
        row = rows[out] + (idx[0] * ndof + idx[1] if len(idx) == 2 else idx[0])
        lines.append(f"    {at(row)} += {printer.doprint(value)}")
    return lines


def emit_lanes(kernel):
    """`<name>_lanes(mode, b, coef, kin, cv, cd)`: `<name>_element`, every mode, for LANES elements
    at once (module docstring; b's layout: lane_rows)."""
    sizes = {inp.name: len(inp.symbols) for inp in kernel.inputs}
    rows, _ = lane_rows(sizes["q"], sizes["geo"])
    head = [f"def {kernel.name}_lanes({', '.join(LANE_ARGUMENTS)}):",
            f'    """{kernel.name}_element for the {LANES} elements of the lane buffer b (same modes)."""']
    return _by_mode(head, _mode_branches(kernel), lambda entries: _lane_statements(kernel, entries, rows))


def _names(kernel, accumulating, scalar):
    names = [kernel.name]
    if scalar:
        names.append(kernel.name + "_into")
    if accumulating and is_residual_kernel(kernel):
        names += [kernel.name + "_element", kernel.name + "_lanes"]
    return names


def _sources(kernel, accumulating, scalar):
    parts = [emit_kernel(kernel)]
    if scalar:
        parts.append(emit_scalar_kernel(kernel))
    if accumulating and is_residual_kernel(kernel):
        parts += [emit_element(kernel), emit_lanes(kernel)]
    return "\n\n".join(parts)
