"""poincare, spectrum and sweep: equal to the CLI's CSV files."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import rotor_rub as rr
from conftest import columns, run_cli

STATE = ["x", "y", "vx", "vy"]


def test_poincare_equals_the_cli(cli: Path, tmp_path: Path) -> None:
    out = run_cli(cli, ["poincare", "--set", "speed_ratio=3", "--transient", "50", "--keep",
                        "24", "--out", "p.csv"], tmp_path)
    expected = columns(tmp_path / "p.csv")
    response = next(line for line in out.stdout.splitlines() if line.startswith("response: "))
    section = rr.poincare(speed_ratio=3.0, transient=50, keep=24)
    assert np.array_equal(section.period, expected["period"].astype(np.int64))
    assert np.array_equal(section.state, np.stack([expected[c] for c in STATE], axis=1))
    assert section.response == response[len("response: "):]
    assert section.lyapunov is None
    with_exponent = rr.poincare(speed_ratio=3.0, transient=50, keep=24, lyapunov=True)
    assert with_exponent.lyapunov is not None and np.isfinite(with_exponent.lyapunov)


def test_spectrum_equals_the_cli(cli: Path, tmp_path: Path) -> None:
    for whirl in (False, True):
        args = ["spectrum", "--preset", "friction", "--transient", "20", "--periods", "12",
                "--out", "s.csv"] + (["--whirl"] if whirl else [])
        run_cli(cli, args, tmp_path)
        expected = columns(tmp_path / "s.csv")
        spec = rr.spectrum(preset="friction", transient=20, periods=12, whirl=whirl)
        assert np.array_equal(spec.order, expected["order"])
        if whirl:
            assert spec.whirl is not None and spec.x is None
            assert np.array_equal(spec.whirl, expected["whirl"])
        else:
            assert spec.x is not None and spec.y is not None and spec.whirl is None
            assert np.array_equal(spec.x, expected["x"])
            assert np.array_equal(spec.y, expected["y"])


def test_sweep_equals_the_cli(cli: Path, tmp_path: Path) -> None:
    run_cli(cli, ["sweep", "--from", "1", "--to", "3.5", "--steps", "6", "--transient", "30",
                  "--keep", "4", "--out", "w.csv", "--no-plot"], tmp_path)
    expected = columns(tmp_path / "w.csv")
    values = np.unique(expected["value"])
    result = rr.sweep("speed_ratio", values, transient=30, keep=4)
    assert np.array_equal(result.value, expected["value"])
    assert np.array_equal(result.period, expected["period"].astype(np.int64))
    assert np.array_equal(result.state, np.stack([expected[c] for c in STATE], axis=1))
    # One thread or many: the same bits.
    single = rr.sweep("speed_ratio", values, transient=30, keep=4, threads=1)
    assert np.array_equal(single.state, result.state)


def test_grid_order_and_independence() -> None:
    grid = {"speed_ratio": [1.5, 2.5, 3.0], "damping_ratio": [0.05, 0.125]}
    result = rr.sweep_grid(grid, transient=10, keep=2)
    assert result.params == ("speed_ratio", "damping_ratio")
    assert result.values.shape == (12, 2)
    assert list(result.values[::2, 0]) == [1.5, 1.5, 2.5, 2.5, 3.0, 3.0]
    assert list(result.values[::2, 1]) == [0.05, 0.125] * 3
    # Each point alone gives its rows of the grid.
    one = rr.sweep("speed_ratio", [2.5], transient=10, keep=2, damping_ratio=0.125)
    assert np.array_equal(one.state, result.state[6:8])
