"""Sweeps: :func:`sweep` over one parameter and :func:`sweep_grid` over one or two, each point's
Poincaré section with its response class (and, on request, the largest Lyapunov exponent), in
parallel in Rust; with ``continuation`` each point starts from the previous point's end state."""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple

import numpy as np

from . import _core, _progress
from .results import Count, FloatArray, PathLike, Problem, Real, Sweep, Values


def _path(config: Optional[PathLike]) -> Optional[str]:
    return None if config is None else os.fspath(config)


def grid_points(grid: Mapping[str, Values]) -> Tuple[Tuple[str, ...], FloatArray]:
    """The parameter names and the (n, k) array of points of a grid given as
    ``{name: values}`` (one or two entries; the first varies slowest). Each entry's values must
    be a 1-D sequence or array of real numbers (integers included; booleans, strings and 2-D
    arrays are refused)."""
    if not 1 <= len(grid) <= 2:
        raise ValueError(f"a grid has one or two parameters, not {len(grid)}")
    names = tuple(grid)
    axes = []
    for name in names:
        raw = np.asarray(grid[name])
        if raw.ndim != 1:
            shape = "a scalar" if raw.ndim == 0 else f"a {raw.ndim}-D array of shape {raw.shape}"
            raise ValueError(f"{name}: the values must be a 1-D sequence or array, not {shape}")
        if raw.size == 0:
            raise ValueError(f"{name}: the grid gives no values")
        if raw.dtype.kind not in "iuf":
            raise ValueError(f"{name}: the values must be real numbers, not {raw.dtype} "
                             f"(e.g. {raw.flat[0]!r})")
        axes.append(raw.astype(np.float64))
    mesh = np.meshgrid(*axes, indexing="ij")
    return names, np.stack([m.ravel() for m in mesh], axis=1)


def _sweep_points(
    names: Sequence[str],
    points: FloatArray,
    *,
    preset: Optional[str],
    config: Optional[PathLike],
    transient: Count,
    keep: Count,
    method: Optional[str],
    tol: Optional[Real],
    contact_scheme: Optional[str],
    step: Optional[Real],
    skip_errors: bool,
    threads: Optional[Count],
    max_work: Optional[Real],
    params: Mapping[str, Real],
    lyapunov: bool = False,
    line: Optional[int] = None,
    progress: Any = None,
    call: str = "sweep",
) -> Sweep:
    """The sweep at the rows of ``points`` (columns ``names``): what :func:`sweep`,
    :func:`sweep_grid` and each Dask chunk run. ``line``: points per continuation line."""
    points = np.ascontiguousarray(points, dtype=np.float64)
    if points.ndim != 2:
        raise ValueError(f"points must be a 2-D array (points × parameters), not {points.ndim}-D")
    r = _progress.run(lambda report: _core.sweep_points(
        list(names), points, preset=preset, config=_path(config), transient=transient,
        keep=keep, lyapunov=lyapunov, line=line, method=method, tol=tol,
        contact_scheme=contact_scheme, step=step, skip_errors=skip_errors, threads=threads,
        max_work=max_work, progress=report, params=dict(params)), progress, call, "points")
    index = r["index"].astype(np.intp)
    response = np.array(["failed" if x is None else x for x in r["response"]], dtype=np.str_)
    options: Dict[str, Any] = {"preset": preset, "config": _path(config),
                               "transient": int(transient), "keep": int(keep),
                               "lyapunov": bool(lyapunov), "continuation": line is not None,
                               "swept": list(names)}
    return Sweep(
        params=tuple(names),
        values=points[index].reshape(len(index), len(names)),
        period=r["period"].astype(np.int64),
        state=r["state"],
        skipped=tuple(r["skipped"]),
        point=index.astype(np.int64),
        points=points,
        response=response,
        lyapunov=r["lyapunov"],
        problem=Problem._of(r["problem"], call, options),
    )


def sweep(
    param: str,
    values: Values,
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: Count = 200,
    keep: Count = 50,
    lyapunov: bool = False,
    continuation: bool = False,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    skip_errors: bool = False,
    threads: Optional[Count] = None,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Sweep:
    """Bifurcation diagram: the Poincaré points of ``keep`` periods after ``transient`` at each
    of ``values`` of ``param``, every value from the same initial state, in parallel in Rust
    (``threads`` workers, default all cores) with the GIL released. Default method ``taylor``.
    Each point also gets its response class (``Sweep.response``) and, with ``lyapunov``, its
    largest Lyapunov exponent (``Sweep.lyapunov``; costs another ``keep`` periods per point).

    With ``continuation`` the values run in the order given, each from the previous value's last
    Poincaré state (the first from the initial state): the sweep follows one attractor through a
    hysteresis band, as a run-up does but at steady state (give the values up then down to see
    both branches). A value whose propagation fails restarts nothing: the next one starts from
    the last good state. Continuation runs the values one after another (no parallelism).

    With ``skip_errors`` values whose propagation fails are left out (listed in
    ``Sweep.skipped``, their response ``failed``). Without ``continuation`` the rows equal
    ``rotor-rub sweep``'s for the same values. ``progress`` (True, a callable
    ``progress(done, total)`` or a tqdm-style bar) counts points.
    """
    return sweep_grid(
        {param: values}, preset=preset, config=config, transient=transient, keep=keep,
        lyapunov=lyapunov, continuation=continuation, method=method, tol=tol,
        contact_scheme=contact_scheme, step=step, skip_errors=skip_errors, threads=threads,
        max_work=max_work, progress=progress, **params)


def sweep_grid(
    grid: Mapping[str, Values],
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: Count = 200,
    keep: Count = 50,
    lyapunov: bool = False,
    continuation: bool = False,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    skip_errors: bool = False,
    threads: Optional[Count] = None,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Sweep:
    """:func:`sweep` over a one- or two-parameter grid ``{name: values}`` (every combination, the
    first parameter varying slowest). With ``continuation`` each line of the last parameter's
    values runs in continuation (from the initial state at each value of the first parameter;
    the lines in parallel). :func:`rotor_rub.dask.sweep` gives the same result, bit for bit, on a
    cluster (without continuation)."""
    if not isinstance(continuation, (bool, np.bool_)):
        raise ValueError(f"continuation: {continuation!r} is not True or False")
    names, points = grid_points(grid)
    line = None
    if continuation:
        line = len(np.asarray(grid[names[-1]]))
    return _sweep_points(
        names, points, preset=preset, config=config, transient=transient, keep=keep,
        method=method, tol=tol, contact_scheme=contact_scheme, step=step,
        skip_errors=skip_errors, threads=threads, max_work=max_work, params=params,
        lyapunov=lyapunov, line=line, progress=progress,
        call="sweep" if len(names) == 1 else "sweep_grid")
