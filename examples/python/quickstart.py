"""rotor_rub from Python: a run, a section, a spectrum and a sweep (checked by mypy --strict in
the tests). Run: python examples/python/quickstart.py"""

from __future__ import annotations

import numpy as np

import rotor_rub as rr


def main() -> None:
    run: rr.Run = rr.simulate(preset="paper", periods=20, method="hybrid", samples=1001,
                              speed_ratio=2.5)
    starts = run.events.time[run.events.kind == "enter"]
    print(f"{len(run.events)} switches, {len(starts)} contacts, "
          f"{100 * run.contact_fraction:.1f} % of the time in contact")
    section: rr.Section = rr.poincare(speed_ratio=3.0, transient=100, keep=50)
    print(f"η = 3: {section.response}")
    whirl: rr.Spectrum = rr.spectrum(preset="friction", whirl=True)
    assert whirl.whirl is not None
    peak = float(whirl.order[int(np.argmax(whirl.whirl))])
    print(f"friction preset: strongest whirl component at {peak:+.3f}× the running speed")
    sweep: rr.Sweep = rr.sweep("speed_ratio", np.linspace(1.0, 3.5, 26), transient=100, keep=20)
    print(f"sweep: {len(sweep)} Poincaré points over {sweep.params[0]}")
    stepper = rr.Stepper(dt=1e-3, speed_ratio=2.5)
    time, state, regime, events = stepper.step()
    print(f"stepper at τ = {time}: {regime}, x = {state[0]:.6f}")


if __name__ == "__main__":
    main()
