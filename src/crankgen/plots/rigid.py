"""The figure of a rigid-versus-flexible comparison (crankgen.analyses.rigid.Comparison): the crank torque,
the pin forces at A and B and the bending moment at mid-span over the revolution, the rigid
mechanism dashed, the flexible one solid."""

import numpy as np

from ..declaration import schema


def comparison_figure(comparison):
    from ..results.outputs import SIView
    from .figures import _si_title, _title, subplots
    from ..analyses.rod_loads import joints
    from ..declaration.units import Scales
    rigid, flexible = comparison.rigid, comparison.flexible
    scales = flexible.scales if comparison.si else None

    def view(result):
        return result if scales is None else SIView(result, scales)

    def unit(name):
        declared = schema.OUTPUTS[name].units
        return declared if scales is None else Scales.si_name(declared)
    pins = joints(flexible.case.guide_record.name)[:2]
    fig, axes = subplots(2 + len(pins), 1, figsize=(7.5, 2.3 * (2 + len(pins)) + 1.2), sharex=True,
                         constrained_layout=True)
    deg = np.degrees(np.asarray(flexible.theta, dtype=float) - float(flexible.theta[0]))
    mid = 0.5 if scales is None else 0.5 * scales.L
    curves = [("torque", "crank torque", lambda r: view(r).quantity("torque"), unit("torque"))]
    for base, x, y in pins:
        curves.append((base, f"|{base.replace('_', ' ')}| force",
                       lambda r, x=x, y=y: np.hypot(view(r).quantity(x), view(r).quantity(y)), unit(x)))
    curves.append(("moment", "bending moment at mid-span", lambda r: view(r).quantity("bending_moment", mid),
                   unit("bending_moment")))
    for ax, (_, label, values, u) in zip(axes, curves):
        ax.plot(deg, values(flexible), lw=1.3, color="C0", label="flexible (steady state)")
        ax.plot(deg, values(rigid), lw=1.3, ls="--", color="C3", label="rigid (kineto-static)")
        ax.set_ylabel(f"{label}\n({u})", fontsize=9)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("crank angle theta (degrees)")
    axes[-1].set_xticks(np.arange(0, 361, 60))
    title = _title(dict(flexible.case.as_dict())) if scales is None else _si_title(flexible, view(flexible))
    fig.suptitle("rigid against flexible\n" + title, fontsize=9)
    return fig


def plot_comparison(comparison, path):
    """comparison_figure written atomically to path (returned)."""
    from ..results.io import save_figure
    return save_figure(comparison_figure(comparison), path)
