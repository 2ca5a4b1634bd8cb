"""What made a result: crankgen's version and a hash of the generated kernels it runs.

Records that outlive a run (sweep checkpoints, the reproduce manifest) carry `code_version()`, so
that results made by other code are recognised as such instead of being reused silently.
"""

import hashlib
from functools import lru_cache
from importlib import resources

VERSION = "0.2.0"


@lru_cache(maxsize=None)
def kernels_hash():
    """sha256 (hex, first 16 digits) of every generated kernel module, in name order."""
    h = hashlib.sha256()
    folder = resources.files("crankgen._generated")
    for entry in sorted(folder.iterdir(), key=lambda p: p.name):
        if entry.name.endswith(".py"):
            h.update(entry.name.encode())
            h.update(entry.read_bytes())
    return h.hexdigest()[:16]


def code_version():
    """{"crankgen": version, "kernels": hash of the generated kernels}."""
    return {"crankgen": VERSION, "kernels": kernels_hash()}
