"""Run-up and coast-down from Python: :func:`runup`, the CLI's ``rotor-rub runup`` programs."""

from __future__ import annotations

import os
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

from . import _core, _progress
from .results import (
    SPEED_DIRECTIONS,
    WHIRL_DIRECTIONS,
    Count,
    Jump,
    PathLike,
    Problem,
    Real,
    Runup,
    RunupEvents,
)

_DIRECTIONS = np.array(SPEED_DIRECTIONS)
_WHIRLS = np.array(WHIRL_DIRECTIONS)

#: A speed profile: rows (τ, η) as an (n, 2) array, or a CSV file of rows time,speed_ratio.
Profile = Union[PathLike, npt.ArrayLike]


def runup(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    from_speed: Optional[Real] = None,
    to_speed: Optional[Real] = None,
    rate: Optional[Real] = None,
    ramp_periods: Optional[Real] = None,
    settle: Optional[Real] = None,
    dwell: Optional[Real] = None,
    one_way: Optional[bool] = None,
    profile: Optional[Profile] = None,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    speed_holds: Optional[Count] = None,
    samples_per_period: Count = 64,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Runup:
    """Run the rotor up through its critical speed and back down (or either, or along any
    speed profile), one row per forcing period: the numbers of ``rotor-rub runup``'s files, bit
    for bit, and each branch's jumps.

    Parameters
    ----------
    preset : str, optional
        A run-up program (``"paper-hysteresis"``, the default: the ``paper`` rotor from η = 0.5
        to 3.5 and back at dη/dτ = 1e-3 after 20 settling periods), or a rotor preset
        (``"paper"``, ``"friction"``, …) run on that program's ramp.
    config : path, optional
        TOML file of parameter values, as in :func:`simulate` (then the rotor is the config's).
    from_speed, to_speed : float, optional
        The ramp's start and turning speed ratios (the CLI's ``--from``, ``--to``).
    rate, ramp_periods : float, optional
        The ramp's pace: |dη/dτ| in (0, 1], or its length in forcing periods (not both).
    settle, dwell : float, optional
        Forcing periods held at ``from_speed`` before the ramp, and at ``to_speed`` before
        running back.
    one_way : bool, optional
        Stop at ``to_speed`` (a run-up alone; a coast-down when ``to_speed < from_speed``).
    profile : path or (n, 2) array, optional
        A speed profile instead of the ramp: rows (τ, η), τ increasing, η linear between rows;
        a CSV file of rows time,speed_ratio (the CLI's ``--profile``) or an array.
    method, tol, contact_scheme, step : optional
        As in :func:`simulate`; default method ``taylor``.
    speed_holds : int, optional
        Held-speed steps per forcing period of the analytic method (default 32).
    samples_per_period : int
        Samples per forcing period for the radii and the whirl (>= 8, default 64).
    max_work : float, optional
        Work limit (forcing periods × samples_per_period plus switches, default 1e9).
    progress : optional
        True, a callable ``progress(done, total)`` or a tqdm-style bar, in forcing periods.
    **params : float
        Model parameters, listed below.

    Returns
    -------
    Runup
        Per forcing period ``.speed``, ``.max_radius``, ``.min_radius``, ``.contact_fraction``,
        ``.whirl`` …; ``.events`` every switch with its ``.speed``, ``.period`` and
        ``.direction``; ``.jumps`` each branch's jumps (``.speed``, ``.direction``).

    Raises
    ------
    ValueError
        Invalid input (a value out of range, a ramp option with a profile, friction with a
        changing speed) or a run over ``max_work``.
    PropagationError
        The run failed.
    """
    path: Optional[str] = None
    points: Optional[np.ndarray] = None
    if isinstance(profile, (str, os.PathLike)):
        path = os.fspath(profile)
    elif profile is not None:
        raw = np.asarray(profile)
        if raw.ndim != 2 or raw.dtype.kind not in "iuf":
            raise ValueError(f"profile: an array of (time, speed_ratio) rows of shape (n, 2), "
                             f"not {raw.dtype} of shape {raw.shape}")
        points = np.ascontiguousarray(raw, dtype=np.float64)
    r = _progress.run(lambda report: _core.runup(
        preset=preset, config=None if config is None else os.fspath(config),
        from_speed=from_speed, to_speed=to_speed, rate=rate, ramp_periods=ramp_periods,
        settle=settle, dwell=dwell, one_way=one_way, profile=points, profile_path=path,
        method=method, tol=tol, contact_scheme=contact_scheme, step=step,
        speed_holds=speed_holds, samples_per_period=samples_per_period, max_work=max_work,
        progress=report, params=params), progress, "runup", "periods")
    events = RunupEvents(r["event_time"], r["event_kind"], r["event_state"],
                         speed=r["event_speed"], period=r["event_period"].astype(np.int64),
                         direction=_DIRECTIONS[r["event_direction"]])
    jumps = tuple(Jump(speed=j["speed"], direction=j["direction"], before=j["before"],
                       after=j["after"], period=int(j["period"])) for j in r["jumps"])
    options = {"preset": preset, "config": None if config is None else os.fspath(config),
               "program": r["program"], "samples_per_period": int(samples_per_period),
               "speed_holds": int(r["speed_holds"]),
               "max_work": None if max_work is None else float(max_work)}
    return Runup(
        direction=_DIRECTIONS[r["direction"]],
        period=r["period"].astype(np.int64),
        start=r["start"],
        end=r["end"],
        speed=r["speed"],
        speed_change=r["speed_change"],
        max_radius=r["max_radius"],
        min_radius=r["min_radius"],
        contact_fraction=r["contact_fraction"],
        whirl=r["whirl"],
        whirl_direction=_WHIRLS[r["whirl_direction"]],
        enters=r["enters"].astype(np.int64),
        exits=r["exits"].astype(np.int64),
        events=events,
        jumps=jumps,
        program=r["program"],
        elapsed=r["elapsed"],
        problem=Problem._of(r["problem"], "runup", options),
    )
