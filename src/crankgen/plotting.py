"""Plots (matplotlib, Agg backend, imported only when a figure is written)."""


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_deflection(result, path):
    """v* at x* = 1/2 against t*."""
    plt = _pyplot()
    s = result.settings
    fig, ax = plt.subplots(figsize=(7, 3.5), constrained_layout=True)
    ax.plot(result.t, result.v_mid, lw=1)
    ax.set_xlabel("t*")
    ax.set_ylabel("v* at x* = 1/2")
    ax.set_title(f"approach {s['approach']}, {s['formulation']} / {s['damping']} damping, "
                 f"Omega* = {s['omega']:g}, eps = {s['eps']:g}, n = {s['n_elements']}", fontsize=9)
    ax.grid(alpha=0.3)
    fig.savefig(path, dpi=120)
    plt.close(fig)
