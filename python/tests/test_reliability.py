"""Issue 32's Python items, each as a class: counts that size memory checked up front (5),
Ctrl-C within ~50 ms of work as KeyboardInterrupt (7), fork safety (8), values refused rather
than converted (11), messages that name keywords and estimate time (12)."""

from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
import sys
import time
from typing import Any, Callable, Dict, List

import numpy as np
import pytest

import rotor_rub as rr

HUGE = 10**12


@pytest.mark.parametrize("call", [
    lambda: rr.Stepper().run(HUGE),
    lambda: rr.simulate(samples=HUGE),
    lambda: rr.poincare(keep=HUGE),
    lambda: rr.spectrum(periods=HUGE),
    lambda: rr.spectrum(samples_per_period=HUGE),
    lambda: rr.sweep("speed_ratio", [1.5, 2.0], keep=HUGE),
    lambda: rr.runup(samples_per_period=HUGE),
], ids=["stepper", "simulate", "poincare", "spectrum-periods", "spectrum-samples", "sweep",
        "runup"])
def test_counts_that_size_memory_are_refused_up_front(call: Callable[[], Any]) -> None:
    """Item 5: a ValueError naming the count and the limit, at once (nothing allocated)."""
    started = time.perf_counter()
    with pytest.raises(ValueError) as error:
        call()
    message = str(error.value)
    import re

    assert re.search(r"\d{13,}|\de1[2-9]", message), message  # the count, in full
    assert "memory" in message or "max_work" in message, message  # and the limit
    assert time.perf_counter() - started < 1.0


BAD_VALUES: List[Dict[str, Any]] = [
    {"samples": 2**64},
    {"samples": -1},
    {"samples": 10.0},
    {"samples": True},
    {"periods": "20"},
    {"periods": [20]},
    {"t_end": np.array([1.0, 2.0])},
    {"speed_ratio": True},
    {"speed_ratio": np.bool_(True)},
    {"speed_ratio": "2"},
    {"speed_ratio": np.array([2.0])},
    {"speed_ratio": 10**400},
    {"tol": "1e-9"},
    {"max_work": True},
    {"method": 3},
]


@pytest.mark.parametrize("keywords", BAD_VALUES, ids=lambda k: f"{k}")
def test_wrong_values_are_value_errors_naming_the_keyword(keywords: Dict[str, Any]) -> None:
    """Items 11 and 12: booleans are not numbers, strings and arrays are not scalars, a count is
    an integer and a huge one is out of range — a ValueError naming the keyword, never an
    OverflowError, a TypeError from the binding or a silent conversion."""
    name = next(iter(keywords))
    with pytest.raises(ValueError, match=name) as error:
        rr.simulate(periods=1, **keywords) if name != "periods" else rr.simulate(**keywords)
    assert type(error.value) is ValueError
    if name == "samples" and keywords[name] == 2**64:
        assert "out of range" in str(error.value) and "18446744073709551615" in str(error.value)


def test_counts_and_flags_of_every_call() -> None:
    """The same rules on the other calls' counts and flags (siblings of item 12)."""
    cases: List[Callable[[], Any]] = [
        lambda: rr.poincare(transient=2.5),
        lambda: rr.poincare(keep=np.float64(3.0)),
        lambda: rr.poincare(lyapunov="yes"),  # type: ignore[arg-type]
        lambda: rr.spectrum(whirl=1),  # type: ignore[arg-type]
        lambda: rr.sweep("speed_ratio", [2.0], threads=0),
        lambda: rr.sweep("speed_ratio", [2.0], skip_errors="no"),  # type: ignore[arg-type]
        lambda: rr.sweep("speed_ratio", [2.0], continuation=1),  # type: ignore[arg-type]
        lambda: rr.Stepper(dt="1e-3"),  # type: ignore[arg-type]
        lambda: rr.Stepper(max_substeps=2**40),
        lambda: rr.Stepper().run(-1),
        lambda: rr.Stepper().set_input_force(True, 0.0),  # type: ignore[arg-type]
        lambda: rr.runup(one_way="yes"),  # type: ignore[arg-type]
        lambda: rr.runup(samples_per_period=4),
    ]
    for call in cases:
        with pytest.raises(ValueError):
            call()


def test_swept_values_must_be_one_dimensional_numbers() -> None:
    """Item 11: a 2-D value array is refused, not flattened; so are booleans and strings."""
    for values in (np.array([[1.0, 2.0], [2.5, 3.0]]), np.array([True, False]), ["1.5", "2"],
                   2.0):
        with pytest.raises(ValueError, match="speed_ratio"):
            rr.sweep("speed_ratio", values, transient=1, keep=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="damping_ratio"):
        rr.sweep_grid({"speed_ratio": [1.5], "damping_ratio": np.ones((2, 2))})


