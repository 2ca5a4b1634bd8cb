"""A BifurcationDiagram to and from JSON, and back from its CSV files.

JSON holds everything: per branch its points (parameter, amplitude, stability, every multiplier,
the state, the section samples, the physical quantities of the orbits with their units), origin and
stop reason; the special points with every multiplier and their state; the model (info).  The CSV
files of BifurcationDiagram.to_csv (branches.csv with the quantities, multipliers.csv,
special_points.csv, states.csv) hold the same numbers at full precision, and read_csv rebuilds the
diagram from them.  A mechanism's special points get their Case back from the model, so that
crankgen.follow takes them as it takes those of a fresh continuation.
"""

import csv
import json
import math
from pathlib import Path

import numpy as np

from ...errors import ParameterError
from ...results.io import atomic_file, read_regular


def cell(x):
    """CSV cell of a number: full precision, empty when it does not exist (NaN, inf, None)."""
    if x is None:
        return ""
    x = float(x)
    return repr(x) if np.isfinite(x) else ""

FORMAT = "crankgen-diagram-1"


def _floats(a):
    return [None if not math.isfinite(float(v)) else float(v) for v in np.asarray(a, dtype=float).ravel()]


def _array(values, shape=None):
    a = np.array([math.nan if v is None else v for v in values], dtype=float)
    return a if shape is None else a.reshape(shape)


def _pairs(a):
    return [[float(z.real), float(z.imag)] for z in np.asarray(a, dtype=complex).ravel()]


def _complex(rows, shape):
    return np.array([complex(r, i) for r, i in rows], dtype=complex).reshape(shape)


