"""The results of rotor_rub's calls: dataclasses of numpy arrays."""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass
from typing import Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core

#: Event kinds, as in the CLI's events CSV: enter, exit, reverse, roll, slip.
EVENT_KINDS: Tuple[str, ...] = tuple(_core.EVENT_KINDS)
#: Regimes, as in the CLI's samples CSV: free, contact, rolling.
REGIMES: Tuple[str, ...] = tuple(_core.REGIMES)

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
StrArray = npt.NDArray[np.str_]
PathLike = Union[str, "os.PathLike[str]"]





_KIND_NAMES = np.array(EVENT_KINDS)
_REGIME_NAMES = np.array(REGIMES)


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
class Run:
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
    method: str
    elapsed: float


@dataclass
class Section:
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
    method: str


@dataclass
class Spectrum:
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
    method: str


@dataclass
class Sweep:
    """The result of :func:`sweep` or :func:`sweep_grid`: Poincaré points over parameter values.

    One row per (point, kept period), ordered by point (in the order given) then period:
    ``values`` (n, k) the swept parameters' values (columns in the order of ``params``),
    ``period`` (n,), ``state`` (n, 4). ``skipped`` lists the points left out with
    ``skip_errors`` and why.
    """

    params: Tuple[str, ...]
    values: FloatArray
    period: IntArray
    state: FloatArray
    skipped: Tuple[str, ...]

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
class Steps:
    """What :meth:`Stepper.run` returns: the state after each step (``samples``: time, state,
    regime) and every switch on the way (``events``)."""

    samples: Samples
    events: Events
