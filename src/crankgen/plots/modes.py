"""The figure of crankgen.modes (crankgen.analyses.modes): each mode shape's transverse and axial
displacement along the rod (in the moving frame of the rigid rod), one panel per mode, with its
kind and frequency."""

import math
import textwrap

import numpy as np

from ..declaration import schema
from .figures import fit_panels, membrane_applies, panels


def _hermite(values, slopes, length, points=12):
    """The element's cubic through nodal values and slopes (psi = dv/dx), sampled on each element."""
    z = np.linspace(0, 1, points)[:-1]
    h = [2 * z**3 - 3 * z**2 + 1, (z**3 - 2 * z**2 + z) * length, -2 * z**3 + 3 * z**2, (z**3 - z**2) * length]
    out = [h[0] * values[e] + h[1] * slopes[e] + h[2] * values[e + 1] + h[3] * slopes[e + 1]
           for e in range(len(values) - 1)]
    return np.concatenate(out + [values[-1:]])


def modes_figure(m):
    """A Figure of the shapes of a crankgen.Modes."""
    count = len(m.frequencies)
    cols = 2 if count > 1 else 1
    rows = math.ceil(count / cols)
    fig, axes = panels(rows, cols, width=4.4, height=2.2, top_margin=0.9)
    n = m.shapes.shape[1] - 1
    x_nodes = np.linspace(0, 1, n + 1)
    x = np.concatenate([np.linspace(x_nodes[e], x_nodes[e + 1], 12)[:-1] for e in range(n)] + [[1.0]])
    si = m.scales is not None
    for j, ax in enumerate(axes.flat):
        if j >= count:
            ax.set_visible(False)
            continue
        s = m.shapes[j]
        ax.plot(x, _hermite(s[:, 1], s[:, 2], 1.0 / n), color="C0", lw=1.4, label="v (across the rod)")
        ax.plot(x_nodes, s[:, 0], color="C1", lw=1.2, ls="--", marker=".", ms=3, label="u (along the rod)")
        ax.axhline(0, color="0.5", lw=0.6)
        f = (f"{m.hz[j]:.5g} Hz" if si else f"{m.frequencies[j]:.5g} omega_b")
        if m.omega_squared[j] < 0:
            f = "divergent (the frozen rod buckles)"
        ax.set_title(f"mode {j + 1}: {m.kinds[j]}, {f}", fontsize=9)
        ax.set_xlabel("x/L along the rod")
        ax.set_ylabel("shape (largest = 1)")
        ax.set_ylim(-1.15, 1.15)
        ax.grid(alpha=0.3)
        if j == 0:
            leg = ax.legend(fontsize=7, loc="upper center", ncol=2, bbox_to_anchor=(0.5, -0.32), frameon=False)
            leg._crankgen_outside = True
    speed = (f"crank speed {m.omega * m.scales.omega_b:g} rad/s ({m.omega * m.scales.omega_b * 30 / math.pi:.5g} "
             f"rpm)" if si else f"Omega* = {m.omega:g}")
    c = m.case
    skip = (schema.CRANK_SPEED, schema.CRANK_ANGLE)
    if si:                                   # the mechanism in SI: the rod and the case's fields
        from ..declaration.si import describe_si
        sc = m.scales
        parts = [f"L = {sc.L:g} m", f"omega_b = {sc.omega_b:.5g} rad/s", f"rho A = {sc.rhoA:.4g} kg/m",
                 f"r = {sc.base['r']:.4g} m"] + describe_si(c.parameters(), sc, skip=skip)
    else:
        main, other = schema.describe(c.parameters(), skip=skip)
        parts = main + other
    # wrapped to the width of the panels, so that no line runs past the figure's edges
    width = int(cols * 4.4 / 0.078)
    membrane = f" / {c.membrane}" if membrane_applies(c.as_dict()) else ""
    text = textwrap.fill(f"approach {c.approach}, {c.formulation} / {c.damping}{membrane}, n = "
                         f"{c.n_elements}, " + ", ".join(parts), width, break_on_hyphens=False)
    fig.suptitle(textwrap.fill(f"mode shapes of the mechanism frozen at crank angle {math.degrees(m.theta):g} "
                               f"degrees, {speed}", width) + "\n" + text, fontsize=9)
    return fit_panels(fig)


def plot_modes(m, path):
    """modes_figure written atomically to path (returned)."""
    from ..results.io import output_path, save_figure
    path = output_path(path)
    return save_figure(modes_figure(m), path, dpi=110)
