"""Atomic output: every file is written to a temporary file beside it and moved into place with
os.replace, so an interrupted run never leaves a half-written CSV, PNG or findings.md."""

import csv
import io
import math
import os
import tempfile
from pathlib import Path

import numpy as np

from ..errors import CrankgenError


class OutputExistsError(CrankgenError):
    """The output folder already holds files that the run would overwrite (and no --force)."""


def atomic_write(path, write, mode="w", overwrite=True):
    """Call write(fileobj) on a temporary file in path's folder, then move it to path.
    On any exception (KeyboardInterrupt included) the temporary file is removed and path is left
    as it was.  With overwrite=False an existing path raises OutputExistsError."""
    path = Path(path)
    if not overwrite and path.exists():
        raise OutputExistsError(f"{path} exists; use --force to overwrite it")
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        kwargs = {"newline": ""} if "b" not in mode else {}
        with os.fdopen(fd, mode, **kwargs) as fh:
            write(fh)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def atomic_write_text(path, text, overwrite=True):
    return atomic_write(path, lambda fh: fh.write(text), overwrite=overwrite)


def _cell(value):
    """CSV cell: full precision floats, empty for a missing number (NaN / None)."""
    if value is None:
        return ""
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return "" if not math.isfinite(value) else repr(value)
    if isinstance(value, (np.integer,)):
        return str(int(value))
    return str(value)


def csv_text(columns, rows):
    """CSV text of rows (mappings) with the given column order."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(columns)
    for row in rows:
        w.writerow([_cell(row.get(c)) for c in columns])
    return buf.getvalue()


def write_csv(path, columns, rows, overwrite=True):
    text = csv_text(columns, rows)
    return atomic_write(path, lambda fh: fh.write(text), overwrite=overwrite)


def save_figure(fig, path, overwrite=True, dpi=120):
    """Save a matplotlib figure atomically as PNG (and close it)."""
    try:
        return atomic_write(path, lambda fh: fig.savefig(fh, format="png", dpi=dpi), mode="wb",
                            overwrite=overwrite)
    finally:
        import matplotlib.pyplot as plt
        plt.close(fig)


def existing_outputs(folder, names):
    """The names (in order) that already exist in folder."""
    folder = Path(folder)
    return [n for n in names if (folder / n).exists()]
