"""Rows as CSV columns: every cell a number, a word or empty.

A case's parameters come as Python values (Case.as_dict: gravity a pair, groups_off a list of
switched-off term groups as text); flat_table turns them into columns that any CSV reader parses:
gravity into two numeric columns gravity_x, gravity_y (units L omega_b^2), a motor's torque_curve
into one cell of its per-unit pairs "0:1,0.8:2.2,1:0" (the text --torque-curve takes), groups_off
dropped when it is empty in every row (it is only set by the audit's term-switching runs)."""

from ..declaration import schema

# a pair parameter as two columns <name>_x, <name>_y
PAIRS = {p.name: (f"{p.name}_x", f"{p.name}_y") for p in schema.PARAMETERS.values() if p.kind == "pair"}
CURVES = tuple(p.name for p in schema.PARAMETERS.values() if p.kind == "curve")


def flat_table(columns, rows):
    """(columns, rows) with pairs split into two columns and always-empty optional columns dropped."""
    rows = [dict(r) for r in rows]
    out_cols = []
    for c in columns:
        if c in PAIRS:
            names = PAIRS[c]
            for r in rows:
                value = r.pop(c, None)
                pair = tuple(value) if isinstance(value, (list, tuple)) and len(value) == 2 else (None, None)
                r.update(zip(names, pair))
            out_cols += list(names)
        elif c in CURVES:
            from ..declaration.torque_curve import text
            for r in rows:
                if isinstance(r.get(c), (list, tuple)):
                    r[c] = text(r[c])
            out_cols.append(c)
        elif c == "groups_off" and not any(r.get(c) for r in rows):
            for r in rows:
                r.pop(c, None)
        else:
            out_cols.append(c)
    return out_cols, rows
