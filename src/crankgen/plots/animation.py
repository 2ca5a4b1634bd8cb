"""Watch the mechanism move: the deforming mechanism in the inertial frame, frame by frame.

A result that stores its states (a simulation, a steady orbit, the orbit of a continuation point)
gives, at every stored step, the rod's nodes in the inertial frame:

    R(x) = A + (x + m u(x)) e_i + m v(x) e_j,    A = a* (cos theta, sin theta),
    e_i = (cos phi, -sin phi),  e_j = (sin phi, cos phi)

(crankgen's moving frame of the rigid rod, phi from the guide's closure), the deflections u, v
magnified by m (m = 1: the true positions, `inertial_nodes`; nodes.csv's X, Y columns).  Between
the nodes the rod is drawn with its element's cubic (v and the slope psi) and linear u.  Each frame
draws the crank (from the origin to the crank pin A), the rod, the end mass, the guide's curve
where the end travels (generated/geometry.py) and, for a guide whose end a link carries from a
ground pivot (a four-bar's rocker), that link; and the step's time and crank angle; the title
states the magnification.  GIF through matplotlib's PillowWriter (Pillow comes with matplotlib); MP4 through
ffmpeg where it is installed.
"""

import math

import numpy as np

from ..discrete import kinematics as _kinematics
from .._generated import geometry as _geometry
from ..errors import ParameterError
from ..discrete.mesh import CHI, NODE_DOFS, PSI, U, V, components_of
from ..analyses.limits import count as bounded
from ..declaration.validation import in_range, integer

TARGET = 0.08          # the default magnification shows the largest deflection as about 8 % of L
FRAMES_PER_REVOLUTION = 24
MAX_FRAMES = 240


def inertial_nodes(result, magnification=1.0):
    """(steps, n + 1, 2): the inertial (X, Y) of every node at every stored step, in units of L,
    the elastic displacements magnified by `magnification`."""
    from ..discrete.system import Model

    if getattr(result, "states", None) is None:
        raise ParameterError("the mechanism's motion needs a result that stores its states "
                             "(simulate with history, a steady state with an orbit)")
    case = result.case
    kin = _run_kinematics(result)
    nodal = Model(case).full_nodal(result.states, kin)              # (steps, NODE_DOFS (n + 1))
    u, v = nodal[:, U::NODE_DOFS], nodal[:, V::NODE_DOFS]
    x = np.linspace(0.0, 1.0, u.shape[1])
    return _place(case, kin, x + magnification * u, magnification * v)


def _run_kinematics(result, steps=slice(None)):
    """The kinematics of a result's stored steps (those at `steps`): the prescribed motion's at their
    times, or a driven crank's from its history."""
    crank = getattr(result, "crank", None)
    if crank is not None:
        return _kinematics.crank_state(result.case, np.asarray(crank)[steps])
    return _kinematics.case_state(result.case, np.asarray(result.t, dtype=float)[steps])


def _place(case, kin, along, across):
    """Inertial (X, Y) of rod points at (along, across) in the rigid rod's frame (arrays (steps, P))."""
    phi = kin.phi[:, None]
    pin = _geometry.crank_pin(kin.vector)
    X = pin[:, 0, None] + along * np.cos(phi) + across * np.sin(phi)
    Y = pin[:, 1, None] - along * np.sin(phi) + across * np.cos(phi)
    return np.stack([X, Y], axis=-1)


def _rocker_curve(case, kin, nodal, magnification, pivot, length, points=6):
    """(steps, P, 2): a flexible rocker drawn between its nodes from its pivot (nodal: its own full
    nodal vectors, rocker_nodal), in its frame (axis at the rigid rocker's angle beta)."""
    n_r = nodal.shape[1] // NODE_DOFS - 1
    along, across = _curve(case, nodal, n_r, length / n_r, length, magnification, points)
    beta = np.asarray(kin.beta, dtype=float)[:, None]
    X = pivot[0] + along * np.cos(beta) - across * np.sin(beta)
    Y = pivot[1] + along * np.sin(beta) + across * np.cos(beta)
    return np.stack([X, Y], axis=-1)


