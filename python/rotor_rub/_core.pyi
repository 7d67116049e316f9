"""Type stubs of the compiled core (python/src/*.rs). The public API is rotor_rub/__init__.py."""

from os import PathLike
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Tuple, Union, final

import numpy as np
import numpy.typing as npt
from typing_extensions import disjoint_base

__all__ = [
    "EVENT_KINDS",
    "PropagationError",
    "REGIMES",
    "SPEED_DIRECTIONS",
    "Stepper",
    "StepperState",
    "VERSION",
    "WHIRL_DIRECTIONS",
    "matrix_check",
    "matrix_load",
    "matrix_modes",
    "matrix_result_of",
    "continuation",
    "orbit",
    "parameters",
    "poincare",
    "presets",
    "runup",
    "rust_simulate_seconds",
    "simulate",
    "simulate_matrix",
    "spectrum",
    "sweep_points",
]

EVENT_KINDS: List[str]
REGIMES: List[str]
SPEED_DIRECTIONS: List[str]
WHIRL_DIRECTIONS: List[str]
VERSION: str

class PropagationError(RuntimeError): ...

_Config = Optional[Union[str, "PathLike[str]"]]
_Real = Union[float, int, np.floating[Any], np.integer[Any]]
_Count = Union[int, np.integer[Any]]
_Flag = Union[bool, np.bool_]
_Report = Optional[Callable[[float, float], None]]

def parameters() -> List[Dict[str, Any]]: ...
def presets() -> Dict[str, Tuple[str, Dict[str, float]]]: ...
def simulate(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    t_end: Optional[_Real] = None,
    periods: Optional[_Real] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    samples: Optional[_Count] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]: ...
def poincare(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    transient: Optional[_Count] = None,
    keep: Optional[_Count] = None,
    lyapunov: Optional[_Flag] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]: ...
def spectrum(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    transient: Optional[_Count] = None,
    periods: Optional[_Count] = None,
    samples_per_period: Optional[_Count] = None,
    whirl: Optional[_Flag] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]: ...
def sweep_points(
    names: List[str],
    points: npt.NDArray[np.float64],
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    transient: Optional[_Count] = None,
    keep: Optional[_Count] = None,
    lyapunov: Optional[_Flag] = None,
    line: Optional[_Count] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    skip_errors: Optional[_Flag] = None,
    threads: Optional[_Count] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]: ...
def runup(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    from_speed: Optional[_Real] = None,
    to_speed: Optional[_Real] = None,
    rate: Optional[_Real] = None,
    ramp_periods: Optional[_Real] = None,
    settle: Optional[_Real] = None,
    dwell: Optional[_Real] = None,
    one_way: Optional[_Flag] = None,
    profile: Optional[npt.NDArray[np.float64]] = None,
    profile_path: Optional[str] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    speed_holds: Optional[_Count] = None,
    samples_per_period: Optional[_Count] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]: ...
def orbit(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    period: Optional[_Count] = None,
    guess: Any = None,
    transient: Optional[_Count] = None,
    newton_tol: Optional[_Real] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]:
    """One periodic orbit by shooting: state, period, multipliers (re, im), stability."""
def continuation(
    param: Any,
    start: Any,
    stop: Any,
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    period: Optional[_Count] = None,
    guess: Any = None,
    transient: Optional[_Count] = None,
    max_period: Optional[_Count] = None,
    max_points: Optional[_Count] = None,
    newton_tol: Optional[_Real] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    max_work: Optional[_Real] = None,
    progress: _Report = None,
    params: Optional[Mapping[str, _Real]] = None,
) -> Dict[str, Any]:
    """Branches of periodic orbits over a parameter, bifurcations located."""
def rust_simulate_seconds(
    repeats: int,
    rounds: int,
    *,
    preset: Optional[str] = None,
    periods: float = 20.0,
    method: Optional[str] = None,
    samples: int = 1001,
    params: Optional[Mapping[str, float]] = None,
) -> float:
    """Seconds per call of the Rust pipeline behind ``simulate`` (scripts/bench_python.py)."""

_Event = Tuple[float, str, List[float]]

@final
class StepperState:
    """The stepper's full internal state; reads as (x, y, vx, vy) when indexed."""

    def to_bytes(self) -> bytes: ...
    @staticmethod
    def from_bytes(data: bytes) -> "StepperState": ...
    def __reduce__(self) -> Tuple[Any, ...]: ...
    @property
    def time(self) -> float: ...
    @property
    def vector(self) -> List[float]: ...
    @property
    def regime(self) -> str: ...
    @property
    def params(self) -> Dict[str, float]: ...
    def __len__(self) -> int: ...
    def __getitem__(self, key: int, /) -> float: ...
    def __iter__(self) -> Iterator[float]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@disjoint_base
class Stepper:
    """Fixed-step propagation (the C ABI's stepper): exact free flight, contact sub-steps,
    switches located inside each step.

    ``Stepper(preset="paper", dt=1e-3, speed_ratio=2.0)``; parameters as keywords.
    """

    def __new__(
        cls,
        *,
        preset: Optional[str] = None,
        config: _Config = None,
        dt: Optional[_Real] = None,
        contact_scheme: Optional[str] = None,
        contact_substeps: Optional[_Count] = None,
        max_substeps: Optional[_Count] = None,
        **params: _Real,
    ) -> "Stepper": ...
    def step(self, dt: Optional[_Real] = None) -> Tuple[float, List[float], str, List[_Event]]:
        """Advance one step; returns (time, state, regime, events)."""
    def run(
        self, steps: _Count, dt: Optional[_Real] = None, progress: _Report = None
    ) -> Dict[str, Any]:
        """Take ``steps`` steps with the GIL released: time, state, regime per step and every
        switch (event_time, event_kind, event_state), as numpy arrays."""
    def set_params(self, **params: _Real) -> None:
        """Change parameters between steps; state and time are kept."""
    def set_input_force(self, fx: _Real, fy: _Real) -> None:
        """Apply the external force (fx, fy) from now on, held until the next call."""
    def set_speed_ratio(self, speed_ratio: _Real) -> None:
        """Change the speed ratio from now on, the forcing phase kept continuous."""
    def _problem(self) -> Dict[str, Any]: ...
    @property
    def state(self) -> StepperState: ...
    @state.setter
    def state(self, state: StepperState) -> None: ...
    @property
    def time(self) -> float: ...
    @property
    def regime(self) -> str: ...
    @property
    def dt(self) -> float: ...
    @property
    def contact_substeps(self) -> int: ...
    @property
    def largest_resolved_dt(self) -> float: ...

# Rotors from matrices (python/src/matrix.rs): the model as rotor_rub.Model._core_dict() gives it.
def matrix_check(model: Mapping[str, Any]) -> None: ...
def matrix_modes(model: Mapping[str, Any]) -> npt.NDArray[np.complex128]: ...
def matrix_load(path: str) -> Dict[str, Any]: ...
def matrix_result_of(
    model: Mapping[str, Any],
    events: List[Tuple[float, int, List[float]]],
    samples: List[Tuple[float, int, List[float]]],
) -> Dict[str, Any]: ...
def simulate_matrix(
    model: Mapping[str, Any],
    *,
    t_end: Optional[_Real] = None,
    periods: Optional[_Real] = None,
    method: Optional[str] = None,
    tol: Optional[_Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[_Real] = None,
    samples: Optional[_Count] = None,
    initial: Optional[List[float]] = None,
) -> Dict[str, Any]: ...
