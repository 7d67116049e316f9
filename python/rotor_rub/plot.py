"""Plots of rotor-rub results with matplotlib (an optional dependency: ``pip install
'rotor_rub[plot]'``).

Each function draws on ``ax`` (a new figure's axes when None) and returns the axes, so plots
compose and save as usual (``ax.figure.savefig("orbit.png")``). Text uses matplotlib's bundled
DejaVu fonts, never the system's.

- :func:`orbit`: the orbit (x, y) of a :class:`rotor_rub.Run`, the clearance circle around the
  stator centre, contact starts and ends marked (reversals, rolling starts and ends with
  friction); with a stator ring with mass, the ring's centre orbit beside the rotor's.
- :func:`bifurcation`: the Poincaré x of a :class:`rotor_rub.Sweep` against the swept value.
- :func:`poincare`: the points of a :class:`rotor_rub.Section` in the (x, y) plane.
- :func:`spectrum`: a :class:`rotor_rub.Spectrum`; a whirl spectrum shades backward (negative
  orders) and forward whirl in two colours.
- :func:`runup`: a :class:`rotor_rub.Runup`, the largest and smallest radius per forcing period
  against the speed for the run-up and the coast-down, rubbing periods marked, jumps marked.
- :func:`rub_orbit`: a :class:`rotor_rub.MatrixRun` (a rotor from matrices, SI): the rub
  station's relative orbit with the clearance circle, switches marked; with a moving stator
  point (a ring with mass) the rotor point's and the stator point's orbits beside it.
- :func:`branches`: a :class:`rotor_rub.Continuation`, its orbits' section x (or largest
  radius) against the parameter, stable solid, unstable dashed, bifurcations marked, optionally
  over a sweep's points.

Each takes what it needs from the result's :class:`rotor_rub.Problem` (the stator centre, the
method, the swept parameter), so no extra argument is needed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional, Tuple

import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from . import Continuation, MatrixRun, Run, Runup, Section, Spectrum, Sweep

__all__ = ["orbit", "bifurcation", "poincare", "spectrum", "runup", "branches", "rub_orbit"]

#: Marker and colour per event kind (as the CLI's figures: starts red, ends green).
EVENT_STYLE = {
    "enter": ("o", "tab:red", "contact start"),
    "exit": ("o", "tab:green", "contact end"),
    "reverse": ("^", "tab:purple", "slip reversal"),
    "roll": ("x", "black", "rolling start"),
    "slip": ("s", "tab:orange", "rolling end"),
}


def _axes(ax: Optional["Axes"], size: Tuple[float, float] = (6.0, 6.0)) -> "Axes":
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, new = plt.subplots(figsize=size)
    return new


def orbit(
    run: "Run",
    ax: Optional["Axes"] = None,
    *,
    offset: Optional[Tuple[float, float]] = None,
    from_time: Optional[float] = None,
    events: bool = True,
    **line: Any,
) -> "Axes":
    """The orbit of ``run`` (its samples), the clearance circle of radius 1 around the stator
    centre (``offset``, default the run's problem's ``offset_x``, ``offset_y``), and its switches
    marked by kind. ``from_time`` drops what comes before (a transient). With a stator ring of
    mass, the ring centre's orbit too, and the rotor's motion relative to the ring, the one
    that meets the clearance circle at the contacts."""
    ax = _axes(ax)
    if offset is None:
        offset = run.problem.offset
    t = run.samples.time
    keep = np.ones_like(t, dtype=bool) if from_time is None else t >= from_time
    state = run.samples.state[keep]
    line.setdefault("lw", 0.8)
    line.setdefault("color", "tab:blue")
    ax.plot(state[:, 0], state[:, 1], label="orbit", **line)
    angle = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(offset[0] + np.cos(angle), offset[1] + np.sin(angle), color="0.5", lw=0.8,
            ls="--", label="clearance")
    if state.shape[1] == 8:
        # A stator ring with mass (stator_mass_ratio > 0): its centre (xs, ys) beside the
        # rotor's orbit, around the stator centre it rests at; and the rotor relative to the
        # ring (x − xs, y − ys), which touches where it meets the clearance circle (the circle
        # is the contact boundary for the relative motion, not for the rotor's own orbit when
        # the ring moves).
        ax.plot(offset[0] + state[:, 4], offset[1] + state[:, 5], lw=0.8, color="tab:orange",
                label="ring centre")
        ax.plot(state[:, 0] - state[:, 4], state[:, 1] - state[:, 5], lw=0.6,
                color="tab:green", ls=":", label="rotor − ring (in contact outside the circle)")
    if events and len(run.events):
        ev_keep = (np.ones(len(run.events), dtype=bool) if from_time is None
                   else run.events.time >= from_time)
        for kind, (marker, color, label) in EVENT_STYLE.items():
            at = ev_keep & (run.events.kind == kind)
            if at.any():
                s = run.events.state[at]
                ax.scatter(s[:, 0], s[:, 1], marker=marker, color=color, s=18, zorder=3,
                           label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("x (clearances)")
    ax.set_ylabel("y (clearances)")
    ax.set_title(f"Orbit, {run.method}")
    ax.legend(loc="upper right", fontsize="small")
    return ax


def bifurcation(sweep: "Sweep", ax: Optional["Axes"] = None, *, component: int = 0,
                **points: Any) -> "Axes":
    """Bifurcation diagram: the Poincaré ``component`` (0 x, 1 y, 2 vx, 3 vy) against the first
    swept parameter's value, one dot per kept period."""
    ax = _axes(ax, (8.0, 5.0))
    points.setdefault("s", 2)
    points.setdefault("color", "tab:blue")
    ax.scatter(sweep.value, sweep.state[:, component], linewidths=0, **points)
    ax.set_xlabel(sweep.params[0])
    ax.set_ylabel(["x", "y", "vx", "vy"][component] + " at the forcing-period boundaries")
    ax.set_title(f"Bifurcation diagram over {sweep.params[0]}, {sweep.problem.method_text}")
    return ax


