"""The figure of a Campbell diagram (crankgen.campbell, crankgen.analyses.campbell): each mode's
band of frequencies over a revolution shaded, its mean drawn, the crank-order lines k Omega and
the crossings of the means marked; in SI, crank speed in rpm and frequency in Hz."""

import numpy as np

from .figures import fit_panels, panels


def _describe(info, scales):
    from ..declaration import schema
    from .figures import membrane_applies
    membrane = f" / {info['membrane']}" if membrane_applies(info) else ""
    model = (f"approach {info['approach']}, {info['formulation']} / {info['damping']}{membrane}, "
             f"n = {info['n_elements']}")
    import textwrap
    values = {k: v for k, v in info.items() if k in schema.PARAMETERS}
    skip = (schema.CRANK_SPEED, schema.CRANK_ANGLE)        # the abscissa, and a frozen angle of each
    if scales is None:
        main, other = schema.describe(values, skip=skip)
        parts = main + other
    else:                                                  # the mechanism in SI
        from ..declaration.si import describe_si
        parts = describe_si(values, scales, skip=skip)
    parts += [] if info.get("rotary_inertia", True) else ["no rotary inertia"]
    si = ("" if scales is None else
          f"\nin SI: L = {scales.L:.4g} m, rho A = {scales.rhoA:.4g} kg/m, r = {scales.base['r']:.4g} m, omega_b = "
          f"{scales.omega_b:.4g} rad/s ({scales.omega_b / (2 * np.pi):.4g} Hz), the first pinned-pinned bending "
          f"frequency")
    return (f"Campbell diagram: the frozen mechanism's natural frequencies over a revolution "
            f"({info['angles']} crank angles)\n" + textwrap.fill(f"{model}; " + ", ".join(parts), 110,
                                                                    break_on_hyphens=False) + si)


def campbell_figure(diagram, title=None):
    """The figure (a matplotlib Figure) of a CampbellDiagram."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    si = diagram.scales is not None
    x = diagram.speeds * (60 / (2 * np.pi) if si else 1.0)
    yscale = 1 / (2 * np.pi) if si else 1.0
    low, mean, high = diagram.low * yscale, diagram.mean * yscale, diagram.high * yscale
    fig, axes = panels(1, 1, width=7.5, height=4.6)
    ax = axes[0, 0]
    handles = []
    kinds = diagram.kinds
    for j in range(low.shape[1]):
        color = f"C{j % 10}"
        ax.fill_between(x, low[:, j], high[:, j], color=color, alpha=0.22, lw=0)
        ax.plot(x, mean[:, j], color=color, lw=1.4)
        kind = "axial" if np.mean(kinds[:, j] == "axial") > 0.5 else "bending"
        handles.append(Patch(facecolor=color, alpha=0.45, label=f"mode {j + 1} ({kind})"))
    top = float(np.max(high)) * 1.08 if np.max(high) > 0 else 1.0
    for k in diagram.orders:
        y = k * x * (1 / 60 if si else 1.0)
        ax.plot(x, y, color="0.35", lw=0.8, ls="--", zorder=2)
        # the order's name on its line, inside the frame: just below the top or left of the right edge
        slope = k * (1 / 60 if si else 1.0)
        xe = min(x[-1] - 0.02 * (x[-1] - x[0]), 0.97 * top / slope)
        ax.annotate(f"{k}x", (xe, slope * xe), xytext=(-2, 0), textcoords="offset points", ha="right",
                    va="bottom", fontsize=8, color="0.25",
                    bbox=dict(boxstyle="round,pad=0.1", facecolor="white", edgecolor="none", alpha=0.8))
    means = [c for c in diagram.crossings if c.edge == "mean"]
    if means:
        ax.scatter([c.speed * (60 / (2 * np.pi) if si else 1.0) for c in means],
                   [c.frequency * yscale for c in means], s=22, facecolor="white", edgecolor="black",
                   zorder=5)
    handles += [Line2D([], [], color="0.35", ls="--", lw=0.8, label="crank orders k Omega (k x)"),
                Line2D([], [], color="0.3", lw=1.4, label="mean over the revolution"),
                Patch(facecolor="0.6", alpha=0.35, label="band: lowest to highest over the revolution"),
                Line2D([], [], ls="none", marker="o", markerfacecolor="white", color="black",
                       label="an order crosses a mean: a resonance to expect")]
    if np.any(diagram.divergent > 0):
        handles.append(Line2D([], [], ls="none", label="a band down to 0: the frozen rod buckles "
                                                       "over part of the revolution"))
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(0, top)
    ax.set_xlabel("crank speed (rpm)" if si else "crank speed Omega*")
    ax.set_ylabel("natural frequency (Hz)" if si else "natural frequency (units of omega_b)")
    ax.grid(alpha=0.3)
    leg = ax.legend(handles=handles, fontsize=8, loc="upper center", ncol=2, frameon=False,
                    bbox_to_anchor=(0.5, -0.14))
    leg._crankgen_outside = True
    ax.set_title(title or _describe(diagram.info, diagram.scales), fontsize=9)
    return fit_panels(fig)
