"""The record of a `crankgen reproduce` output folder (manifest.json): the preset of the run that
made the folder, and for each step of the run (convergence check, bifurcations, each figure,
refinement check, convergence files, findings) the settings and code version (runner.run_version)
that made it, its files with their sha256, and its wall time.  A rerun keeps a step whose record
is complete, whose settings and code version are the current ones and whose files are unchanged,
and recomputes the others.

A manifest that cannot be read or does not have this shape is treated as absent, and a step
record that does not have it as missing, each with a warning naming the file (ManifestWarning):
never a traceback.  File names a record may hold are those of the run's outputs only."""

import json
import warnings
from pathlib import Path

from ..errors import CrankgenError
from ..results.io import read_regular
from .io import atomic_write, file_hash, to_json

NAME = "manifest.json"
FORMAT = 1
STATES = ("complete", "incomplete")


class ManifestError(CrankgenError):
    """manifest.json cannot be used (kept for callers that catch it; load() no longer raises it)."""


class ManifestWarning(UserWarning):
    """manifest.json, or one of its step records, is unreadable or malformed: treated as absent."""


def normalized(obj):
    """Plain JSON value of settings (tuples, numbers and arrays as to_json stores them), so that
    recorded and current settings compare equal exactly when they are the same."""
    return json.loads(json.dumps(to_json(obj), sort_keys=True))


def digest(obj):
    import hashlib
    return hashlib.sha256(json.dumps(normalized(obj), sort_keys=True).encode()).hexdigest()[:16]


def _is_sha(x):
    return isinstance(x, str) and len(x) == 64 and all(c in "0123456789abcdef" for c in x)


def _entry_problem(entry, names):
    """Why a step record does not have the expected shape (None if it does)."""
    if not isinstance(entry, dict):
        return f"a {type(entry).__name__}, not an object"
    if entry.get("state") not in STATES:
        return f"state {entry.get('state')!r} is not one of {', '.join(STATES)}"
    for key in ("settings", "code_version"):
        if not isinstance(entry.get(key), dict):
            return f"{key} is not an object"
    files = entry.get("files")
    if not isinstance(files, dict):
        return f"files is a {type(files).__name__}, not an object"
    for name, sha in files.items():
        if names is not None and name not in names:
            return f"file {name!r} is not an output of crankgen reproduce"
        if not (sha is None or _is_sha(sha)):
            return f"the hash of {name} is not a sha256"
    wall = entry.get("wall_time")
    if wall is not None and (isinstance(wall, bool) or not isinstance(wall, (int, float))):
        return "wall_time is not a number"
    return None


def _document_problem(doc):
    if not isinstance(doc, dict):
        return f"it holds a JSON {type(doc).__name__ if doc is not None else 'null'}, not an object"
    if doc.get("format") != FORMAT:
        return f"format {doc.get('format')!r}, not {FORMAT}"
    if not isinstance(doc.get("steps"), dict):
        return "its steps are not an object"
    if doc.get("preset") is not None and not isinstance(doc.get("preset"), str):
        return "its preset is not a name"
    return None


