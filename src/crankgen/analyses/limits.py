"""Bounded work: the memory a run would need, estimated before anything is computed or allocated,
and refused (ParameterError naming the parameter and the estimate) when it exceeds the machine.

One estimate for every caller (the command line and the Python API):

    check_run_size(n_elements, n_steps, n_cases=1, stored="states", batch=None, names=None,
                   n_times=0)

- n_elements: rod elements (3 n_elements degrees of freedom);
- n_steps: time steps whose results are kept (per case);
- n_cases: cases of the run (a sweep's grid), batch: how many of them are computed at once
  (default all);
- stored: what is kept per step: "outputs" (t, theta, v*, u*, delta*), "states" (and the reduced
  displacements, velocities and accelerations, as `simulate` keeps them for the declared outputs),
  "nodes" (and the nodal vector, store_nodes=True) or
  "steady" (a steady state per case: its revolution, and the monodromy matrix while it is
  computed);
- n_times: the requested times of `simulate(..., times=...)`, each a stored state (and, between
  steps, a case of the batch that steps to it).

The figures are measured on the compiled engine (peak resident memory; about 3 kB per element of
working memory, two copies of every stored step while a run is assembled, 5.5 (2N)^2 doubles per
steady state being computed) and rounded up.  The limit is the machine's physical memory, or
CRANKGEN_MEMORY_LIMIT (bytes, or with a suffix K, M, G, T: "8G") when set.
"""

import math
import os

from ..declaration import schema
from ..errors import ParameterError
from ..discrete.mesh import NODE_DOFS

__all__ = ["check_run_size", "run_size", "memory_limit", "format_bytes"]

STORED = ("outputs", "states", "nodes", "steady")
ELEMENT_WORKING = 3200          # bytes of working memory per element of a running case
CASE_BOOKKEEPING = 4096         # bytes per case of a sweep (the case, its key, its row, twice)
MONODROMY_COPIES = 6            # (2N)^2 doubles per steady state being computed


def format_bytes(n):
    """1.2 GiB, 109 TiB, 512 B."""
    n = float(n)
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"):
        if n < 1024 or unit == "EiB":
            return f"{n:.0f} {unit}" if unit == "B" or n >= 100 else f"{n:.3g} {unit}"
        n /= 1024


def _parse_size(text):
    text = text.strip().upper().removesuffix("B").removesuffix("I")
    scale = 1
    if text and text[-1] in "KMGTP":
        scale = 1024 ** ("KMGTP".index(text[-1]) + 1)
        text = text[:-1]
    value = float(text) * scale
    if not math.isfinite(value) or value <= 0:
        raise ValueError
    return int(value)


def memory_limit():
    """(bytes, where the figure comes from) of the memory a run may use, or (None, reason) when
    it cannot be known (no check then)."""
    text = os.environ.get("CRANKGEN_MEMORY_LIMIT")
    if text:
        try:
            return _parse_size(text), f"CRANKGEN_MEMORY_LIMIT={text}"
        except ValueError:
            raise ParameterError(f"CRANKGEN_MEMORY_LIMIT must be a size in bytes (e.g. 8G), "
                                 f"got {text!r}") from None
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return None, "unknown"
    return (total, "the physical memory of this machine") if total > 0 else (None, "unknown")


def _parts(n_elements, n_steps, n_cases, stored, batch, n_times=0):
    """{"n_cases" | "n_steps" | "n_elements" | "n_times": bytes} of the estimate."""
    if stored not in STORED:
        raise ParameterError(f"stored must be one of {', '.join(STORED)}, got {stored!r}")
    n_elements, n_steps, n_cases, n_times = (max(0, int(x)) for x in (n_elements, n_steps, n_cases, n_times))
    running = n_cases if batch is None else min(n_cases, max(1, int(batch)))
    dofs = NODE_DOFS * n_elements           # the reduced DOFs (a node's components per element)
    row = 2 + len(schema.ENGINE_OUTPUTS)    # t, theta and the engine's outputs per step
    per_step = {"outputs": row * 8 + 4, "states": 8 * (3 * dofs + row) + 4,
                "nodes": 8 * (3 * dofs + row + NODE_DOFS * (n_elements + 1)) + 4,
                "steady": 4 * 8 * (dofs + row)}[stored]
    working = ELEMENT_WORKING * n_elements
    if stored == "steady":
        working += MONODROMY_COPIES * 8 * (2 * dofs) ** 2
    stored_cases = running if stored == "steady" else n_cases
    at_time = 2 * (8 * (3 * dofs + 5) + 4) + ELEMENT_WORKING * max(1, n_elements)
    return {"n_cases": CASE_BOOKKEEPING * n_cases if n_cases > 1 else 0,
            "n_steps": 2 * per_step * n_steps * stored_cases,
            "n_elements": working * running,
            "n_times": at_time * n_times}


def run_size(n_elements, n_steps, n_cases=1, stored="states", batch=None, n_times=0):
    """Estimated peak memory in bytes of a run (see the module docstring)."""
    return sum(_parts(n_elements, n_steps, n_cases, stored, batch, n_times).values())


def check_run_size(n_elements, n_steps, n_cases=1, stored="states", batch=None, names=None,
                   limit=None, n_times=0):
    """The estimate of run_size, or ParameterError when it exceeds the limit (default
    memory_limit()).  The message names the parameter that weighs most (names maps "n_cases",
    "n_steps", "n_elements" to the caller's words, e.g. {"n_steps": "--revolutions"}) and gives
    the estimate and the limit."""
    parts = _parts(n_elements, n_steps, n_cases, stored, batch, n_times)
    size = sum(parts.values())
    source = "the given limit"
    if limit is None:
        limit, source = memory_limit()
    if limit is None or size <= limit:
        return size
    heaviest = max(parts, key=parts.get)
    names = dict({key: key for key in parts}, **(names or {}))
    cases = f" x {int(n_cases)} cases" if n_cases > 1 and stored != "steady" else ""
    what = {"n_cases": f"{names['n_cases']}: {int(n_cases)} cases",
            "n_steps": (f"{names['n_steps']}: {int(n_steps)} time steps x 5 per-step outputs{cases}"
                        if stored == "outputs" else
                        f"{names['n_steps']} x {names['n_elements']}: {int(n_steps)} time steps x "
                        f"{3 * int(n_elements)} degrees of freedom{cases}"),
            "n_elements": f"{names['n_elements']}: {int(n_elements)} elements"
                          + (f" ({min(int(n_cases), int(batch or n_cases))} cases at once)"
                             if n_cases > 1 else ""),
            "n_times": f"{names['n_times']}: {int(n_times)} requested times x "
                       f"{3 * int(n_elements)} degrees of freedom"}[heaviest]
    raise ParameterError(f"{what} would need about {format_bytes(size)} of memory, more than "
                         f"{format_bytes(limit)} ({source}); ask for less, or set "
                         "CRANKGEN_MEMORY_LIMIT")
