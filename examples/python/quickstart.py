"""rotor_rub from Python: a run, a section, a spectrum, a sweep, a run-up, the stepper's state
and a saved result (checked by mypy --strict and run by the tests).
Run: python examples/python/quickstart.py [OUT_DIR]"""

from __future__ import annotations

import os
import sys
import tempfile

import numpy as np

import rotor_rub as rr


def main(out: str) -> None:
    run: rr.Run = rr.simulate(preset="paper", periods=20, method="hybrid", samples=1001,
                              speed_ratio=2.5)
    starts = run.events.time[run.events.kind == "enter"]
    print(f"{len(run.events)} switches, {len(starts)} contacts, "
          f"{100 * run.contact_fraction:.1f} % of the time in contact "
          f"({run.problem.method_text}, stator centre {run.problem.offset})")
    section: rr.Section = rr.poincare(speed_ratio=np.float32(3.0), transient=np.int64(100),
                                      keep=50)
    print(f"η = 3: {section.response}")
    whirl: rr.Spectrum = rr.spectrum(preset="friction", whirl=True)
    assert whirl.whirl is not None
    peak = float(whirl.order[int(np.argmax(whirl.whirl))])
    print(f"friction preset: strongest whirl component at {peak:+.3f}× the running speed")
    sweep: rr.Sweep = rr.sweep("speed_ratio", np.arange(1, 4), transient=100, keep=20,
                               lyapunov=True)
    assert sweep.lyapunov is not None
    for value, response, exponent in zip(sweep.points[:, 0], sweep.response, sweep.lyapunov):
        print(f"  η = {value:g}: {response}, λ₁ = {exponent:.4f}")
    up: rr.Runup = rr.runup(method="hybrid")
    for jump in up.jumps:
        print(f"run-up program: {jump.direction} jump at η = {jump.speed:.3f}")
    stepper = rr.Stepper(dt=1e-3, speed_ratio=2.5)
    stepper.run(1000)
    saved: rr.StepperState = stepper.state
    first = stepper.run(1000)
    stepper.state = saved
    assert stepper.run(1000).samples.state.tobytes() == first.samples.state.tobytes()
    print(f"stepper at τ = {stepper.time:.3f}: {stepper.regime}, repeated from τ = {saved.time}")
    path = os.path.join(out, "sweep.parquet")
    sweep.save(path)
    again = rr.load(path)
    assert isinstance(again, rr.Sweep) and again.state.tobytes() == sweep.state.tobytes()
    print(f"saved and loaded {path}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp())