def _curve(case, nodal, n, h, length, magnification, points):
    """(along, across) of a beam's points between its n nodes (element length h, total length)."""
    u, v, psi = nodal[:, U::NODE_DOFS], nodal[:, V::NODE_DOFS], nodal[:, PSI::NODE_DOFS]
    chi = nodal[:, CHI::NODE_DOFS]
    cubic_u = "chi" in components_of(case.options)
    z = np.linspace(0.0, 1.0, points + 1)[:-1]
    H = np.stack([2 * z**3 - 3 * z**2 + 1, (z**3 - 2 * z**2 + z) * h, -2 * z**3 + 3 * z**2, (z**3 - z**2) * h])

    def hermite(f, slope, e):
        return f[:, e, None] * H[0] + slope[:, e, None] * H[1] + f[:, e + 1, None] * H[2] + slope[:, e + 1, None] * H[3]

    along, across = [], []
    for e in range(n):
        axial = hermite(u, chi, e) if cubic_u else u[:, e, None] * (1 - z) + u[:, e + 1, None] * z
        along.append((e + z) * h + magnification * axial)
        across.append(magnification * hermite(v, psi, e))
    along.append(length + magnification * u[:, -1:])
    across.append(magnification * v[:, -1:])
    return np.concatenate(along, axis=1), np.concatenate(across, axis=1)


def _rod_curve(case, kin, nodal, magnification, points=6):
    """(steps, P, 2): the rod drawn between its nodes as its elements interpolate it (cubic v with
    the slopes psi; u linear, or cubic with the slopes chi on the exact rod)."""
    n = case.n_elements
    return _place(case, kin, *_curve(case, nodal, n, 1.0 / n, 1.0, magnification, points))


def _nice(value):
    """The largest of 1, 2, 5 times a power of ten not above value (at least 1)."""
    if not value > 1:
        return 1.0
    k = 10.0 ** math.floor(math.log10(value))
    return max(m * k for m in (1, 2, 5) if m * k <= value)


