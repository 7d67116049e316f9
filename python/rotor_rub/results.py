"""The results of rotor_rub's calls: dataclasses of numpy arrays, each carrying the
:class:`Problem` it came from. Every result converts with ``.to_pandas()`` / ``.to_xarray()``
and saves with ``.save(path)`` (Parquet or NetCDF, metadata included; :func:`rotor_rub.load`
reads it back): see :mod:`rotor_rub._io`."""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core
from ._io import Result

#: Event kinds, as in the CLI's events CSV: enter, exit, reverse, roll, slip.
EVENT_KINDS: Tuple[str, ...] = tuple(_core.EVENT_KINDS)
#: Regimes, as in the CLI's samples CSV: free, contact, rolling.
REGIMES: Tuple[str, ...] = tuple(_core.REGIMES)
#: Which way the speed went over a forcing period of a run-up: up, down, hold.
SPEED_DIRECTIONS: Tuple[str, ...] = tuple(_core.SPEED_DIRECTIONS)
#: Which way the orbit turned over a forcing period: forward, backward, mixed.
WHIRL_DIRECTIONS: Tuple[str, ...] = tuple(_core.WHIRL_DIRECTIONS)

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
StrArray = npt.NDArray[np.str_]
PathLike = Union[str, "os.PathLike[str]"]
#: A real number as the calls take it: a Python or numpy scalar.
Real = Union[float, int, np.floating[Any], np.integer[Any]]
#: A count: a Python or numpy integer.
Count = Union[int, np.integer[Any]]
#: Values of a swept parameter: a sequence or a 1-D array of floats or integers.
Values = Union[Sequence[Real], npt.NDArray[np.floating[Any]], npt.NDArray[np.integer[Any]]]

_KIND_NAMES = np.array(EVENT_KINDS)
_REGIME_NAMES = np.array(REGIMES)


@dataclass(frozen=True)
class Problem:
    """What a result was computed from: every model parameter's value (``params``, the start
    state included), the method with the tolerance in force (``tol``: the method's default when
    none was given), contact scheme and step, the call (``call``) and its own settings
    (``options``: run length, samples, transient, swept names, …), and the rotor_rub
    ``version``."""

    params: Mapping[str, float]
    method: str
    tol: Optional[float]
    contact_scheme: Optional[str]
    step: Optional[float]
    method_text: str
    version: str
    call: str = ""
    options: Mapping[str, Any] = field(default_factory=dict)

    @property
    def offset(self) -> Tuple[float, float]:
        """The stator centre (``offset_x``, ``offset_y``), in clearances."""
        return (float(self.params.get("offset_x", 0.0)), float(self.params.get("offset_y", 0.0)))

    def to_dict(self) -> Dict[str, Any]:
        """A JSON-ready dict (what saved files carry)."""
        return {"params": dict(self.params), "method": self.method, "tol": self.tol,
                "contact_scheme": self.contact_scheme, "step": self.step,
                "method_text": self.method_text, "version": self.version, "call": self.call,
                "options": {k: _plain(v) for k, v in self.options.items()}}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Problem":
        tol = d.get("tol")
        return cls(params=dict(d["params"]), method=d["method"],
                   tol=None if tol is None else float(tol),
                   contact_scheme=d.get("contact_scheme"), step=d.get("step"),
                   method_text=d["method_text"], version=d["version"], call=d.get("call", ""),
                   options=dict(d.get("options", {})))

    @classmethod
    def _of(cls, core: Mapping[str, Any], call: str, options: Mapping[str, Any]) -> "Problem":
        """The problem the compiled core reports (its dict is the problem's own)."""
        return cls(core["params"], core["method"], core["tol"], core["contact_scheme"],
                   core["step"], core["method_text"], core["version"], call, options)


def _plain(value: Any) -> Any:
    """An option's value as JSON takes it (numpy scalars as Python numbers, paths as text)."""
    if isinstance(value, np.generic):
        return value.item()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return repr(value)


@dataclass
class Events:
    """Every switch of a run, in time order.

    ``time`` (n,), ``kind`` (n,) strings of :data:`EVENT_KINDS`, ``state`` (n, 4): x, y, vx, vy
    at the switch. ``kind_code`` holds the kinds as indices into :data:`EVENT_KINDS` (uint8);
    ``kind`` is made from it on first access.
    """

    time: FloatArray
    kind_code: npt.NDArray[np.uint8]
    state: FloatArray

    @functools.cached_property
    def kind(self) -> StrArray:
        return _KIND_NAMES[self.kind_code]

    def __len__(self) -> int:
        return int(self.time.shape[0])


@dataclass
class Samples:
    """Uniform samples of a run: ``time`` (m,), ``state`` (m, 4), ``regime`` (m,) strings of
    :data:`REGIMES` (made on first access from ``regime_code``, uint8 indices into
    :data:`REGIMES`), ``contact`` (m,) booleans (contact or rolling)."""

    time: FloatArray
    state: FloatArray
    regime_code: npt.NDArray[np.uint8]

    @functools.cached_property
    def regime(self) -> StrArray:
        return _REGIME_NAMES[self.regime_code]

    @property
    def contact(self) -> npt.NDArray[np.bool_]:
        contact: npt.NDArray[np.bool_] = self.regime_code != 0
        return contact

    def __len__(self) -> int:
        return int(self.time.shape[0])


