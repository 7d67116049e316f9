"""A Jeffcott rotor rubbing on an anisotropically supported stator, simulated segment by segment.

rotor-rub's Python interface: the same engine, inputs and error messages as the ``rotor-rub``
command line, results as numpy arrays.

>>> import rotor_rub as rr
>>> run = rr.simulate(preset="paper", periods=20, method="hybrid", samples=1001, speed_ratio=2.5)
>>> run.events.time.shape == run.events.kind.shape
True

Quantities are dimensionless as in the paper: lengths in radial clearances, time τ = ω_n t,
speed ratio η = Ω/ω_n, forcing period 2π/η, stiffnesses relative to the rotor stiffness.

Functions: :func:`simulate`, :func:`poincare`, :func:`spectrum`, :func:`sweep`,
:func:`sweep_grid`, :func:`presets`, :func:`parameters`; the fixed-step :class:`Stepper`.
Every function takes the model parameters as keywords (``speed_ratio=2.5``,
``friction_coefficient=0.2``; :func:`parameters` lists them with ranges), on top of a
``preset`` (default ``paper``) and an optional TOML ``config`` file, in that order of precedence.
Invalid input raises :class:`ValueError` naming the value and its valid range; a propagation that
fails (divergence, work limit) raises :class:`PropagationError`.

Plots: :mod:`rotor_rub.plot` (matplotlib). Sweeps on a Dask cluster: :mod:`rotor_rub.dask`.
"""

from __future__ import annotations

import os
from typing import Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import PropagationError

__all__ = [
    "EVENT_KINDS",
    "REGIMES",
    "Events",
    "Parameter",
    "PropagationError",
    "Run",
    "Samples",
    "Section",
    "Steps",
    "Spectrum",
    "Stepper",
    "Sweep",
    "parameters",
    "poincare",
    "presets",
    "simulate",
    "spectrum",
    "sweep",
    "sweep_grid",
]

__version__: str = _core.VERSION


from .results import (
    EVENT_KINDS,
    REGIMES,
    Events,
    FloatArray,
    Parameter,
    PathLike,
    Run,
    Samples,
    Section,
    Spectrum,
    Steps,
    Sweep,
)


def parameters() -> List[Parameter]:
    """Every model parameter: name, paper symbol, default, valid range and meaning (the CLI's
    ``rotor-rub params``)."""
    return [
        Parameter(
            name=d["name"],
            symbol=d["symbol"],
            default=d["default"],
            min=d["min"],
            max=d["max"],
            min_open=d["min_open"],
            range=d["range"],
            doc=d["doc"],
        )
        for d in _core.parameters()
    ]


def presets() -> Dict[str, Dict[str, float]]:
    """Every preset by name, with the value of every parameter (the CLI's ``rotor-rub presets``).
    ``presets()["paper"]["speed_ratio"]`` is 1.5."""
    return {name: dict(values) for name, (_, values) in _core.presets().items()}


def _path(config: Optional[PathLike]) -> Optional[str]:
    return None if config is None else os.fspath(config)


def simulate(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    t_end: Optional[float] = None,
    periods: Optional[float] = None,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    samples: int = 1001,
    max_work: Optional[float] = None,
    **params: float,
) -> Run:
    """Simulate one parameter set from τ = 0: every switch and uniform samples.

    Parameters
    ----------
    preset : str, optional
        Named parameter set to start from (see :func:`presets`); default ``"paper"``.
    config : path, optional
        TOML file of parameter values (keys as the keywords below, optional
        ``preset = "NAME"``); its values override the preset's, keywords override both.
    t_end, periods : float, optional
        Run length: an end time τ, or a number of forcing periods 2π/η (default 20).
    method : str, optional
        ``"analytic"`` (default: exact free flight, closed-form contact), ``"hybrid"``,
        ``"taylor"`` (exact free flight, generated Taylor series in contact), ``"dop853"`` or
        ``"rk45"``.
    tol : float, optional
        Accuracy target; each method's default and valid range as in ``rotor-rub simulate
        --help`` (analytic 1e-9, the others 1e-10).
    contact_scheme, step : optional
        The analytic method's contact scheme (``"exprb43"`` or ``"exprb2"``) and fixed sub-step.
    samples : int
        Number of uniform samples t_i = t_end·i/(samples − 1); 0 for none. Default 1001.
    max_work : float, optional
        Work limit (switches plus samples, default 1e9, about an hour): longer runs are refused.
    **params : float
        Model parameters, listed below.

    Returns
    -------
    Run
        ``run.events.time``, ``.kind``, ``.state`` and ``run.samples.time``, ``.state``,
        ``.regime`` as numpy arrays: the same switches and samples as ``rotor-rub simulate
        --events … --samples …`` with the same inputs.

    Raises
    ------
    ValueError
        Invalid input, with the CLI's message (name, value, valid range).
    PropagationError
        The run failed (diverged, or its switch rate exceeds ``max_work``).
    """
    r = _core.simulate(
        preset=preset,
        config=_path(config),
        t_end=t_end,
        periods=periods,
        method=method,
        tol=tol,
        contact_scheme=contact_scheme,
        step=step,
        samples=samples,
        max_work=max_work,
        params=params,
    )
    time_free, time_contact, time_rolling = r["time_in"]
    return Run(
        events=Events(r["event_time"], r["event_kind"], r["event_state"]),
        samples=Samples(r["sample_time"], r["sample_state"], r["sample_regime"]),
        start_time=r["start_time"],
        end_time=r["end_time"],
        end_state=r["end_state"],
        time_free=time_free,
        time_contact=time_contact,
        time_rolling=time_rolling,
        contact_fraction=r["contact_fraction"],
        forcing_period=r["forcing_period"],
        method=r["method"],
        elapsed=r["elapsed"],
    )


