"""Stage 2b: element integrals by Gauss quadrature, with the residual and its tangents derived at
the points (the way FFCx treats a form with a quadrature degree).

Closed-form integration (shape_functions.integrate_element) needs a polynomial integrand; the
geometrically exact rod's strain, curvature and section rotation are not polynomials in the nodal
values.  Here an element integral is a weighted sum over the points of a rule,

    int_0^l f dx = l sum_g w_g f(zeta_g),

and f is written in *point fields*: one symbol per field value at a point (u, v, psi, u_x, v_x,
v_xx, u_xx and their first and second time derivatives), each a linear form B_F(zeta_g) . q (or qd,
qdd) in the element's nodal vector, B_F the shape function column of eqs. (8)-(13) tabulated at the
point.  A field whose column is the same at every point (u_x of the linear axial field) is one
symbol; a field whose column vanishes (u_xx) is 0.

An element energy E (kinetic, potential or dissipation) in point fields gives, by SymPy, the
generalized force of each point field P (the weak form's integrand):

    potential     R_P = dE/dP
    dissipation   R_P = dE/dP'                     (P' the rate of P)
    kinetic       R_P = d/dt dE/dP' - dE/dP        (d/dt through the point fields and the
                                                    rigid kinematics)

and the element residual and tangents follow by the chain rule through the tabulated columns:

    r = sum_P R_P B_P,   K = sum_P B_P (sum_Q dR_P/dQ B_Q)^T,   C, M: the same over the rates and
    the accelerations Q.

Only then are the point fields replaced by their linear forms, and the existing code generation
(common subexpressions, the one-element and lane functions) runs on r, K, C, M as on any kernel.
The same path applied to the polynomial energies of approaches A, B and C reproduces their
closed-form kernels to round-off (tests/test_quadrature_path.py).
"""

from dataclasses import dataclass
from functools import cached_property, lru_cache

import sympy as sp
from sympy.integrals.quadrature import gauss_legendre

from . import symbols as s
from .energies import field_columns

DIGITS = 20                      # decimal digits of the rule's points and weights (printed as literals)

# The fields at a point: name -> shape function column (eqs. 8-13; energies.field_columns: the
# approach's u, whose "u_xx" vanishes where u is linear).
FIELD_COLUMNS = field_columns()
# d/dx of a field, as a field (what the curvature of the exact section rotation needs)
X_DERIVATIVE = {"u": "u_x", "v": "v_x", "u_x": "u_xx", "v_x": "v_xx"}
# time levels: the nodal vector a field is a linear form in, and the suffix of its name in the field
# dictionary (energies.fields' convention: "ud_x" is the rate of u_x)
LEVELS = ((s.q, ""), (s.qd, "d"), (s.qdd, "dd"))


def level_name(field, level):
    """energies.fields' key of a field at a time level: u, ud, udd; u_x, ud_x, udd_x."""
    base, _, rest = field.partition("_")
    suffix = LEVELS[level][1]
    return f"{base}{suffix}_{rest}" if rest else f"{base}{suffix}"


@dataclass(frozen=True)
class Rule:
    """A quadrature rule on [0, 1]: points zeta_g and weights w_g (sum 1), exact for polynomials of
    degree <= `degree`."""

    name: str
    degree: int
    points: tuple
    weights: tuple

    @property
    def text(self):
        return f"{len(self.points)}-point Gauss-Legendre (exact to degree {self.degree})"


