"""Output of `crankgen reproduce`: the atomic writers of crankgen.results.io (every file written to a
temporary file beside it, `.NAME.*.tmp`, synced and moved into place, with the mode open() would
give it), the clean-up of a killed run's temporary files, file hashes for the manifest, and the
figures' data as JSON."""

import base64
import hashlib
import json
import math
from pathlib import Path

import numpy as np

from ..results.io import (OutputExistsError, _cell, atomic_write, atomic_write_text, csv_text, existing_outputs,  # noqa: F401
                          save_figure, write_csv)


def remove_temporaries(folder, names):
    """Delete leftover temporary files `.NAME.*.tmp` of the given output names in folder (what a
    killed run leaves behind); returns the names removed."""
    folder = Path(folder)
    removed = []
    for name in names:
        for p in folder.glob(f".{Path(name).name}.*.tmp"):
            try:
                p.unlink()
                removed.append(p.name)
            except FileNotFoundError:
                pass
    return sorted(removed)


def file_hash(path):
    """sha256 (hex) of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


# ----------------------------------------------------------------------------- data as JSON

def to_json(obj):
    """A JSON-able form of nested dicts, lists, tuples, numbers and numpy arrays that from_json
    turns back into equal objects (arrays bit for bit, NaN kept, tuple keys kept).  Objects with a
    `to_record()` method are stored as {"__record__": class name, ...} and rebuilt by the
    `records` mapping given to from_json."""
    if hasattr(obj, "to_record"):
        return {"__record__": type(obj).__name__, "fields": to_json(obj.to_record())}
    if isinstance(obj, np.ndarray):
        arr = np.ascontiguousarray(obj)
        return {"__array__": base64.b64encode(arr.astype(arr.dtype.newbyteorder("<")).tobytes()).decode(),
                "dtype": arr.dtype.newbyteorder("<").str, "shape": list(arr.shape)}
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        return x if math.isfinite(x) else {"__float__": repr(x)}
    if isinstance(obj, dict):
        if all(isinstance(k, str) and not k.startswith("__") for k in obj):
            return {k: to_json(v) for k, v in obj.items()}
        return {"__items__": [[to_json(k), to_json(v)] for k, v in obj.items()]}
    if isinstance(obj, tuple):
        return {"__tuple__": [to_json(v) for v in obj]}
    if isinstance(obj, list):
        return [to_json(v) for v in obj]
    if obj is None or isinstance(obj, str):
        return obj
    raise TypeError(f"cannot store {type(obj).__name__} as JSON")


def from_json(obj, records=None):
    """Inverse of to_json."""
    records = records or {}
    if isinstance(obj, list):
        return [from_json(v, records) for v in obj]
    if not isinstance(obj, dict):
        return obj
    if "__record__" in obj:
        return records[obj["__record__"]].from_record(from_json(obj["fields"], records))
    if "__array__" in obj:
        arr = np.frombuffer(base64.b64decode(obj["__array__"]), dtype=np.dtype(obj["dtype"]))
        return arr.reshape(obj["shape"]).astype(arr.dtype.newbyteorder("="))
    if "__float__" in obj:
        return float(obj["__float__"])
    if "__tuple__" in obj:
        return tuple(from_json(v, records) for v in obj["__tuple__"])
    if "__items__" in obj:
        return {_hashable(from_json(k, records)): from_json(v, records) for k, v in obj["__items__"]}
    return {k: from_json(v, records) for k, v in obj.items()}


def _hashable(k):
    return tuple(_hashable(x) for x in k) if isinstance(k, (list, tuple)) else k


def write_json(path, obj, overwrite=True):
    text = json.dumps(to_json(obj), separators=(",", ":"), sort_keys=False)
    return atomic_write(path, lambda fh: fh.write(text), overwrite=overwrite)


def read_json(path, records=None):
    with open(path) as fh:
        return from_json(json.load(fh), records)