def poincare(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: int = 200,
    keep: int = 100,
    lyapunov: bool = False,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    max_work: Optional[float] = None,
    **params: float,
) -> Section:
    """The Poincaré section: the state at τ = k·2π/η for ``keep`` periods k after ``transient``,
    classified (period-n, quasi-periodic, chaotic); with ``lyapunov`` also the largest Lyapunov
    exponent. Default method ``taylor``. Same points as ``rotor-rub poincare``."""
    r = _core.poincare(
        preset=preset,
        config=_path(config),
        transient=transient,
        keep=keep,
        lyapunov=lyapunov,
        method=method,
        tol=tol,
        contact_scheme=contact_scheme,
        step=step,
        max_work=max_work,
        params=params,
    )
    return Section(
        period=r["period"].astype(np.int64),
        state=r["state"],
        response=r["response"],
        lyapunov=r["lyapunov"],
        distinct=r["distinct"],
        method=r["method"],
    )


def spectrum(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: int = 100,
    periods: int = 60,
    samples_per_period: int = 64,
    whirl: bool = False,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    max_work: Optional[float] = None,
    **params: float,
) -> Spectrum:
    """Amplitude spectrum (Hann window) over ``periods`` forcing periods after ``transient``, in
    orders of the running speed (½× and ⅓× rub sub-harmonics fall on 0.5 and 0.333 when
    ``periods`` is a multiple of 6). With ``whirl``, the spectrum of x + i y: negative orders are
    backward whirl. Default method ``taylor``. Same bins as ``rotor-rub spectrum``."""
    r = _core.spectrum(
        preset=preset,
        config=_path(config),
        transient=transient,
        periods=periods,
        samples_per_period=samples_per_period,
        whirl=whirl,
        method=method,
        tol=tol,
        contact_scheme=contact_scheme,
        step=step,
        max_work=max_work,
        params=params,
    )
    return Spectrum(
        order=r["order"], x=r.get("x"), y=r.get("y"), whirl=r.get("whirl"), method=r["method"]
    )


def _sweep_points(
    names: Sequence[str],
    points: FloatArray,
    *,
    preset: Optional[str],
    config: Optional[PathLike],
    transient: int,
    keep: int,
    method: Optional[str],
    tol: Optional[float],
    contact_scheme: Optional[str],
    step: Optional[float],
    skip_errors: bool,
    threads: Optional[int],
    max_work: Optional[float],
    params: Mapping[str, float],
) -> Sweep:
    """The sweep at the rows of ``points`` (columns ``names``): what :func:`sweep`,
    :func:`sweep_grid` and each Dask chunk run."""
    points = np.ascontiguousarray(points, dtype=np.float64)
    if points.ndim != 2:
        raise ValueError(f"points must be a 2-D array (points × parameters), not {points.ndim}-D")
    r = _core.sweep_points(
        list(names),
        points,
        preset=preset,
        config=_path(config),
        transient=transient,
        keep=keep,
        method=method,
        tol=tol,
        contact_scheme=contact_scheme,
        step=step,
        skip_errors=skip_errors,
        threads=threads,
        max_work=max_work,
        params=dict(params),
    )
    index = r["index"].astype(np.intp)
    return Sweep(
        params=tuple(names),
        values=points[index].reshape(len(index), len(names)),
        period=r["period"].astype(np.int64),
        state=r["state"],
        skipped=tuple(r["skipped"]),
    )