class Frames:
    """The drawing of a result's motion: the positions of every part at the chosen steps, a figure
    and `draw(k)`, which sets the artists to frame k (0 .. len(self) - 1)."""

    def __init__(self, result, magnification=None, frames=None, title=None, scales=None):
        from ..discrete.system import Model
        check_animatable(result)
        case = result.case
        self.case, self.result = case, result
        t = np.asarray(result.t, dtype=float)
        turns = abs(float(result.theta[-1] - result.theta[0])) / (2 * math.pi)
        count = len(t) if frames is None else bounded("frames", frames)
        if frames is None:
            count = min(len(t), MAX_FRAMES, max(2, int(math.ceil(turns * FRAMES_PER_REVOLUTION)) + 1))
        self.steps = np.unique(np.round(np.linspace(0, len(t) - 1, min(count, len(t)))).astype(int))
        kin = _run_kinematics(result, self.steps)
        nodal = Model(case).full_nodal(np.asarray(result.states)[self.steps], kin)
        largest = float(np.max(np.abs(nodal[:, V::NODE_DOFS]))) if nodal.size else 0.0
        self.magnification = (_nice(TARGET / largest) if largest > 0 else 1.0) if magnification is None \
            else in_range("magnification", magnification, 0, None, True)
        if scales is None:
            scales = getattr(result, "scales", None)           # a run made in SI: metres and seconds
        self.scales = scales
        self.length = 1.0 if scales is None else scales.L
        self.unit = ("L", "t*") if scales is None else ("m", "t")
        self.kin = kin
        self.rod = _rod_curve(case, kin, nodal, self.magnification) * self.length   # (frames, P, 2)
        self.pin = _geometry.crank_pin(kin.vector) * self.length
        self.end = self.rod[:, -1, :]
        guide, params = case.guide_record, case.kinematic_parameters
        self.pivot = (getattr(_geometry, f"pivot_{guide.name}")(params) * self.length if guide.pivot else None)
        beta = np.asarray(kin.beta, dtype=float)           # the guide co-ordinate of the rigid end
        model = Model(case)
        self.rocker = None
        if model.mesh.rocker_elements:                     # a flexible rocker: drawn deformed, its tip the rod's end
            rocker = model.rocker_nodal(np.asarray(result.states)[self.steps])
            self.rocker = _rocker_curve(case, kin, rocker, self.magnification, self.pivot / self.length,
                                        model.mesh.rocker_length) * self.length
        else:
            s = np.asarray(result.states, dtype=float)[self.steps][:, model.mesh.reduced_coordinates()[0]]
            beta = np.concatenate([beta, beta + self.magnification * s])      # and of the drawn end on it
        span = float(beta.max() - beta.min()) if beta.size else 0.0
        reach = np.linspace(beta.min() - 0.5 * span - 0.1, beta.max() + 0.5 * span + 0.1, 181)
        self.guide_curve = getattr(_geometry, f"curve_{guide.name}")(reach, params) * self.length
        self.t = t[self.steps] * (1.0 if scales is None else scales.factor("1/omega_b"))
        self.theta = np.asarray(result.theta, dtype=float)[self.steps]
        self.title = title

    def __len__(self):
        return len(self.steps)

    def figure(self):
        """(fig, artists): the figure with every part at frame 0."""
        from matplotlib.patches import Circle as Disc

        from .figures import subplots
        ell, guide = self.length, self.case.guide_record
        fig, ax = subplots(figsize=(7.0, 3.9), dpi=90, constrained_layout=True)
        pts = np.concatenate([self.rod.reshape(-1, 2), self.pin, [[0.0, 0.0]]]
                             + ([self.pivot[None]] if self.pivot is not None else [])
                             + ([self.rocker.reshape(-1, 2)] if self.rocker is not None else []))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = 0.08 * max(hi - lo) + 0.05
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.plot(self.guide_curve[:, 0], self.guide_curve[:, 1], color="0.45", lw=1.2, zorder=1,
                ls="-" if self.pivot is None else ":", label=f"guide ({guide.name})")
        if self.pivot is not None:
            ax.plot([self.pivot[0]], [self.pivot[1]], marker="^", color="0.3", ms=9, ls="none")
        radius = float(np.max(np.hypot(self.pin[:, 0], self.pin[:, 1])))
        ax.add_patch(Disc((0.0, 0.0), radius, fill=False, color="0.8", lw=0.8, ls=":"))
        ax.plot([0.0], [0.0], marker="o", color="0.3", ms=6, ls="none")
        art = {}
        art["crank"], = ax.plot([], [], color="0.2", lw=3.0, solid_capstyle="round", label="crank")
        art["rod"], = ax.plot([], [], color="C0", lw=2.0, label="rod (deflection magnified)")
        if self.pivot is not None:
            art["rocker"], = ax.plot([], [], color="C2", lw=2.5 if self.rocker is None else 2.0,
                                     label="rocker (the link to the ground pivot)" if self.rocker is None
                                     else "flexible rocker (deflection magnified)")
        art["end"], = ax.plot([], [], marker="s" if self.pivot is None else "o", color="C3", ms=10,
                              ls="none", label=f"end mass ({guide.label or guide.name})")
        art["clock"] = ax.text(0.01, 0.98, "", transform=ax.transAxes, va="top", fontsize=8)
        ax.set_xlabel("X / L" if ell == 1.0 and self.unit[0] == "L" else "X (m)")
        ax.set_ylabel("Y / L" if ell == 1.0 and self.unit[0] == "L" else "Y (m)")
        ax.grid(alpha=0.25)
        ax.legend(fontsize=7, loc="lower right", ncol=2)
        from .figures import _si_title, _title
        if self.title:
            head = self.title
        elif self.scales is not None:                 # a run in SI: its mechanism in SI
            head = _si_title(self.result, self.scales)
        else:
            head = _title(self.result.settings if hasattr(self.result, "settings") else dict(self.case.as_dict()))
        ax.set_title(f"{head}\ndeflections magnified {self.magnification:g}x", fontsize=8)
        self.ax, self.art = ax, art
        self.draw(0)
        return fig, art

    def draw(self, k):
        """Set the artists to frame k; returns them."""
        art = self.art
        art["crank"].set_data([0.0, self.pin[k, 0]], [0.0, self.pin[k, 1]])
        art["rod"].set_data(self.rod[k, :, 0], self.rod[k, :, 1])
        art["end"].set_data([self.end[k, 0]], [self.end[k, 1]])
        if "rocker" in art and self.rocker is not None:
            art["rocker"].set_data(self.rocker[k, :, 0], self.rocker[k, :, 1])
        elif "rocker" in art:
            art["rocker"].set_data([self.pivot[0], self.end[k, 0]], [self.pivot[1], self.end[k, 1]])
        when = f"t* = {self.t[k]:.3f}" if self.unit[1] == "t*" else f"t = {self.t[k]:.4g} s"
        from ..analyses.stresses import crank_degrees
        art["clock"].set_text(f"{when}, crank angle {crank_degrees(self.theta[k]):.0f} deg")
        return list(art.values())


