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
:func:`sweep_grid`, :func:`runup`, :func:`orbit`, :func:`continuation`, :func:`presets`,
:func:`parameters`, :func:`load`; the fixed-step :class:`Stepper`. Every function takes the model parameters as keywords
(``speed_ratio=2.5``, ``friction_coefficient=0.2``; :func:`parameters` lists them with ranges),
on top of a ``preset`` (default ``paper``) and an optional TOML ``config`` file, in that order of
precedence. Numbers may be Python or numpy scalars (``np.float32``, ``np.int64``); booleans,
strings and arrays are refused. Invalid input raises :class:`ValueError` naming the value and its
valid range — a run over ``max_work`` too, refused up front or as soon as its switch rate shows
it; a propagation that fails (divergence, a singular contact) raises :class:`PropagationError`.
Ctrl-C interrupts any call within about 50 ms (KeyboardInterrupt); the long calls take
``progress=`` (True, a callable ``progress(done, total)`` or a tqdm-style bar).

Every result carries its :class:`Problem` (parameters, method, tolerance, version) and converts
with ``.to_pandas()`` / ``.to_xarray()``; ``.save(path)`` writes Parquet or NetCDF with the
metadata and :func:`load` reads it back.

Plots: :mod:`rotor_rub.plot` (matplotlib). Sweeps on a Dask cluster: :mod:`rotor_rub.dask`.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional

import numpy as np

from . import _core, _progress
from ._core import PropagationError, StepperState
from ._io import load
from ._model import MatrixRun, Model, Rub
from .results import (
    EVENT_KINDS,
    REGIMES,
    SPEED_DIRECTIONS,
    WHIRL_DIRECTIONS,
    Count,
    Events,
    Jump,
    Parameter,
    PathLike,
    Problem,
    Real,
    Run,
    Runup,
    RunupEvents,
    Samples,
    Section,
    Spectrum,
    Steps,
    Sweep,
    Values,
)

__all__ = [
    "EVENT_KINDS",
    "REGIMES",
    "SPEED_DIRECTIONS",
    "WHIRL_DIRECTIONS",
    "Count",
    "Events",
    "Bifurcation",
    "Branch",
    "Continuation",
    "Jump",
    "MatrixRun",
    "Model",
    "Orbit",
    "Parameter",
    "Problem",
    "PropagationError",
    "Real",
    "Rub",
    "Run",
    "Runup",
    "RunupEvents",
    "Samples",
    "Section",
    "Spectrum",
    "Steps",
    "Stepper",
    "StepperState",
    "Sweep",
    "Values",
    "continuation",
    "load",
    "orbit",
    "parameters",
    "poincare",
    "presets",
    "runup",
    "simulate",
    "spectrum",
    "sweep",
    "sweep_grid",
]

__version__: str = _core.VERSION


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
    t_end: Optional[Real] = None,
    periods: Optional[Real] = None,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    samples: Count = 1001,
    max_work: Optional[Real] = None,
    progress: Any = None,
    model: Optional[Model] = None,
    initial: Optional[Any] = None,
    **params: Real,
) -> Run:
    """Simulate one parameter set from τ = 0: every switch and uniform samples.

    With ``model=`` (a :class:`Model`: a rotor from matrices, SI units) the run is that model's
    from t = 0 s: ``t_end`` in s or ``periods`` of 2π/Ω, ``initial`` its start (n positions
    then n velocities, m and m/s; default rest), and the result a :class:`MatrixRun` whose state
    columns are the model's DOFs, their velocities and the rub station's relative displacement
    (``run.columns``); ``preset``, ``config`` and parameter keywords do not apply.

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
    progress : optional
        True (a bar), a callable ``progress(done, total)`` or a tqdm-style bar, in forcing
        periods.
    **params : float
        Model parameters, listed below.

    Returns
    -------
    Run
        ``run.events.time``, ``.kind``, ``.state`` and ``run.samples.time``, ``.state``,
        ``.regime`` as numpy arrays: the same switches and samples as ``rotor-rub simulate
        --events … --samples …`` with the same inputs; ``run.problem`` what it was run with.

    Raises
    ------
    ValueError
        Invalid input, with the CLI's message (name, value, valid range); a run over
        ``max_work`` (refused before it starts, or as soon as its switch rate shows it, with an
        estimate of its length).
    PropagationError
        The run failed (diverged, a singular contact).
    KeyboardInterrupt
        Ctrl-C, within about 50 ms.
    """
    if model is not None or initial is not None:
        given = [k for k, v in (("preset", preset), ("config", config), ("max_work", max_work),
                                ("progress", progress)) if v is not None] + sorted(params)
        if model is None or given:
            raise ValueError("initial= needs model=" if model is None else
                             f"model= runs a rotor from matrices: {', '.join(given)} do(es) "
                             "not apply to it")
        from ._model import simulate_model
        return simulate_model(model, t_end=t_end, periods=periods, method=method, tol=tol,
                              contact_scheme=contact_scheme, step=step, samples=samples,
                              initial=initial)
    r = _progress.run(lambda report: _core.simulate(
        preset=preset, config=_path(config), t_end=t_end, periods=periods, method=method,
        tol=tol, contact_scheme=contact_scheme, step=step, samples=samples,
        max_work=max_work, progress=report, params=params), progress, "simulate", "periods",
        whole=False)
    time_free, time_contact, time_rolling = r["time_in"]
    options = {"preset": preset, "config": config, "t_end": t_end, "periods": periods,
               "samples": r["samples"], "max_work": max_work}
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
        elapsed=r["elapsed"],
        problem=Problem._of(r["problem"], "simulate", options),
    )