def grid_points(
    grid: Mapping[str, Union[Sequence[float], FloatArray]],
) -> Tuple[Tuple[str, ...], FloatArray]:
    """The parameter names and the (n, k) array of points of a grid given as
    ``{name: values}`` (one or two entries; the first varies slowest)."""
    if not 1 <= len(grid) <= 2:
        raise ValueError(f"a grid has one or two parameters, not {len(grid)}")
    names = tuple(grid)
    axes = [np.asarray(grid[n], dtype=np.float64).ravel() for n in names]
    for name, axis in zip(names, axes):
        if axis.size == 0:
            raise ValueError(f"{name}: the grid gives no values")
    mesh = np.meshgrid(*axes, indexing="ij")
    return names, np.stack([m.ravel() for m in mesh], axis=1)


def sweep(
    param: str,
    values: Union[Sequence[float], FloatArray],
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: int = 200,
    keep: int = 50,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    skip_errors: bool = False,
    threads: Optional[int] = None,
    max_work: Optional[float] = None,
    **params: float,
) -> Sweep:
    """Bifurcation diagram: the Poincaré points of ``keep`` periods after ``transient`` at each
    of ``values`` of ``param``, every value from the same initial state, in parallel in Rust
    (``threads`` workers, default all cores) with the GIL released. Default method ``taylor``.

    With ``skip_errors`` values whose propagation fails are left out (listed in
    ``Sweep.skipped``). The rows equal ``rotor-rub sweep``'s for the same values.
    """
    return sweep_grid(
        {param: values},
        preset=preset,
        config=config,
        transient=transient,
        keep=keep,
        method=method,
        tol=tol,
        contact_scheme=contact_scheme,
        step=step,
        skip_errors=skip_errors,
        threads=threads,
        max_work=max_work,
        **params,
    )


def sweep_grid(
    grid: Mapping[str, Union[Sequence[float], FloatArray]],
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: int = 200,
    keep: int = 50,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    skip_errors: bool = False,
    threads: Optional[int] = None,
    max_work: Optional[float] = None,
    **params: float,
) -> Sweep:
    """:func:`sweep` over a one- or two-parameter grid ``{name: values}`` (every combination, the
    first parameter varying slowest). :func:`rotor_rub.dask.sweep` gives the same result, bit for
    bit, on a cluster."""
    names, points = grid_points(grid)
    return _sweep_points(
        names,
        points,
        preset=preset,
        config=config,
        transient=transient,
        keep=keep,
        method=method,
        tol=tol,
        contact_scheme=contact_scheme,
        step=step,
        skip_errors=skip_errors,
        threads=threads,
        max_work=max_work,
        params=params,
    )


class Stepper(_core.Stepper):
    """Fixed-step propagation (the C ABI's stepper) for loops in Python or HIL-style use: exact
    free flight, contact sub-steps, every switch inside a step located.

    ``Stepper(preset="paper", dt=1e-3, speed_ratio=2.0)``: a preset, a TOML ``config``, the step
    ``dt`` Φ(dt) is precomputed for, the ``contact_scheme`` (exprb43 or exprb2),
    ``contact_substeps`` per step and the cap ``max_substeps``, and model parameters as keywords.

    ``step(dt=None)`` advances one step and returns ``(time, state, regime, events)``;
    ``run(steps, dt=None)`` takes many steps in Rust (GIL released) and returns :class:`Steps`;
    ``set_params(**params)`` changes parameters between steps, ``set_input_force(fx, fy)`` the
    external force (held until the next call) and ``set_speed_ratio(eta)`` the speed with a
    continuous phase; ``time``, ``state``, ``regime`` and ``dt`` read the current values.
    """

    def run(self, steps: int, dt: Optional[float] = None) -> Steps:  # type: ignore[override]
        """Take ``steps`` steps of ``dt`` (default: the configured step) in Rust."""
        r = super().run(steps, dt)
        return Steps(
            samples=Samples(r["time"], r["state"], r["regime"]),
            events=Events(r["event_time"], r["event_kind"], r["event_state"]),
        )


def _parameter_section() -> str:
    lines = ["", "    Model parameters (keywords; ``rotor-rub params``)",
             "    -------------------------------------------------"]
    for p in parameters():
        lines.append(f"    {p.name} ({p.symbol}), default {p.default:g}, in {p.range}")
        lines.append(f"        {p.doc}")
    return "\n".join(lines) + "\n"


for _function in (simulate, poincare, spectrum, sweep, sweep_grid):
    _function.__doc__ = (_function.__doc__ or "").rstrip() + "\n" + _parameter_section()
