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
    assert list(a.state) == a.state.vector == out.samples.state[-1].tolist()
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
    assert stepper.time == time and stepper.state.vector == state.vector
    assert stepper.state != state  # the parameters are part of the full state
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


def test_state_restores_and_repeats_bit_for_bit() -> None:
    """Stepper.state is the full internal state: set back, the stepper repeats its run bit for
    bit (through contact: the paper preset rubs at η = 2.5); a copy and a pickled stepper step
    on identically, independently of the original."""
    import copy
    import pickle

    stepper = rr.Stepper(dt=1e-2, speed_ratio=2.5)
    stepper.run(300)
    saved = stepper.state
    assert isinstance(saved, rr.StepperState)
    assert saved.time == stepper.time and saved.regime == stepper.regime
    first = stepper.run(2000)
    assert len(first.events) > 0
    stepper.state = saved
    again = stepper.run(2000)
    assert again.samples.state.tobytes() == first.samples.state.tobytes()
    assert again.events.time.tobytes() == first.events.time.tobytes()
    stepper.state = saved
    for other in (copy.copy(stepper), copy.deepcopy(stepper), pickle.loads(pickle.dumps(stepper))):
        assert isinstance(other, rr.Stepper) and other.state == saved
        out = other.run(2000)
        assert out.samples.state.tobytes() == first.samples.state.tobytes()
    assert stepper.state == saved  # the copies did not move the original
    # The state's bytes round-trip and are checked.
    data = saved.to_bytes()
    assert rr.StepperState.from_bytes(data) == saved
    assert pickle.loads(pickle.dumps(saved)) == saved and hash(saved) == hash(
        rr.StepperState.from_bytes(data))
    import pytest

    with pytest.raises(ValueError, match="not a StepperState"):
        stepper.state = [0.1, 0.1, 0.0, 0.0]  # type: ignore[assignment]
    for bad in (data[:-1], data[:20], b"nonsense" * 10,
                data[:40] + bytes([data[40] ^ 1]) + data[41:]):
        with pytest.raises(ValueError, match="StepperState"):
            rr.StepperState.from_bytes(bad)


def test_start_values_are_fixed_once_stepped() -> None:
    """As the FMU: x0, y0, vx0, vy0 and the phase may change before the first step (the stepper
    starts from them), not after (ValueError, nothing changed)."""
    import pytest

    fresh = rr.Stepper(dt=1e-3)
    fresh.set_params(x0=0.5, phase=0.3)
    same = rr.Stepper(dt=1e-3, x0=0.5, phase=0.3)
    assert fresh.state == same.state
    assert fresh.run(500).samples.state.tobytes() == same.run(500).samples.state.tobytes()
    before = fresh.state
    for name in ("x0", "y0", "vx0", "vy0", "phase"):
        with pytest.raises(ValueError, match=f"{name}: the start values"):
            fresh.set_params(**{name: 0.25})
    assert fresh.state == before
    restored = rr.Stepper()
    restored.state = before
    with pytest.raises(ValueError, match="x0"):
        restored.set_params(x0=0.0)
    fresh.set_params(damping_ratio=0.1)  # a model parameter still changes
    assert fresh.state.params["damping_ratio"] == 0.1


def test_a_stiff_stator_is_sub_stepped_as_dop853_finds_it() -> None:
    """A stator 30× stiffer than dry-whip's at dt = 1e-2: the stepper takes the contact
    sub-steps the contact mode needs (more than the configured 1) and finds DOP853's switches;
    `largest_resolved_dt` tells how long a step the configured cap resolves."""
    stiff = {"k_xx": 1e4, "k_yy": 1e4}
    stepper = rr.Stepper(preset="dry-whip", dt=1e-2, **stiff)
    k = stepper.contact_substeps
    assert k > 1
    # Each of the k sub-steps is at most 0.5/ρ_c, so the default cap of 8 resolves 8·dt/k.
    assert 8 * 1e-2 / k <= stepper.largest_resolved_dt < 8 * 1e-2 / (k - 1)
    assert rr.Stepper(preset="dry-whip", dt=1e-2).contact_substeps == 1
    out = stepper.run(2000)
    reference = rr.simulate(preset="dry-whip", method="dop853", tol=1e-12,
                            t_end=float(out.samples.time[-1]), samples=0, **stiff)
    assert list(out.events.kind) == list(reference.events.kind)
    assert np.max(np.abs(out.events.time - reference.events.time)) < 1e-6