def poincare(section: "Section", ax: Optional["Axes"] = None, *, clearance: bool = False,
             **points: Any) -> "Axes":
    """The Poincaré section in the (x, y) plane, titled with its response class; with
    ``clearance`` the clearance circle around the problem's stator centre too."""
    ax = _axes(ax)
    points.setdefault("s", 8)
    points.setdefault("color", "tab:blue")
    ax.scatter(section.state[:, 0], section.state[:, 1], **points)
    if clearance:
        cx, cy = section.problem.offset
        angle = np.linspace(0.0, 2.0 * np.pi, 361)
        ax.plot(cx + np.cos(angle), cy + np.sin(angle), color="0.5", lw=0.8, ls="--")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (clearances)")
    ax.set_ylabel("y (clearances)")
    title = f"Poincaré section: {section.response}"
    if section.lyapunov is not None:
        title += f", λ₁ = {section.lyapunov:.4f}"
    ax.set_title(title)
    return ax


def spectrum(spec: "Spectrum", ax: Optional["Axes"] = None, *, max_order: float = 4.0,
             log: bool = True) -> "Axes":
    """Amplitude against order (multiples of the running speed), up to ``max_order``. A whirl
    spectrum is drawn two-sided: backward whirl (negative orders) and forward whirl in two
    colours; otherwise x and y."""
    ax = _axes(ax, (8.0, 4.5))
    order = spec.order
    if spec.whirl is not None:
        amp = spec.whirl
        shown = np.abs(order) <= max_order
        top = float(amp[shown].max()) if shown.any() else 1.0
        # Lines rise from a floor six decades below the largest peak (log scale) or from 0.
        floor = top * 1e-6 if log else 0.0
        for side, color, label in ((order < 0, "tab:red", "backward whirl"),
                                   (order >= 0, "tab:blue", "forward whirl")):
            sel = side & shown
            ax.vlines(order[sel], floor, np.maximum(amp[sel], floor), color=color, lw=1.0,
                      label=label)
        ax.set_xlim(-max_order, max_order)
        if log:
            ax.set_ylim(floor, top * 2.0)
        ax.axvline(0.0, color="0.6", lw=0.6)
    else:
        sel = order <= max_order
        for values, color, label in ((spec.x, "tab:blue", "x"), (spec.y, "tab:orange", "y")):
            if values is not None:
                ax.plot(order[sel], values[sel], color=color, lw=1.0, label=label)
        ax.set_xlim(0.0, max_order)
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("order (multiples of the running speed)")
    ax.set_ylabel("amplitude (clearances)")
    ax.set_title("Whirl spectrum" if spec.whirl is not None else "Amplitude spectrum")
    ax.legend(fontsize="small")
    return ax


#: Colours of the run-up and coast-down branches (as the CLI's run-up figure).
BRANCH_COLOR = {"up": "tab:blue", "down": "tab:orange", "hold": "0.4"}