def poincare(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: Count = 200,
    keep: Count = 100,
    lyapunov: bool = False,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Section:
    """The Poincaré section: the state at τ = k·2π/η for ``keep`` periods k after ``transient``,
    classified (period-n, quasi-periodic, chaotic); with ``lyapunov`` also the largest Lyapunov
    exponent. Default method ``taylor``. Same points as ``rotor-rub poincare``. ``progress`` in
    forcing periods; errors as in :func:`simulate`."""
    r = _progress.run(lambda report: _core.poincare(
        preset=preset, config=_path(config), transient=transient, keep=keep,
        lyapunov=lyapunov, method=method, tol=tol, contact_scheme=contact_scheme, step=step,
        max_work=max_work, progress=report, params=params), progress, "poincare", "periods")
    options = {"preset": preset, "config": config, "transient": transient, "keep": keep,
               "lyapunov": lyapunov, "max_work": max_work}
    return Section(
        period=r["period"].astype(np.int64),
        state=r["state"],
        response=r["response"],
        lyapunov=r["lyapunov"],
        distinct=r["distinct"],
        problem=Problem._of(r["problem"], "poincare", options),
    )


def spectrum(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: Count = 100,
    periods: Count = 60,
    samples_per_period: Count = 64,
    whirl: bool = False,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Spectrum:
    """Amplitude spectrum (Hann window) over ``periods`` forcing periods after ``transient``, in
    orders of the running speed (½× and ⅓× rub sub-harmonics fall on 0.5 and 0.333 when
    ``periods`` is a multiple of 6). With ``whirl``, the spectrum of x + i y: negative orders are
    backward whirl. Default method ``taylor``. Same bins as ``rotor-rub spectrum``.
    ``progress`` in forcing periods; errors as in :func:`simulate`."""
    r = _progress.run(lambda report: _core.spectrum(
        preset=preset, config=_path(config), transient=transient, periods=periods,
        samples_per_period=samples_per_period, whirl=whirl, method=method, tol=tol,
        contact_scheme=contact_scheme, step=step, max_work=max_work, progress=report,
        params=params), progress, "spectrum", "periods")
    options = {"preset": preset, "config": config, "transient": transient, "periods": periods,
               "samples_per_period": samples_per_period, "whirl": whirl, "max_work": max_work}
    return Spectrum(order=r["order"], x=r.get("x"), y=r.get("y"), whirl=r.get("whirl"),
                    problem=Problem._of(r["problem"], "spectrum", options))


from ._sweeps import grid_points, sweep, sweep_grid  # noqa: E402
from ._runup import runup  # noqa: E402
from ._stepper import Stepper  # noqa: E402
from ._orbits import Bifurcation, Branch, Continuation, Orbit, continuation, orbit  # noqa: E402


def _parameter_section() -> str:
    lines = ["", "    Model parameters (keywords; ``rotor-rub params``)",
             "    -------------------------------------------------"]
    for p in parameters():
        lines.append(f"    {p.name} ({p.symbol}), default {p.default:g}, in {p.range}")
        lines.append(f"        {p.doc}")
    return "\n".join(lines) + "\n"


for _function in (simulate, poincare, spectrum, sweep, sweep_grid, runup, orbit, continuation):
    _function.__doc__ = (_function.__doc__ or "").rstrip() + "\n" + _parameter_section()