class Manifest:
    def __init__(self, folder, entries=None, existed=False, preset=None):
        self.folder = Path(folder)
        self.entries = entries or {}
        self.existed = existed
        self.preset = preset          # preset of the run that made the folder (None: unknown)

    @classmethod
    def load(cls, folder, steps=None, names=None):
        """The folder's manifest; absent (empty) when there is none or it cannot be used, and
        without the step records that are malformed, with a ManifestWarning for each.  steps,
        names: the step names and output file names a record may have (None: any)."""
        path = Path(folder) / NAME
        if not path.exists():
            return cls(folder)
        try:
            doc = json.loads(read_regular(path))
            problem = _document_problem(doc)
        except (OSError, ValueError) as exc:
            problem = f"it cannot be read ({exc})"
        if problem:
            warnings.warn(ManifestWarning(
                f"{path} is not a crankgen reproduce manifest: {problem}; it is treated as absent "
                "(files of the output names already there are then refused without --force)"),
                stacklevel=2)
            return cls(folder)
        entries = {}
        for step, entry in doc["steps"].items():
            problem = ("not a step of crankgen reproduce" if steps is not None and step not in steps
                       else _entry_problem(entry, names))
            if problem:
                warnings.warn(ManifestWarning(f"{path}: the record of step {step!r} is malformed "
                                              f"({problem}); the step is treated as not computed"),
                              stacklevel=2)
            else:
                entries[step] = entry
        preset = doc.get("preset")
        if preset is None:        # written before the preset was recorded: the findings' config
            config = entries.get("findings", {}).get("settings", {}).get("config")
            preset = config.get("preset") if isinstance(config, dict) else None
        return cls(folder, entries, existed=True,
                   preset=preset if isinstance(preset, str) else None)

    def save(self):
        doc = {"format": FORMAT, "about": "crankgen reproduce: what made each output file",
               "preset": self.preset, "steps": self.entries}
        text = json.dumps(doc, indent=1, sort_keys=True) + "\n"
        atomic_write(self.folder / NAME, lambda fh: fh.write(text))

    def owned(self, name):
        """Whether a file name is one the recorded steps wrote (or were writing)."""
        return any(name in e.get("files", {}) for e in self.entries.values())

    def state(self, step, settings, version):
        """("current" | "missing" | "stale" | "incomplete", reason)."""
        e = self.entries.get(step)
        if e is None:
            return "missing", "not computed yet"
        if e.get("state") != "complete":
            return "incomplete", "an earlier run was interrupted while computing it"
        if e.get("code_version") != normalized(version):
            return "stale", f"made by other code ({_version_change(e.get('code_version'), normalized(version))})"
        now = normalized(settings)
        old = e.get("settings", {})
        if old != now:
            keys = sorted(k for k in set(old) | set(now) if old.get(k) != now.get(k))
            return "stale", "made with other settings (" + ", ".join(keys[:6]) + \
                (", ..." if len(keys) > 6 else "") + ")"
        for name, sha in e.get("files", {}).items():
            p = self.folder / name
            if not p.exists():
                return "incomplete", f"{name} is missing"
            if sha is None or file_hash(p) != sha:
                return "incomplete", f"{name} was changed or not finished"
        return "current", "complete and current"

    def start(self, step, settings, version, files):
        self.entries[step] = dict(state="incomplete", settings=normalized(settings),
                                  code_version=normalized(version), files={f: None for f in files})
        self.save()

    def finish(self, step, wall_time):
        e = self.entries[step]
        e["files"] = {f: file_hash(self.folder / f) for f in e["files"]}
        e["state"] = "complete"
        e["wall_time"] = round(float(wall_time), 3)
        self.save()

    def remove(self, steps):
        """Forget the records of `steps` and delete their files; returns the files deleted."""
        deleted = []
        for step in steps:
            entry = self.entries.pop(step, None)
            for name in (entry or {}).get("files", {}):
                if not any(name in e.get("files", {}) for e in self.entries.values()):
                    try:
                        (self.folder / name).unlink()
                        deleted.append(name)
                    except FileNotFoundError:
                        pass
        self.save()
        return deleted

    def fingerprint(self, step):
        """Digest of a complete step's settings, code version and file contents (for the steps
        that depend on it)."""
        e = self.entries[step]
        return digest([e["settings"], e["code_version"], e["files"]])

    def wall_time(self, step):
        return self.entries.get(step, {}).get("wall_time")


def _version_change(old, new):
    """'experiments 4c0f... -> 8f4a...' for the parts of the code version that differ."""
    old = old if isinstance(old, dict) else {}
    keys = sorted(k for k in set(old) | set(new) if old.get(k) != new.get(k))
    return ", ".join(f"{k} {old.get(k, 'unknown')} -> {new.get(k, 'unknown')}" for k in keys)