def runup(result: "Runup", ax: Optional["Axes"] = None, *, jumps: bool = True) -> "Axes":
    """Run-up diagram: the largest (thick) and smallest (thin) orbit radius per forcing period
    against the mean speed, one colour per direction (run-up, coast-down), forcing periods with
    contact shaded along the speed axis, jumps marked with triangles; titled with the program
    and the method."""
    ax = _axes(ax, (9.0, 5.5))
    names = {"up": "run-up", "down": "coast-down", "hold": "held speed"}
    for direction, color in BRANCH_COLOR.items():
        sel = result.direction == direction
        if not sel.any():
            continue
        speed = result.speed[sel]
        ax.plot(speed, result.max_radius[sel], color=color, lw=1.4, label=names[direction])
        ax.plot(speed, result.min_radius[sel], color=color, lw=0.6)
        rubbing = result.contact_fraction[sel] > 0
        if rubbing.any():
            ax.scatter(speed[rubbing], np.zeros(int(rubbing.sum())), marker="|", color=color,
                       s=30, alpha=0.5, label=f"rubs ({names[direction]})",
                       transform=ax.get_xaxis_transform())
    if jumps:
        for j in result.jumps:
            marker = "v" if j.after < j.before else "^"
            ax.scatter([j.speed], [j.before], marker=marker, color=BRANCH_COLOR[j.direction],
                       s=50, zorder=3, edgecolors="black", linewidths=0.5)
    ax.set_xlabel("speed ratio η")
    ax.set_ylabel("orbit radius |q| (clearances)")
    ax.set_title(f"Run-up and coast-down: {result.program}\n{result.method}", fontsize="medium")
    ax.legend(fontsize="small")
    return ax


def rub_orbit(
    run: "MatrixRun",
    ax: Optional["Axes"] = None,
    *,
    bodies_ax: Optional["Axes"] = None,
    from_time: Optional[float] = None,
    events: bool = True,
    unit: float = 1e-3,
    **line: Any,
) -> "Axes":
    """The rub station's relative orbit P = q_rotor − q_stator of a run of a rotor from matrices
    (columns ``rub_x``, ``rub_y``), the clearance circle around the stator centre (the model's
    ``offset``), switches marked by kind; lengths in ``unit`` metres (default mm).

    With a moving stator point (``model.station.stator``), the rotor point's and the stator
    point's own orbits are drawn beside it, on ``bodies_ax`` (a second axes of a new figure when
    ``ax`` is None too). Returns the relative orbit's axes."""
    model = run.model
    if model is None:
        raise ValueError("rub_orbit draws a rotor_rub.MatrixRun (rr.simulate(model=...))")
    station = model.station
    moving = station.stator is not None
    if ax is None:
        import matplotlib.pyplot as plt

        if moving and bodies_ax is None:
            _, (ax, bodies_ax) = plt.subplots(1, 2, figsize=(11.0, 5.5))
        else:
            _, ax = plt.subplots(figsize=(6.0, 6.0))
    t = run.samples.time
    keep = np.ones_like(t, dtype=bool) if from_time is None else t >= from_time
    cols = list(run.columns)
    px, py = cols.index("rub_x"), cols.index("rub_y")
    state = run.samples.state[keep]
    line.setdefault("lw", 0.8)
    line.setdefault("color", "tab:blue")
    ax.plot(state[:, px] / unit, state[:, py] / unit, label="rotor − stator", **line)
    angle = np.linspace(0.0, 2.0 * np.pi, 361)
    r = station.clearance / unit
    ox, oy = station.offset[0] / unit, station.offset[1] / unit
    ax.plot(ox + r * np.cos(angle), oy + r * np.sin(angle), color="0.5", lw=0.8, ls="--",
            label=f"clearance {station.clearance:g} m")
    if events and len(run.events):
        ev_keep = (np.ones(len(run.events), dtype=bool) if from_time is None
                   else run.events.time >= from_time)
        for kind, (marker, color, label) in EVENT_STYLE.items():
            at = ev_keep & (run.events.kind == kind)
            if at.any():
                s = run.events.state[at]
                ax.scatter(s[:, px] / unit, s[:, py] / unit, marker=marker, color=color, s=18,
                           zorder=3, label=label)
    names = model.dofs
    unit_name = {1.0: "m", 1e-3: "mm", 1e-6: "µm"}.get(unit, f"× {unit:g} m")
    ax.set_aspect("equal")
    ax.set_xlabel(f"rub x ({unit_name})")
    ax.set_ylabel(f"rub y ({unit_name})")
    rx, ry = int(station.dof_x), int(station.dof_y)  # indices once the model has stated them
    ax.set_title(f"Rub station ({names[rx]}, {names[ry]}), {run.method}")
    ax.legend(loc="upper right", fontsize="small")
    if moving and bodies_ax is not None:
        sx, sy = (int(d) for d in station.stator)  # type: ignore[union-attr]
        for (i, j), label, color in (((rx, ry), "rotor point", "tab:blue"),
                                     ((sx, sy), "stator point (ring centre)", "tab:orange")):
            bodies_ax.plot(state[:, i] / unit, state[:, j] / unit, lw=0.8, color=color,
                           label=f"{label} ({names[i]}, {names[j]})")
        bodies_ax.set_aspect("equal")
        bodies_ax.set_xlabel(f"x ({unit_name})")
        bodies_ax.set_ylabel(f"y ({unit_name})")
        bodies_ax.set_title("Rotor and stator orbits")
        bodies_ax.legend(loc="upper right", fontsize="small")
    return ax