@dataclass
class Run(Result):
    """The result of :func:`simulate`.

    ``events`` and ``samples`` hold the arrays; ``end_state`` is the state at ``end_time``;
    ``time_free``, ``time_contact`` (slipping or frictionless contact) and ``time_rolling`` add up
    to the run length; ``elapsed`` is the propagation time in seconds (Rust side, GIL released).
    """

    events: Events
    samples: Samples
    start_time: float
    end_time: float
    end_state: FloatArray
    time_free: float
    time_contact: float
    time_rolling: float
    contact_fraction: float
    forcing_period: float
    elapsed: float
    problem: Problem

    @property
    def method(self) -> str:
        """The method and its settings, e.g. ``hybrid (tol 1e-10)``."""
        return self.problem.method_text


@dataclass
class Section(Result):
    """The result of :func:`poincare`: the state at each kept forcing-period boundary.

    ``period`` (n,) forcing-period indices, ``state`` (n, 4); ``response`` the class
    (``period-2``, ``chaotic``, ...); ``lyapunov`` the largest Lyapunov exponent per unit τ when
    asked for; ``distinct`` the number of distinct points.
    """

    period: IntArray
    state: FloatArray
    response: str
    lyapunov: Optional[float]
    distinct: int
    problem: Problem

    @property
    def method(self) -> str:
        return self.problem.method_text


@dataclass
class Spectrum(Result):
    """The result of :func:`spectrum`: amplitudes (in clearances) against ``order``, frequency in
    multiples of the running speed.

    Without ``whirl``: ``x`` and ``y`` one-sided spectra, ``whirl`` is None. With ``whirl``: the
    two-sided spectrum of x + i y (positive orders forward whirl, negative backward), ``x`` and
    ``y`` are None.
    """

    order: FloatArray
    x: Optional[FloatArray]
    y: Optional[FloatArray]
    whirl: Optional[FloatArray]
    problem: Problem

    @property
    def method(self) -> str:
        return self.problem.method_text


@dataclass
class Sweep(Result):
    """The result of :func:`sweep` or :func:`sweep_grid`: Poincaré points over parameter values.

    One row per (point, kept period), ordered by point (in the order given) then period:
    ``values`` (n, k) the swept parameters' values (columns in the order of ``params``),
    ``period`` (n,), ``state`` (n, 4), ``point`` (n,) the row's point (an index into
    ``points``). Per point: ``points`` (p, k) its values, ``response`` (p,) its response class
    (``period-1``, ``chaotic``, …; ``failed`` for a point left out with ``skip_errors``) and,
    when asked for, ``lyapunov`` (p,) the largest Lyapunov exponent (NaN where failed).
    ``skipped`` lists the points left out and why.
    """

    params: Tuple[str, ...]
    values: FloatArray
    period: IntArray
    state: FloatArray
    skipped: Tuple[str, ...]
    point: IntArray
    points: FloatArray
    response: StrArray
    lyapunov: Optional[FloatArray]
    problem: Problem

    @property
    def value(self) -> FloatArray:
        """The first swept parameter's value of each row."""
        return self.values[:, 0]

    def __len__(self) -> int:
        return int(self.period.shape[0])


@dataclass
class Parameter:
    """One entry of the parameter table."""

    name: str
    symbol: str
    default: float
    min: float
    max: float
    min_open: bool
    range: str
    doc: str


@dataclass
class Steps(Result):
    """What :meth:`Stepper.run` returns: the state after each step (``samples``: time, state,
    regime) and every switch on the way (``events``)."""

    samples: Samples
    events: Events
    problem: Problem


@dataclass
class RunupEvents(Events):
    """Every switch of a run-up: as :class:`Events`, plus ``speed`` (η at the switch),
    ``period`` (the forcing period it falls in) and ``direction`` (up, down, hold)."""

    speed: FloatArray = field(default_factory=lambda: np.empty(0))
    period: IntArray = field(default_factory=lambda: np.empty(0, np.int64))
    direction: StrArray = field(default_factory=lambda: np.empty(0, np.str_))


@dataclass(frozen=True)
class Jump:
    """A jump of a run-up branch's largest radius: at ``speed`` going ``direction`` (up: the
    run-up, down: the coast-down), from ``before`` to ``after`` (clearances), in forcing period
    ``period``."""

    speed: float
    direction: str
    before: float
    after: float
    period: int


@dataclass
class Runup(Result):
    """The result of :func:`runup`, one entry per forcing period (the rows of ``rotor-rub
    runup``'s CSV): ``direction`` (up, down, hold), ``period``, ``start``, ``end``, ``speed``
    (mean speed ratio), ``speed_change``, ``max_radius`` and ``min_radius`` (|q|, clearances),
    ``contact_fraction``, ``whirl`` (+1 one forward circle) and ``whirl_direction``, ``enters``,
    ``exits``; ``events`` every switch with its speed (those after the last whole forcing
    period too, with ``period`` = the number of rows); ``jumps`` each branch's jumps; ``program``
    the speed program; ``elapsed`` the run time in seconds."""

    direction: StrArray
    period: IntArray
    start: FloatArray
    end: FloatArray
    speed: FloatArray
    speed_change: FloatArray
    max_radius: FloatArray
    min_radius: FloatArray
    contact_fraction: FloatArray
    whirl: FloatArray
    whirl_direction: StrArray
    enters: IntArray
    exits: IntArray
    events: RunupEvents
    jumps: Tuple[Jump, ...]
    program: str
    elapsed: float
    problem: Problem

    @property
    def method(self) -> str:
        return self.problem.method_text

    def __len__(self) -> int:
        return int(self.period.shape[0])
