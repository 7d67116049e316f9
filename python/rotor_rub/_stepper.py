"""The fixed-step :class:`Stepper`: the compiled core's with typed results, its state saved and
set back (``Stepper.state``), pickling and copying."""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

from . import _core, _progress
from ._core import StepperState
from .results import Count, Events, Problem, Real, Samples, Steps


class Stepper(_core.Stepper):
    """Fixed-step propagation (the C ABI's stepper) for loops in Python or HIL-style use: exact
    free flight, contact sub-steps, every switch inside a step located.

    ``Stepper(preset="paper", dt=1e-3, speed_ratio=2.0)``: a preset, a TOML ``config``, the step
    ``dt`` Φ(dt) is precomputed for, the ``contact_scheme`` (exprb43 or exprb2),
    ``contact_substeps`` per step and the cap ``max_substeps``, and model parameters as keywords.

    ``step(dt=None)`` advances one step and returns ``(time, state, regime, events)``;
    ``run(steps, dt=None, progress=None)`` takes many steps in Rust (GIL released, Ctrl-C
    checked) and returns :class:`Steps`; ``set_params(**params)`` changes parameters between
    steps (the start values x0, y0, vx0, vy0 and the phase only before the first step, as in the
    FMU), ``set_input_force(fx, fy)`` the external force (held until the next call) and
    ``set_speed_ratio(eta)`` the speed with a continuous phase; ``time``, ``regime`` and ``dt``
    read the current values.

    ``state`` is the full internal state (a :class:`StepperState`: time, x, y, vx, vy, regime,
    parameters, slip and forcing phase): ``saved = stepper.state`` … ``stepper.state = saved``
    and the stepper repeats its run bit for bit (what shooting, checkpoints and ensembles need;
    the FMU's get/set state). A state reads as (x, y, vx, vy) when indexed. Steppers pickle
    (their state, as checked bytes) and copy (``copy.copy``, ``copy.deepcopy``): a copy steps
    on independently and identically.
    """

    def run(self, steps: Count, dt: Optional[Real] = None,  # type: ignore[override]
            progress: Any = None) -> Steps:
        """Take ``steps`` steps of ``dt`` (default: the configured step) in Rust. The arrays'
        size is checked against memory first (a ValueError naming the count and the limit)."""
        r = _progress.run(lambda report: super(Stepper, self).run(steps, dt, report),
                          progress, "steps", "steps")
        return Steps(
            samples=Samples(r["time"], r["state"], r["regime"]),
            events=Events(r["event_time"], r["event_kind"], r["event_state"]),
            problem=Problem._of(self._problem(), "Stepper.run", {"steps": int(steps)}),
        )

    def __reduce__(self) -> Tuple[Any, Tuple[StepperState]]:
        return (_restored, (self.state,))

    def __copy__(self) -> "Stepper":
        return _restored(self.state)

    def __deepcopy__(self, memo: Dict[int, Any]) -> "Stepper":
        return _restored(self.state)


def _restored(state: StepperState) -> Stepper:
    """A stepper set to ``state`` (pickle's and copy's constructor)."""
    stepper = Stepper()
    stepper.state = state
    return stepper