def jsonable(value):
    """value with NumPy scalars made Python numbers and keys made text, nested (json.dump's input);
    the diagram's and a curve's info alike."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, (np.floating, np.integer, np.bool_)):
        return value.item()
    return value


def case_of(info, parameter, value):
    """The mechanism's Case at parameter = value from a diagram's info (None: not a mechanism's)."""
    from ...declaration.cases import Case
    fields = {k: v for k, v in info.items() if k in Case.__dataclass_fields__}
    if not fields:
        return None
    fields = {k: tuple(v) if isinstance(v, list) else v for k, v in fields.items()}
    fields[parameter] = float(value)
    try:
        return Case.from_dict(fields)
    except Exception:
        return None


def as_dict(d):
    branches = []
    for br in d.branches:
        branches.append(dict(
            period=int(br.period), parameter=_floats(br.parameter), amplitude=_floats(br.amplitude),
            stable=[bool(s) for s in br.stable], multipliers=_pairs(br.multipliers),
            multipliers_shape=list(np.shape(br.multipliers)), states=_floats(br.states),
            states_shape=list(np.shape(br.states)),
            section=None if br.section is None else _floats(br.section),
            section_shape=None if br.section is None else list(np.shape(br.section)),
            origin=br.origin, stop_reason=br.stop_reason,
            quantities={k: _floats(v) for k, v in br.quantities.items()},
            quantity_units=dict(br.quantity_units), quantity_notes=list(br.quantity_notes)))
    points = [dict(kind=s.kind, parameter=float(s.parameter), amplitude=float(s.amplitude), period=int(s.period),
                   branch=int(s.branch), multiplier=[float(s.multiplier.real), float(s.multiplier.imag)],
                   state=None if s.state is None else _floats(s.state),
                   multipliers=None if s.multipliers is None else _pairs(s.multipliers),
                   parameter_name=s.parameter_name, range=None if s.range is None else [float(v) for v in s.range])
              for s in d.special_points]
    return dict(parameter_name=d.parameter_name, branches=branches, special_points=points,
                info=jsonable(d.info))


def from_dict(x, classes):
    """The diagram of as_dict's data; classes: (BifurcationDiagram, Branch, SpecialPoint), which
    diagram.py passes (this module does not import it back)."""
    BifurcationDiagram, Branch, SpecialPoint = classes
    name = x["parameter_name"]
    branches = []
    for b in x["branches"]:
        branches.append(Branch(
            period=int(b["period"]), parameter_name=name, parameter=_array(b["parameter"]),
            amplitude=_array(b["amplitude"]), stable=np.array(b["stable"], dtype=bool),
            multipliers=_complex(b["multipliers"], tuple(b["multipliers_shape"])),
            states=_array(b["states"], tuple(b["states_shape"])),
            section=None if b["section"] is None else _array(b["section"], tuple(b["section_shape"])),
            origin=b["origin"], stop_reason=b["stop_reason"],
            quantities={k: _array(v) for k, v in b.get("quantities", {}).items()},
            quantity_units=dict(b.get("quantity_units", {})), quantity_notes=list(b.get("quantity_notes", []))))
    info = dict(x["info"])
    points = []
    for s in x["special_points"]:
        points.append(SpecialPoint(
            kind=s["kind"], parameter=s["parameter"], amplitude=s["amplitude"], period=s["period"],
            branch=s["branch"], multiplier=complex(*s["multiplier"]),
            state=None if s["state"] is None else _array(s["state"]),
            multipliers=None if s["multipliers"] is None else _complex(s["multipliers"], (len(s["multipliers"]),)),
            parameter_name=s.get("parameter_name") or name,
            case=case_of(info, name, s["parameter"]),
            range=None if s.get("range") is None else tuple(s["range"])))
    d = BifurcationDiagram(name, branches, points, info)
    d.flag_range()
    return d


def write_json(d, path):
    with atomic_file(path) as fh:
        json.dump(dict(format=FORMAT, diagram=as_dict(d)), fh)
    return Path(path)


def read_json(path, classes):
    x = json.loads(read_regular(path))
    if x.get("format") != FORMAT:
        raise ParameterError(f"{path} is not a crankgen bifurcation diagram file (format {x.get('format')!r})")
    return from_dict(x["diagram"], classes)


def write_states(d, path):
    """states.csv: per branch point its section samples (one per revolution of the orbit) and its
    state, full precision."""
    dim = max((np.shape(br.states)[1] for br in d.branches), default=0)
    periods = max((br.period for br in d.branches), default=1)
    with atomic_file(path) as fh:
        w = csv.writer(fh)
        w.writerow(["branch", "point", d.parameter_name] + [f"section_{k}" for k in range(periods)]
                   + [f"state_{k}" for k in range(dim)])
        for b, br in enumerate(d.branches):
            for i in range(len(br)):
                sec = [] if br.section is None else list(br.section[i])
                w.writerow([b, i, cell(br.parameter[i])] + [cell(v) for v in sec] + [""] * (periods - len(sec))
                           + [cell(v) for v in br.states[i]])
    return Path(path)


def _rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _value(text):
    return math.nan if text == "" else float(text)


def read_csv(folder, info, classes):
    """The BifurcationDiagram of the CSV files BifurcationDiagram.to_csv wrote in folder (info: the
    model it was computed for, which the CSV files do not hold; the mechanism's special points need
    it to carry their Case); classes as from_dict's."""
    BifurcationDiagram, Branch, SpecialPoint = classes
    folder = Path(folder)
    rows = _rows(folder / "branches.csv")
    if not rows:
        raise ParameterError(f"{folder / 'branches.csv'} holds no branch point")
    name = list(rows[0])[3]
    mults, states = {}, {}
    for r in _rows(folder / "multipliers.csv"):
        mults.setdefault((int(r["branch"]), int(r["point"])), []).append(complex(_value(r["re"]), _value(r["im"])))
    for r in _rows(folder / "states.csv"):
        states[(int(r["branch"]), int(r["point"]))] = r
    from ...declaration import schema
    from .quantities import MOTOR_QUANTITIES
    declared = {r.name for r in schema.REDUCTIONS}
    quantities = [k for k in rows[0] if k.startswith("peak_") or k in MOTOR_QUANTITIES or k in declared]
    groups = {}
    for r in rows:
        groups.setdefault(int(r["branch"]), []).append(r)
    branches = []
    for b in sorted(groups):
        rs = sorted(groups[b], key=lambda r: int(r["point"]))
        period = int(rs[0]["period"])
        st = [states[(b, int(r["point"]))] for r in rs]
        dim = len([k for k in st[0] if k.startswith("state_") and st[0][k] != ""])
        branches.append(Branch(
            period=period, parameter_name=name, parameter=np.array([_value(r[name]) for r in rs]),
            amplitude=np.array([_value(r["amplitude"]) for r in rs]),
            stable=np.array([r["stable"] == "1" for r in rs]),
            multipliers=np.array([mults[(b, int(r["point"]))] for r in rs], dtype=complex),
            states=np.array([[_value(s[f"state_{k}"]) for k in range(dim)] for s in st]),
            section=np.array([[_value(s[f"section_{k}"]) for k in range(period)] for s in st]),
            origin=rs[0]["origin"], stop_reason=rs[0]["stop_reason"],
            quantities={q: np.array([_value(r[q]) for r in rs]) for q in quantities if any(r[q] for r in rs)}))
    info = dict(info or {})
    points = []
    for r in _rows(folder / "special_points.csv"):
        b = int(r["branch"])
        br = branches[b]
        p = _value(r[name])
        i = int(np.argmin(np.abs(br.parameter - p) + np.abs(br.amplitude - _value(r["amplitude"]))))
        points.append(SpecialPoint(
            kind=r["kind"], parameter=p, amplitude=_value(r["amplitude"]), period=int(r["period"]), branch=b,
            multiplier=complex(_value(r["multiplier_re"]), _value(r["multiplier_im"])), state=br.states[i].copy(),
            multipliers=br.multipliers[i].copy(), parameter_name=name, case=case_of(info, name, p)))
    d = BifurcationDiagram(name, branches, points, info)
    d.flag_range()
    return d
