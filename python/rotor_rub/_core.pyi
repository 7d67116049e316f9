"""Type stubs of the compiled core (python/src/*.rs). The public API is rotor_rub/__init__.py."""

from os import PathLike
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import disjoint_base

__all__ = [
    "EVENT_KINDS",
    "PropagationError",
    "REGIMES",
    "Stepper",
    "VERSION",
    "parameters",
    "poincare",
    "presets",
    "rust_simulate_seconds",
    "simulate",
    "spectrum",
    "sweep_points",
]

EVENT_KINDS: List[str]
REGIMES: List[str]
VERSION: str

class PropagationError(RuntimeError): ...

_Config = Optional[Union[str, "PathLike[str]"]]

def parameters() -> List[Dict[str, Any]]: ...
def presets() -> Dict[str, Tuple[str, Dict[str, float]]]: ...
def simulate(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    t_end: Optional[float] = None,
    periods: Optional[float] = None,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    samples: int = 1001,
    max_work: Optional[float] = None,
    params: Optional[Mapping[str, float]] = None,
) -> Dict[str, Any]: ...
def poincare(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    transient: int = 200,
    keep: int = 100,
    lyapunov: bool = False,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    max_work: Optional[float] = None,
    params: Optional[Mapping[str, float]] = None,
) -> Dict[str, Any]: ...
def spectrum(
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    transient: int = 100,
    periods: int = 60,
    samples_per_period: int = 64,
    whirl: bool = False,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    max_work: Optional[float] = None,
    params: Optional[Mapping[str, float]] = None,
) -> Dict[str, Any]: ...
def sweep_points(
    names: List[str],
    points: npt.NDArray[np.float64],
    *,
    preset: Optional[str] = None,
    config: _Config = None,
    transient: int = 200,
    keep: int = 50,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    skip_errors: bool = False,
    threads: Optional[int] = None,
    max_work: Optional[float] = None,
    params: Optional[Mapping[str, float]] = None,
) -> Dict[str, Any]: ...

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
        dt: float = 1e-3,
        contact_scheme: Optional[str] = None,
        contact_substeps: int = 1,
        max_substeps: int = 8,
        **params: float,
    ) -> "Stepper": ...
    def step(self, dt: Optional[float] = None) -> Tuple[float, List[float], str, List[_Event]]:
        """Advance one step; returns (time, state, regime, events)."""
    def run(self, steps: int, dt: Optional[float] = None) -> Dict[str, Any]:
        """Take ``steps`` steps with the GIL released: time, state, regime per step and every
        switch (event_time, event_kind, event_state), as numpy arrays."""
    def set_params(self, **params: float) -> None:
        """Change parameters between steps; state and time are kept."""
    def set_input_force(self, fx: float, fy: float) -> None:
        """Apply the external force (fx, fy) from now on, held until the next call."""
    def set_speed_ratio(self, speed_ratio: float) -> None:
        """Change the speed ratio from now on, the forcing phase kept continuous."""
    @property
    def time(self) -> float: ...
    @property
    def state(self) -> List[float]: ...
    @property
    def regime(self) -> str: ...
    @property
    def dt(self) -> float: ...