def gauss(degree):
    """The Gauss-Legendre rule with the fewest points exact for polynomials of degree `degree`
    (n points: degree 2n - 1), its points and weights as SymPy numbers of DIGITS digits."""
    n = max(1, (degree + 2) // 2)
    xs, ws = gauss_legendre(n, DIGITS)
    half = sp.Rational(1, 2)
    return Rule(f"gauss{n}", 2 * n - 1, tuple((1 + x) * half for x in xs), tuple(w * half for w in ws))


class PointSpace:
    """The point fields of one element under a rule: their symbols, columns and derivatives.
    `quantities`: {SymPy function: its definition (a Lambda)}, point quantities an energy may use
    opaquely (energies.QUANTITIES); element_terms computes each of their partial derivatives once
    per point."""

    def __init__(self, rule, quantities=None, element_fields=None, point_fields=None, columns=FIELD_COLUMNS):
        self.rule = rule
        self.quantities = dict(quantities or {})
        self.derived = {}        # element field symbol (and its rates) -> its definition
        self.column = {}         # point symbol -> (level, column over the nodal vector)
        self.rate = {}           # point symbol -> the symbol of its time derivative
        self._fields = []        # per point: {energies.fields key: symbol or 0, "x": abscissa}
        self._x_derivative = {}  # point symbol -> symbol (or 0) of its x-derivative
        self._totals = {}        # (element field, symbol) -> total(its definition, symbol)
        shared = {}
        for g, zeta in enumerate(rule.points):
            values = {}
            for field, column in columns.items():
                col = column.subs(s.zeta, zeta).applyfunc(sp.expand)
                constant = not column.has(s.zeta)
                for level in range(len(LEVELS)):
                    key = level_name(field, level)
                    if col == sp.zeros(s.ELEMENT_DOFS, 1):
                        values[key] = sp.Integer(0)
                        continue
                    if constant:
                        if key not in shared:
                            shared[key] = self._new(sp.Symbol(f"{key}_", real=True), level, col)
                        values[key] = shared[key]
                    else:
                        values[key] = self._new(sp.Symbol(f"{key}_{g}", real=True), level, col)
            values["x"] = s.x0 + s.l * zeta
            self._fields.append(values)
            for field in columns:
                for level in range(len(LEVELS)):
                    sym = values[level_name(field, level)]
                    if level < len(LEVELS) - 1 and sym != 0:
                        self.rate[sym] = values[level_name(field, level + 1)]
                    if field in X_DERIVATIVE and sym != 0:
                        self._x_derivative[sym] = values[level_name(X_DERIVATIVE[field], level)]
        for values in self._fields:
            values.update(self._element_fields(element_fields or {}, values))
        for g, values in enumerate(self._fields):
            values.update(self._point_fields(point_fields or {}, values, g))

    def _element_fields(self, element_fields, values):
        """The element fields (constant in the element): a symbol for the field and one for each of
        its time derivatives, defined by build(self), an expression in the point fields (kept
        opaque: its partial derivatives are named once), and its time derivatives."""
        out = {}
        for name, build in element_fields.items():
            symbols = [sp.Symbol(f"{level_name(name, k)}_", real=True) for k in range(len(LEVELS))]
            if symbols[0] not in self.derived:
                # an opaque quantity of the point fields it depends on, its derivatives named once
                explicit = build(self)
                arguments = tuple(sorted(explicit.free_symbols & set(self.column), key=str))
                function = sp.Function(name, real=True)
                self.quantities[function] = sp.Lambda(arguments, explicit)
                self._define_levels(symbols, function(*arguments))
            out.update({level_name(name, k): sym for k, sym in enumerate(symbols)})
        return out

    def _define_levels(self, symbols, definition):
        """symbols[k] defined as the k-th time derivative of `definition`, each the rate of the one
        before it."""
        for k, sym in enumerate(symbols):
            self.derived[sym] = definition
            if k + 1 < len(symbols):
                self.rate[sym] = symbols[k + 1]
                definition = self.d_dt(definition)

    def _point_fields(self, point_fields, values, g):
        """Fields of a point defined by build(fields of the point): a symbol for the field at point
        g and one for each of its time derivatives, defined by the expression and its time
        derivatives (the chain rule through them is `total`'s)."""
        out = {}
        for name, build in point_fields.items():
            symbols = [sp.Symbol(f"{level_name(name, k)}_{g}", real=True) for k in range(len(LEVELS))]
            self._define_levels(symbols, build(values))
            out.update({level_name(name, k): sym for k, sym in enumerate(symbols)})
        return out

    def total(self, expr, symbol):
        """d expr / d symbol through the element fields' dependence on it (chain rule)."""
        out = sp.diff(expr, symbol)
        for field in self.derived:
            if expr.has(field):
                inner = self._field_total(field, symbol)
                if inner != 0:
                    out += sp.diff(expr, field) * inner
        return out

    def _field_total(self, field, symbol):
        """total(definition of the element field, symbol), computed once per pair."""
        key = (field, symbol)
        if key not in self._totals:
            self._totals[key] = self.total(self.derived[field], symbol)
        return self._totals[key]

    def _new(self, sym, level, column):
        self.column[sym] = (level, column)
        return sym

    def fields(self, g):
        """energies.fields' dictionary at point g (and "x", the point's abscissa x0 + l zeta_g)."""
        return dict(self._fields[g])

    def integral(self, density):
        """int_0^l density(fields) dx by the rule: l sum_g w_g density(fields(g))."""
        return s.l * sp.Add(*(w * density(self.fields(g)) for g, w in enumerate(self.rule.weights)))

    def d_dx(self, expr):
        """d/dx of an expression in the point fields of one point."""
        return sp.Add(*(sp.diff(expr, p) * self._x_derivative[p]
                        for p in expr.free_symbols if p in self._x_derivative))

    def d_dt(self, expr):
        """Total time derivative through the point fields, the element fields and the rigid
        kinematics (no expansion)."""
        out = [sp.diff(expr, p) * self.rate[p] for p in sorted(expr.free_symbols & set(self.rate), key=str)]
        out += [sp.diff(expr, sym) * rate for sym, rate in s.TIME_DERIVATIVE.items() if expr.has(sym)]
        return sp.Add(*out)

    @cached_property
    def displacement_symbols(self):
        """The point fields of the displacements (level 0), in a fixed order."""
        return tuple(p for p, (level, _) in sorted(self.column.items(), key=lambda kv: str(kv[0])) if level == 0)

    def generalized_forces(self, kind, energy):
        """{P: R_P} over the displacement point fields P of an element energy of kind "potential",
        "dissipation" or "kinetic" (module docstring)."""
        out = {}
        for p in self.displacement_symbols:
            rate = self.rate[p]
            if kind == "potential":
                force = self.total(energy, p)
            elif kind == "dissipation":
                force = self.total(energy, rate)
            elif kind == "kinetic":
                # expanded: polynomial in the point fields and the quantities' derivatives, so
                # that d/dt dT/dP' and dT/dP cancel where they should (mixed partials)
                force = sp.expand(self.d_dt(self.total(energy, rate)) - self.total(energy, p))
            else:
                raise ValueError(f"unknown energy kind {kind!r}")
            if force != 0:
                out[p] = force
        return out

    def element_terms(self, forces):
        """(r, K, C, M, definitions) of the element from generalized point forces {P: R_P}: the
        residual and tangents written in symbols that `definitions` defines in four stages (what
        a kernel computes first, derive/emit.py): the point fields' linear forms in q, qd, qdd; the
        opaque point quantities' partial derivatives (`quantities`); the point forces R_P and their
        derivatives D_PQ = dR_P/dQ; the rows T_P = sum_Q D_PQ B_Q^T.
        Then r = sum_P R_P B_P and K (C, M) = sum_P B_P T_P over the displacement (rate,
        acceleration) point fields Q."""
        n = s.ELEMENT_DOFS
        r = sp.zeros(n, 1)
        tangents = [sp.zeros(n, n) for _ in LEVELS]
        points, rows = [], []
        for p in sorted(forces, key=str):
            col = self.column[p][1]
            force = sp.Symbol(f"R_{p}", real=True)
            points.append((force, forces[p]))
            r += force * col
            row = [sp.zeros(1, n) for _ in LEVELS]
            for other in sorted(self._depends_on(forces[p]), key=str):
                level, col_q = self.column[other]
                derivative = sp.Symbol(f"D{level}_{p}__{other}", real=True)
                points.append((derivative, self.total(forces[p], other)))
                row[level] += derivative * col_q.T
            for level in range(len(LEVELS)):
                named = sp.zeros(1, n)
                for j in range(n):
                    if row[level][j] != 0:
                        sym = sp.Symbol(f"T{level}_{p}_{j}", real=True)
                        rows.append((sym, row[level][j]))
                        named[j] = sym
                tangents[level] += col * named
        quantities, points = self._quantities(points, dict(self.derived))
        definitions = (self.definitions, *quantities, tuple(points), tuple(rows))
        return (r, *tangents, definitions)

    def _depends_on(self, expr):
        """The point fields expr depends on, directly or through the element fields (and through
        the arguments of the opaque quantities it uses)."""
        out = set()
        for sym in expr.free_symbols:
            if sym in self.column:
                out.add(sym)
            elif sym in self.derived:
                out |= self._depends_on(self.derived[sym])
        return out

    def _quantities(self, pairs, definitions):
        """(stages of the opaque point quantities and partial derivatives the expressions of pairs
        use, each a symbol defined by its definition differentiated; pairs with them replaced).
        A definition may itself use opaque quantities (a composition: the exact rotation of the
        element's stretch): those are named in turn, and the stages order every definition after
        the symbols it uses."""
        named, work = {}, list(pairs) + list(definitions.items())
        while True:
            atoms = set()
            for _, expr in work:
                atoms |= {a for a in expr.atoms(sp.Derivative) if self._opaque(a.expr)}
                atoms |= {a for a in expr.atoms(sp.Function) if self._opaque(a)}
            atoms -= set(named)
            if not atoms:
                break
            for atom in sorted(atoms, key=str):
                call = atom.expr if isinstance(atom, sp.Derivative) else atom
                counts = dict(atom.variable_count) if isinstance(atom, sp.Derivative) else {}
                orders = "".join(str(counts.get(arg, 0)) for arg in call.args)
                named[atom] = sp.Symbol(f"{call.func}{orders}_{'_'.join(map(str, call.args))}", real=True)
                definitions[named[atom]] = self._reveal_once(atom)
            # a derivative of an outer quantity in an argument that was an inner quantity is a Subs
            # object: with the inner one named, it becomes a derivative in that symbol
            work = [(sym, _settle(expr.xreplace(named))) for sym, expr in work]
            definitions = {sym: _settle(expr.xreplace(named)) for sym, expr in definitions.items()}
            work = work[:len(pairs)] + list(definitions.items())
        level = {}

        def depth(sym):
            if sym not in level:
                used = definitions[sym].free_symbols & set(definitions)
                level[sym] = 1 + max((depth(u) for u in used), default=0)
            return level[sym]
        stages = [tuple(sorted(((s, e) for s, e in definitions.items() if depth(s) == k), key=lambda p: str(p[0])))
                  for k in range(1, 1 + max(map(depth, definitions), default=0))]
        return tuple(stages), work[:len(pairs)]

    def _opaque(self, call):
        """A quantity's application whose arguments are all symbols (point fields or named quantities)."""
        return call.func in self.quantities and all(isinstance(arg, sp.Symbol) for arg in call.args)

    def _reveal_once(self, atom):
        """An opaque quantity's application or partial derivative with its function's definition put
        in (which may use other opaque quantities) and the derivatives taken."""
        call = atom.expr if isinstance(atom, sp.Derivative) else atom
        return _revealed(atom, call, self.quantities[call.func])

    def reveal(self, expr):
        """expr with the opaque quantities replaced by their definitions (those using others in
        turn), derivatives evaluated."""
        while any(expr.has(function) for function in self.quantities):
            for function, definition in self.quantities.items():
                expr = expr.replace(function, definition)
            expr = expr.doit()
        return expr


    @cached_property
    def definitions(self):
        """((point field, its linear form in q, qd or qdd), ...), in the order of their names."""
        return tuple(sorted(self._linear_forms.items(), key=lambda kv: str(kv[0])))

    @cached_property
    def _linear_forms(self):
        return {p: (col.T * LEVELS[level][0])[0, 0] for p, (level, col) in self.column.items()}

    def substitute(self, expr):
        """expr with every point field replaced by its linear form in q, qd, qdd."""
        return expr.xreplace(self._linear_forms)

    def in_nodal(self, expr):
        """expr (in point fields, element fields and opaque quantities) in q, qd, qdd: the element
        fields by their definitions, the quantities revealed, the point fields' linear forms."""
        while True:      # a field's definition revealed before the fields it uses are replaced
            expr = self.reveal(expr)
            if not any(expr.has(field) for field in self.derived):
                return self.substitute(expr)
            expr = expr.xreplace(self.derived)


@lru_cache(maxsize=None)
def _revealed(atom, call, definition):
    """atom (call or a partial derivative of it) with call's function replaced by its definition
    (a Lambda), derivatives taken: shared by the point spaces of every variant, whose quantities
    (the same rule's) and their derivatives are the same."""
    return atom.xreplace({call: definition(*call.args)}).doit()


def _settle(expr):
    """expr with its Subs objects evaluated (a derivative in a named quantity's symbol)."""
    return expr.replace(lambda e: isinstance(e, sp.Subs), lambda e: e.doit())
