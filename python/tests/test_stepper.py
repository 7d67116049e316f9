"""The fixed-step Stepper from Python."""

from __future__ import annotations

import numpy as np

import rotor_rub as rr


def test_run_equals_a_loop_of_steps() -> None:
    a, b = rr.Stepper(dt=1e-2, speed_ratio=2.5), rr.Stepper(dt=1e-2, speed_ratio=2.5)
    out = a.run(2000)
    states, kinds = [], []
    for _ in range(2000):
        time, state, regime, events = b.step()
        states.append(state)
        kinds.extend(kind for _, kind, _ in events)
    assert np.array_equal(out.samples.state, np.array(states))
    assert list(out.events.kind) == kinds
    assert a.time == b.time and a.state == b.state and a.regime == b.regime
    assert out.samples.time[-1] == a.time
    assert out.samples.regime[-1] == a.regime


def test_matches_the_reference_method() -> None:
    """Stepper switches agree with dop853 at tol 1e-13 (the library's accuracy claim for the
    stepper at dt = 1e-3 is far tighter than the 1e-8 checked here)."""
    stepper = rr.Stepper(dt=1e-3, speed_ratio=2.5)
    period = 2 * np.pi / 2.5
    steps = int(round(5 * period / 1e-3))
    out = stepper.run(steps)
    reference = rr.simulate(method="dop853", tol=1e-13, t_end=float(out.samples.time[-1]),
                            samples=0, speed_ratio=2.5)
    assert list(out.events.kind) == list(reference.events.kind)
    assert np.max(np.abs(out.events.time - reference.events.time)) < 1e-8
    assert np.max(np.abs(out.samples.state[-1] - reference.end_state)) < 1e-8


def test_set_params_keeps_state_and_time() -> None:
    stepper = rr.Stepper(dt=1e-3)
    stepper.run(100)
    time, state = stepper.time, stepper.state
    stepper.set_params(speed_ratio=2.0)
    assert stepper.time == time and stepper.state == state
    other = rr.Stepper(dt=1e-3)
    other.run(100)
    stepper.run(500)
    other.run(500)
    assert stepper.state != other.state


def test_friction_regimes() -> None:
    stepper = rr.Stepper(preset="dry-whip", dt=1e-3)
    out = stepper.run(20000)
    assert "rolling" in set(out.samples.regime)
    assert "roll" in set(out.events.kind)


def test_input_force_and_speed_between_steps() -> None:
    """A force set between steps moves the orbit as the force parameter does from the start
    (the same closed forms); bad values raise ValueError naming them."""
    a = rr.Stepper(dt=1e-3)
    b = rr.Stepper(dt=1e-3, force_x=0.2, force_y=-0.1)
    a.set_input_force(0.2, -0.1)
    out_a, out_b = a.run(5000), b.run(5000)
    assert np.array_equal(out_a.samples.state, out_b.samples.state)
    a.set_speed_ratio(1.6)
    a.run(100)
    for bad in [(float("nan"), 0.0), (0.0, 2e3)]:
        try:
            a.set_input_force(*bad)
        except ValueError as e:
            assert "force" in str(e)
        else:
            raise AssertionError("accepted")