def test_numpy_scalars_and_integer_arrays_are_numbers() -> None:
    """Issue 33 item 5: np.int64, np.float32 and integer arrays are accepted, with the same
    results as the Python numbers they stand for."""
    a = rr.simulate(periods=np.int64(3), samples=np.int64(11), speed_ratio=np.float32(2.5),
                    method="hybrid", tol=np.float64(1e-9))
    b = rr.simulate(periods=3, samples=11, speed_ratio=float(np.float32(2.5)), method="hybrid",
                    tol=1e-9)
    assert a.samples.state.tobytes() == b.samples.state.tobytes()
    s = rr.sweep("speed_ratio", np.arange(1, 4), transient=np.int64(5), keep=np.uint8(2))
    t = rr.sweep("speed_ratio", [1.0, 2.0, 3.0], transient=5, keep=2)
    assert s.state.tobytes() == t.state.tobytes()
    p = rr.poincare(transient=np.int32(5), keep=np.int16(4), lyapunov=np.bool_(False))
    assert len(p.period) == 4
    stepper = rr.Stepper(dt=np.float32(0.5), max_substeps=np.int64(8))
    stepper.run(np.int64(3), dt=np.float64(1e-3))
    stepper.set_params(speed_ratio=np.int64(2))
    assert stepper.state.params["speed_ratio"] == 2.0


def test_switch_rate_refusal_names_keywords_and_estimates_time() -> None:
    """Item 12: the refusal names max_work (not --max-work), gives a time estimate from the
    measured rate (not "hours to days" for a run of a second) and is the documented error."""
    started = time.perf_counter()
    with pytest.raises(ValueError) as error:
        rr.simulate(periods=1e5, method="hybrid", speed_ratio=2.5, samples=0, max_work=1e5)
    message = str(error.value)
    assert time.perf_counter() - started < 5
    assert "--" not in message and "max_work 100000" in message, message
    assert "hours to days" not in message and "would locate about" in message, message
    assert " of work)" in message and ("ms of work" in message or " s of work" in message), message
    doc = rr.simulate.__doc__ or ""
    assert "max_work" in doc.split("Raises")[1].split("PropagationError")[0]


def test_other_messages_name_keywords() -> None:
    """Siblings of item 12: every CLI flag in a message reads as the keyword."""
    for call, keyword in [
        (lambda: rr.simulate(method="hybrid", step=0.01), "step applies only to method"),
        (lambda: rr.poincare(transient=2**64 - 1, keep=5), "transient"),
        (lambda: rr.spectrum(periods=2**40, samples_per_period=2**40), "samples_per_period"),
        (lambda: rr.runup(method="hybrid", speed_holds=4), "speed_holds applies only"),
    ]:
        with pytest.raises(ValueError) as error:
            call()
        assert keyword in str(error.value) and "--" not in str(error.value), str(error.value)


INTERRUPTED = """
import sys, time, numpy as np, rotor_rub as rr
calls = {
    "simulate": lambda: rr.simulate(periods=1e7, method="dop853", speed_ratio=2.0, samples=0,
                                    max_work=1e15, k_xx=0, k_yy=0, k_xy=0, k_yx=0, offset_x=0,
                                    offset_y=0, eccentricity_ratio=1),
    "poincare": lambda: rr.poincare(transient=10**7, keep=10, method="rk45", speed_ratio=2.0,
                                    max_work=1e15),
    "lyapunov": lambda: rr.poincare(transient=0, keep=10**6, lyapunov=True, method="rk45",
                                    speed_ratio=2.0, max_work=1e15),
    "sweep": lambda: rr.sweep("speed_ratio", np.linspace(1.5, 3, 8), transient=10**6, keep=2,
                              method="dop853", max_work=1e15),
    "stepper": lambda: rr.Stepper(dt=1e-3, speed_ratio=2.5).run(5 * 10**7),
    "runup": lambda: rr.runup(from_speed=0.5, to_speed=3.5, rate=1e-5, method="dop853",
                              max_work=1e15),
}
print("started", flush=True)
calls[sys.argv[1]]()
"""


@pytest.mark.parametrize("call", ["simulate", "poincare", "lyapunov", "sweep", "stepper",
                                  "runup"])
def test_ctrl_c_raises_keyboard_interrupt_at_once(call: str, tmp_path: Any) -> None:
    """Item 7: SIGINT during a long call (switch-free DOP853 flight, a long transient, a
    Lyapunov estimate, a sweep on Rust threads, a stepper run, a run-up) ends it within about a
    second with KeyboardInterrupt — in a fresh process too, never a PanicException."""
    script = tmp_path / "long.py"
    script.write_text(INTERRUPTED)
    child = subprocess.Popen([sys.executable, str(script), call], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout is not None
        assert child.stdout.readline().strip() == "started"
        time.sleep(0.7)
        sent = time.perf_counter()
        child.send_signal(signal.SIGINT)
        _, stderr = child.communicate(timeout=30)
        took = time.perf_counter() - sent
    finally:
        child.kill()
    assert "KeyboardInterrupt" in stderr, stderr
    assert "Panic" not in stderr and "panicked" not in stderr, stderr
    assert took < 1.5, took


def _sweep_in_child(queue: Any) -> None:
    result = rr.sweep("speed_ratio", [1.5, 2.0, 2.5], transient=5, keep=2)
    queue.put(result.state.tobytes())


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")
def test_sweep_in_a_forked_child_after_a_sweep() -> None:
    """Item 8: the parent's sweep leaves no thread pool behind that a forked child would wait
    on (a pool per call): the child's sweep finishes, with the parent's bits."""
    parent = rr.sweep("speed_ratio", [1.5, 2.0, 2.5], transient=5, keep=2)
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    child = context.Process(target=_sweep_in_child, args=(queue,))
    child.start()
    child.join(timeout=60)
    if child.is_alive():
        child.kill()
        pytest.fail("the sweep in the forked child hung")
    assert child.exitcode == 0
    assert queue.get(timeout=5) == parent.state.tobytes()