def check_animatable(result):
    """ParameterError unless result stores the states of two steps or more (its motion): a result
    simulated with history=False keeps none."""
    states = getattr(result, "states", None)
    if getattr(result, "case", None) is None or not hasattr(result, "t"):
        raise ParameterError(f"animate needs a result of crankgen (a simulation, a steady state), got "
                             f"{type(result).__name__}")
    if states is None:
        why = (" (this run was simulated with history=False, which keeps no states: simulate with "
               "history=True)" if getattr(result, "settings", {}).get("history") is False else "")
        raise ParameterError("animate needs a result that stores its states (simulate with history, a steady "
                             f"state with an orbit){why}")
    if len(np.asarray(result.t)) < 2:
        raise ParameterError("animate needs a result of two steps or more")


def animate(result, path, magnification=None, frames=None, fps=20, title=None, scales=None, progress=None):
    """Write the motion of a result that stores its states (module docstring) to path: a .gif
    (Pillow), or an .mp4 where ffmpeg is installed.  magnification: of the elastic displacements
    (default: the largest deflection drawn as about 8 % of the rod's length, rounded to 1, 2 or 5
    times a power of ten; stated in the title); frames: how many (default 24 per revolution, at most
    240, evenly spread over the stored steps; the first is the first step); fps: frames per
    second; scales: crankgen's units in SI (crankgen.declaration.units.Scales) to draw in metres and seconds
    (default: the result's own, for a run made in SI); progress(done, total) after each frame.
    Returns the path."""
    from matplotlib import animation as mpl_animation

    from ..results.io import atomic_path, output_path

    check_animatable(result)
    path = output_path(path, (".gif", ".mp4"))                # named before any work
    fmt = path.suffix.lower()
    if fmt == ".mp4" and not mpl_animation.writers.is_available("ffmpeg"):
        raise ParameterError("writing .mp4 needs ffmpeg, which is not installed here; write a .gif")
    fps = in_range("fps", fps, 0, 100, True)
    if progress is not None and not callable(progress):
        raise ParameterError(f"progress must be None or a function, got {progress!r}")
    movie = Frames(result, magnification, frames, title, scales)
    fig, _ = movie.figure()
    fig.canvas.draw()                    # the layout once, at frame 0, then kept for every frame: laid
    fig.set_layout_engine("none")        # out again at each grab, the first frame sat 4 px off the rest
    writer = (mpl_animation.PillowWriter(fps=fps) if fmt == ".gif"
              else mpl_animation.FFMpegWriter(fps=fps))
    with atomic_path(path) as tmp:
        with writer.saving(fig, str(tmp), dpi=fig.dpi):
            for k in range(len(movie)):
                movie.draw(k)
                writer.grab_frame()
                if progress is not None:
                    progress(k + 1, len(movie))
    return path
