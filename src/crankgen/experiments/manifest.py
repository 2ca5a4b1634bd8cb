"""The record of a `crankgen reproduce` output folder (manifest.json): for each step of the run
(convergence check, bifurcations, each figure, refinement check, convergence files, findings) the
settings and code version (runner.run_version) that made it, its files with their sha256, and its
wall time.  A rerun keeps a step whose record is complete, whose settings and code version are
the current ones and whose files are unchanged, and recomputes the others."""

import json
from pathlib import Path

from ..errors import CrankgenError
from .io import atomic_write, file_hash, to_json

NAME = "manifest.json"
FORMAT = 1


class ManifestError(CrankgenError):
    """manifest.json exists but cannot be read as a reproduce manifest."""


def normalized(obj):
    """Plain JSON value of settings (tuples, numbers and arrays as to_json stores them), so that
    recorded and current settings compare equal exactly when they are the same."""
    return json.loads(json.dumps(to_json(obj), sort_keys=True))


def digest(obj):
    import hashlib
    return hashlib.sha256(json.dumps(normalized(obj), sort_keys=True).encode()).hexdigest()[:16]


class Manifest:
    def __init__(self, folder, entries=None, existed=False):
        self.folder = Path(folder)
        self.entries = entries or {}
        self.existed = existed

    @classmethod
    def load(cls, folder):
        path = Path(folder) / NAME
        if not path.exists():
            return cls(folder)
        try:
            with open(path) as fh:
                doc = json.load(fh)
            if doc.get("format") != FORMAT or not isinstance(doc.get("steps"), dict):
                raise ValueError("unknown format")
        except (OSError, ValueError) as exc:
            raise ManifestError(f"{path} is not a readable reproduce manifest ({exc}); "
                                "use --force to recompute everything") from None
        return cls(folder, doc["steps"], existed=True)

    def save(self):
        doc = {"format": FORMAT, "about": "crankgen reproduce: what made each output file",
               "steps": self.entries}
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
