"""The four figures of rotor_rub.plot on one page (docs/python-plots.png):
python examples/python/plots.py [OUT.png]"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rotor_rub as rr  # noqa: E402
import rotor_rub.plot as rplot  # noqa: E402


def main(out: str) -> None:
    fig, axes = plt.subplots(2, 2, figsize=(12, 10), layout="constrained")
    run = rr.simulate(preset="friction", periods=60, method="hybrid", samples=20001)
    rplot.orbit(run, axes[0, 0], offset=(0.3, -0.2), from_time=30 * run.forcing_period)
    sweep = rr.sweep("speed_ratio", np.linspace(1.0, 3.5, 126), transient=200, keep=40)
    rplot.bifurcation(sweep, axes[0, 1])
    section = rr.poincare(speed_ratio=2.5, transient=200, keep=600, lyapunov=True)
    rplot.poincare(section, axes[1, 0])
    whirl = rr.spectrum(preset="friction", whirl=True, transient=100, periods=60)
    rplot.spectrum(whirl, axes[1, 1], max_order=3.0)
    fig.savefig(out, dpi=80)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/python-plots.png")