#: Colour of period-k orbits' branches (as the CLI's figure).
PERIOD_COLOR = {1: "tab:blue", 2: "tab:orange", 4: "tab:green"}
#: Marker, colour and label per bifurcation kind.
BIFURCATION_STYLE = {
    "fold": ("o", "tab:red", "fold"),
    "period-doubling": ("^", "tab:purple", "period doubling"),
    "neimark-sacker": ("s", "tab:cyan", "Neimark-Sacker"),
    "grazing": ("x", "black", "grazing"),
}


def branches(cont: "Continuation", ax: Optional["Axes"] = None, *,
             sweep: Optional["Sweep"] = None, quantity: str = "x") -> "Axes":
    """Branch diagram: each orbit's ``quantity`` (``"x"`` on the section, ``"max_radius"`` or
    ``"min_radius"``) against the continued parameter, stable runs solid and unstable ones
    dashed, one colour per period, the located bifurcations marked; with ``sweep`` (a
    :class:`rotor_rub.Sweep` over the same parameter and ``quantity="x"``) its Poincaré points
    in grey behind, which the stable branches run through."""
    ax = _axes(ax, (9.0, 5.5))
    if quantity == "x":
        values = cont.state[:, 0]
        label = "x on the section τ = 0 mod 2π/η (clearances)"
    elif quantity in ("max_radius", "min_radius"):
        values = getattr(cont, quantity)
        label = quantity.replace("_", " ") + " |q| (clearances)"
    else:
        raise ValueError(f"quantity: {quantity!r} is not 'x', 'max_radius' or 'min_radius'")
    if sweep is not None:
        ax.scatter(sweep.value, sweep.state[:, 0], s=1, color="0.7", linewidths=0,
                   label="sweep", zorder=1)
    plain = cont.kind == ""
    seen = set()
    for b in np.unique(cont.branch):
        rows = np.flatnonzero((cont.branch == b) & plain)
        if rows.size == 0:
            continue
        color = PERIOD_COLOR.get(int(cont.period[rows[0]]), "tab:gray")
        start = 0
        for k in range(1, rows.size + 1):
            if k < rows.size and cont.stable[rows[k]] == cont.stable[rows[start]]:
                continue
            run = rows[start:k + 1] if k < rows.size else rows[start:k]
            stable = bool(cont.stable[rows[start]])
            name = f"period-{int(cont.period[rows[0]])} " + ("stable" if stable else "unstable")
            ax.plot(cont.value[run], values[run], color=color, lw=1.6 if stable else 0.8,
                    ls="-" if stable else "--", label=None if name in seen else name, zorder=2)
            seen.add(name)
            start = k
    for kind, (marker, color, text) in BIFURCATION_STYLE.items():
        sel = cont.kind == kind
        if sel.any():
            ax.scatter(cont.value[sel], values[sel], marker=marker, color=color, s=36,
                       zorder=3, label=text)
    ax.set_xlabel(cont.param)
    ax.set_ylabel(label)
    ax.set_title(f"Periodic orbits over {cont.param}: {len(cont.branches)} branch(es), "
                 f"{len(cont.bifurcations)} bifurcations\n{cont.method}", fontsize="medium")
    ax.legend(fontsize="small")
    return ax
