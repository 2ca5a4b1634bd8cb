"""The table of a sweep: one row per case (its parameters, then status, amplitude, ..., message),
with NumPy columns, strict CSV and pandas; a missing number is None in a row and an empty CSV
field, never NaN."""

import csv
import math
from pathlib import Path

import numpy as np

from ..declaration.cases import Case
from ..errors import ParameterError
from .io import atomic_file
from ..analyses.steady import SteadyState

__all__ = ["SweepTable", "failed_row", "plain"]


def failed_row(case, error):
    """Row of a case whose computation raised instead of returning a SteadyState."""
    message = error if isinstance(error, str) else f"{type(error).__name__}: {error}"
    return SteadyState(case, "failed", None, None, 0, 0, None, message, 0.0).row()


def plain(value):
    """numpy scalars -> Python scalars, a non-finite float -> None (rows must be strict JSON and
    CSV friendly; a missing number is None)."""
    value = value.item() if isinstance(value, np.generic) else value
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _standard_columns():
    return list(failed_row(Case(), "").keys())


class SweepTable:
    """Rows of a sweep (dicts: the case's parameters, then status, amplitude, half_peak_to_peak,
    periods, iterations, residual, wall_time, message), in the order of the input cases."""

    def __init__(self, rows):
        self.rows = [dict(row) for row in rows]

    @property
    def columns(self):
        """Column names: those of the rows in order of first appearance."""
        if not self.rows:
            return _standard_columns()
        names = {}
        for row in self.rows:
            names.update(dict.fromkeys(row))
        return list(names)

    def column(self, name):
        """One column as a NumPy array (float for numbers, str for text).  A numeric column with
        missing values (None) is a masked array (numpy.ma), masked where the value is missing."""
        if name not in self.columns:
            raise KeyError(f"no column {name!r}; columns are {', '.join(self.columns)}")
        values = [row.get(name) for row in self.rows]
        present = [v for v in values if v is not None]
        if len(present) < len(values) and present and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
            return np.ma.masked_array([0.0 if v is None else float(v) for v in values],
                                      mask=[v is None for v in values])
        return np.array(values)

    @property
    def failed(self):
        """Rows whose status is not "periodic" (failed, not periodic or unstable)."""
        return [row for row in self.rows if row.get("status") != "periodic"]

    @property
    def cases(self):
        """The rows' cases, as Case objects."""
        return [Case.from_dict(row) for row in self.rows]

    def __len__(self):
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def __getitem__(self, index):
        return self.rows[index]

    def __repr__(self):
        return f"SweepTable({len(self)} rows, {len(self.failed)} not periodic)"

    def to_csv(self, path):
        """Write the table as CSV (floats in full precision; a missing number, None, is an empty
        field), atomically (crankgen.results.io.atomic_file): path holds either the old or the complete new
        table, never a partial one."""
        with atomic_file(path) as fh:
            writer = csv.DictWriter(fh, fieldnames=self.columns)
            writer.writeheader()
            writer.writerows({k: plain(v) for k, v in row.items()} for row in self.rows)
        return Path(path)

    def si_view(self, si):
        """The table with every row's SI columns added (crankgen.results.si_row.row_in_si: the rod, each
        parameter with a unit by its SI name, the amplitude in m, the peak loads in N and N m; each
        column named with its SI unit): si is the crankgen.SIMechanism whose rod (L, E, rho, A, I)
        every row is of, or a sequence of them, one per row."""
        from ..declaration.si import SIMechanism
        from .si_row import row_in_si
        mechs = [si] * len(self.rows) if isinstance(si, SIMechanism) else list(si)
        if len(mechs) != len(self.rows) or not all(isinstance(m, SIMechanism) for m in mechs):
            raise ParameterError(f"si must be a crankgen.SIMechanism or {len(self.rows)} of them (one per row)")
        out = []
        for k, (row, mech) in enumerate(zip(self.rows, mechs)):
            try:
                out.append(dict(row, **row_in_si(row, mech)))
            except ParameterError as exc:
                raise ParameterError(f"row {k}: {exc}") from None
        table = SweepTable(out)
        table._si = mechs
        return table

    def describe(self, columns=None):
        """[{column, units, meaning}] of every column (or of `columns`: the CSV's, with gravity as
        gravity_x, gravity_y): the units are crankgen's declared units strings (crankgen.declaration.units),
        or SI for the columns si_view adds."""
        from .steady_row import describe
        columns = list(self.columns if columns is None else columns)
        out = {d["column"]: d for d in describe(columns)}
        mechs = getattr(self, "_si", None)
        if mechs and self.rows:
            from .si_row import describe_row_in_si
            for d in describe_row_in_si(self.rows[0], mechs[0]):
                out[d["column"]] = d
        return [out[c] for c in columns]

    def to_pandas(self):
        """The table as a pandas DataFrame (needs pandas, which crankgen does not require)."""
        import pandas as pd
        return pd.DataFrame(self.rows, columns=self.columns)
