"""The two presets with a stator ring of mass (issue 28), their numbers and their orbits
(docs/ring.png): ``python examples/python/ring_presets.py [OUT.png]``.

``stator-mass``: the paper's rotor and stator with a ring of the disk's mass; the rub goes on and
the ring moves with it. ``ring-whirl``: friction drives the rotor into full annular backward
whirl, rolling on the ring without slip (dry whip), at the coupled rotor–ring mode, the ring
whirling opposite it.
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rotor_rub as rr  # noqa: E402
import rotor_rub.plot as rplot  # noqa: E402


def summary(name: str, run: rr.Run, start: float) -> None:
    """The rub, the ring's motion and the whirl after `start` forcing periods."""
    t = run.samples.time
    late = t >= start * run.forcing_period
    s = run.samples.state[late]            # x, y, vx, vy, xs, ys, vxs, vys
    p = run.problem.params
    d = (s[:, 0] - s[:, 4] - p["offset_x"]) + 1j * (s[:, 1] - s[:, 5] - p["offset_y"])
    angle = np.unwrap(np.angle(d))
    whirl = (angle[-1] - angle[0]) / (t[late][-1] - t[late][0])
    enters = int(np.sum((run.events.time >= start * run.forcing_period)
                        & (run.events.kind == "enter")))
    print(f"{name}: after {start:g} periods {enters} contact starts, in contact "
          f"{np.mean(np.abs(d) > 1):.0%} of the time, rotor up to "
          f"{np.hypot(s[:, 0], s[:, 1]).max():.2f}, ring up to "
          f"{np.hypot(s[:, 4], s[:, 5]).max():.2f} clearances, whirl {whirl:+.2f} per unit τ "
          f"({whirl / p['speed_ratio']:+.1f} × the running speed)")


def main(out: str) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(12, 6), layout="constrained")
    ring = rr.simulate(preset="stator-mass", periods=100, method="hybrid", samples=20001)
    summary("stator-mass", ring, 50)
    rplot.orbit(ring, axes[0], from_time=90 * ring.forcing_period)
    axes[0].set_title("stator-mass: periods 90–100")
    whip = rr.simulate(preset="ring-whirl", periods=100, method="hybrid", samples=40001)
    summary("ring-whirl", whip, 90)
    rplot.orbit(whip, axes[1], from_time=98 * whip.forcing_period)
    axes[1].set_title("ring-whirl: periods 98–100, dry whip")
    fig.savefig(out, dpi=80)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/ring.png")
