"""Markdown for findings.md: numbers as text (n/a for a missing one), tables, row selection."""

import math

import numpy as np


def num(x, digits=4):
    if x is None:
        return "n/a"
    try:
        x = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(x):
        return "n/a"
    return f"{x:.{digits}g}"


def pct(x, digits=3):
    if x is None or not math.isfinite(float(x)):
        return "n/a"
    return f"{100 * float(x):.{digits}g} %"


def _cell(c):
    return " ".join(str(c).split()).replace("|", "\\|")


def table(headers, rows):
    out = ["| " + " | ".join(_cell(h) for h in headers) + " |", "|" + "---|" * len(headers)]
    for r in rows:
        out.append("| " + " | ".join(_cell(c) for c in r) + " |")
    return "\n".join(out)


def short(message, limit=110):
    message = " ".join(str(message).split())
    return message if len(message) <= limit else message[: limit - 3] + "..."


def rows_where(data, **match):
    return [r for r in data["rows"] if all(r[k] == v for k, v in match.items())]


def series(rows, xkey, ykey="amplitude"):
    rows = sorted(rows, key=lambda r: r[xkey])
    return (np.array([r[xkey] for r in rows], dtype=float),
            np.array([r[ykey] for r in rows], dtype=float), rows)
