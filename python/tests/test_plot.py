"""rotor_rub.plot renders every figure (Agg backend, bundled fonts)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rotor_rub as rr  # noqa: E402
import rotor_rub.plot as rplot  # noqa: E402


def _saved(ax: "matplotlib.axes.Axes", path: Path) -> int:
    ax.figure.savefig(path, dpi=60)
    plt.close(ax.figure)
    return path.stat().st_size


def test_every_plot_renders(tmp_path: Path) -> None:
    run = rr.simulate(preset="friction", periods=10, method="hybrid", samples=2001)
    ax = rplot.orbit(run, offset=(0.3, -0.2))
    labels = ax.get_legend_handles_labels()[1]
    assert "contact start" in labels and "orbit" in labels
    assert _saved(ax, tmp_path / "orbit.png") > 1000
    sweep = rr.sweep("speed_ratio", np.linspace(1.0, 3.5, 8), transient=20, keep=4)
    assert _saved(rplot.bifurcation(sweep), tmp_path / "bif.png") > 1000
    section = rr.poincare(transient=20, keep=16, speed_ratio=3.0)
    assert _saved(rplot.poincare(section), tmp_path / "p.png") > 1000
    whirl = rr.spectrum(preset="friction", transient=20, periods=12, whirl=True)
    ax = rplot.spectrum(whirl)
    assert set(ax.get_legend_handles_labels()[1]) == {"backward whirl", "forward whirl"}
    assert _saved(ax, tmp_path / "w.png") > 1000
    plain = rr.spectrum(transient=20, periods=12)
    assert _saved(rplot.spectrum(plain, log=False), tmp_path / "s.svg") > 1000
