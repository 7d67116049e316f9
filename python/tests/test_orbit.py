"""rr.orbit and rr.continuation: the numbers of `rotor-rub orbit` and `rotor-rub continue` bit
for bit, the call shapes of issue 30, errors naming the keywords, files and conversions,
progress, and rotor_rub.plot.branches."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import rotor_rub as rr  # noqa: E402
import rotor_rub.plot as rplot  # noqa: E402
from conftest import columns, run_cli  # noqa: E402

ANNULAR = [2.1, -1.2, 0.5, -5.6]


def test_orbit_is_the_clis_orbit(cli: Path, tmp_path: Path) -> None:
    o = rr.orbit(preset="paper", period=1, speed_ratio=2.2, guess=ANNULAR)
    assert isinstance(o, rr.Orbit)
    assert o.state.shape == (4,) and o.period == 1 and o.minimal_period == 1
    assert o.multipliers.dtype == np.complex128 and o.multipliers.shape == (4,)
    assert o.stable and np.all(np.abs(o.multipliers) < 1)
    assert o.residuals[-1] < 1e-10 and o.monodromy.shape == (4, 4)
    out = run_cli(cli, ["orbit", "--set", "speed_ratio=2.2", "--start", "2.1,-1.2,0.5,-5.6"],
                  tmp_path).stdout
    printed = re.search(r"x = (\S+), y = (\S+), x' = (\S+), y' = (\S+)", out)
    assert printed is not None, out
    assert [float(v) for v in printed.groups()] == list(o.state)
    # The multipliers are the monodromy's eigenvalues.
    ev = np.linalg.eigvals(o.monodromy)
    for m in o.multipliers:
        assert np.min(np.abs(ev - m)) < 1e-12


def test_orbit_starts(cli: Path) -> None:
    two = rr.orbit(period=2, speed_ratio=3.0)
    assert two.period == 2 and two.minimal_period == 2 and two.stable
    assert two.sections.shape == (2, 4)
    assert np.array_equal(two.sections[-1], two.sections[-1])
    free = rr.orbit(speed_ratio=3.0, guess="free")
    assert free.contacts == 0 and free.contact_fraction == 0.0
    assert len(free.residuals) == 1
    # A numpy state and numpy scalars are taken.
    again = rr.orbit(speed_ratio=np.float64(2.2), guess=np.array(ANNULAR), period=np.int64(1))
    assert np.array_equal(again.state, rr.orbit(speed_ratio=2.2, guess=ANNULAR).state)


def test_continuation_is_the_clis_branch(cli: Path, tmp_path: Path) -> None:
    c = rr.continuation("speed_ratio", 1.8, 1.4, guess="free", max_period=1)
    assert isinstance(c, rr.Continuation)
    n = len(c)
    assert c.value.shape == (n,) and c.state.shape == (n, 4) and c.period.shape == (n,)
    assert c.stable.dtype == np.bool_ and c.multipliers.shape == (n, 4)
    kinds = {b.kind for b in c.bifurcations}
    assert {"grazing", "fold"} <= kinds <= set(rr._orbits.BIFURCATION_KINDS)
    grazing = next(b for b in c.bifurcations if b.kind == "grazing")
    assert abs(grazing.value - 1.442133059012) < 1e-8
    assert c.branches[0].parent is None and "left the range" in c.branches[0].end
    run_cli(cli, ["continue", "--from", "1.8", "--to", "1.4", "--start", "free",
                  "--max-period", "1", "--out", "b.csv", "--no-plot"], tmp_path)
    rows = columns(tmp_path / "b.csv")
    assert c.value.tobytes() == rows["value"].tobytes()
    assert c.state[:, 0].tobytes() == rows["x"].tobytes()
    assert c.max_radius.tobytes() == rows["max_radius"].tobytes()
    assert list(c.kind) == [k if isinstance(k, str) else "" for k in rows["bifurcation"]]
    assert np.allclose(np.abs(c.multipliers[:, 0]), rows["modulus_1"], rtol=1e-15, atol=0)
    assert list(c.stable) == [s == "true" for s in rows["stable"]]


def test_period_doubling_switches_to_the_period_two_branch() -> None:
    c = rr.continuation("speed_ratio", 3.5, 2.9, max_period=2)
    doubling = next(b for b in c.bifurcations if b.kind == "period-doubling")
    assert 3.0 < doubling.value < 3.25
    assert any(b.period == 2 and b.parent == doubling.index for b in c.branches)
    assert set(c.period) == {1, 2}


def test_bad_input_names_the_keyword() -> None:
    for kwargs, pieces in [
        (dict(period=0), ["period", "0"]),
        (dict(period=33), ["period", "33", "[1, 32]"]),
        (dict(guess=[1.0, 2.0]), ["guess", "2 entries"]),
        (dict(guess="nowhere"), ["guess", "nowhere"]),
        (dict(guess=[1.0, 2.0, 3.0, float("nan")]), ["guess"]),
        (dict(newton_tol=1.0), ["newton_tol", "[1e-14, 1e-3]"]),
        (dict(transient=-1), ["transient"]),
        (dict(speed_ratio=0.0), ["speed_ratio"]),
        (dict(period=True), ["period"]),
    ]:
        with pytest.raises(ValueError) as e:
            rr.orbit(**kwargs)  # type: ignore[arg-type]
        for piece in pieces:
            assert piece in str(e.value), (kwargs, str(e.value))
    with pytest.raises(rr.PropagationError, match="did not converge"):
        rr.orbit(preset="friction", speed_ratio=1.5)
    for args, pieces in [
        (("x0", 0.0, 1.0), ["param x0", "model parameter"]),
        (("speed_ratio", 1.0, 1.0), ["stop = 1 equals start"]),
        (("speed_ratio", 0.0, 1.0), ["start = 0", "speed_ratio"]),
        (("no_such", 1.0, 2.0), ["param", "no_such"]),
    ]:
        with pytest.raises(ValueError) as e:
            rr.continuation(*args)  # type: ignore[arg-type]
        for piece in pieces:
            assert piece in str(e.value), (args, str(e.value))


def test_results_save_and_convert(tmp_path: Path) -> None:
    o = rr.orbit(speed_ratio=2.2, guess=ANNULAR)
    c = rr.continuation("speed_ratio", 1.6, 1.5, guess="free", max_period=1)
    for stem, result in (("o", o), ("c", c)):
        for suffix in (".parquet", ".nc"):
            result.save(tmp_path / (stem + suffix))
            back = rr.load(tmp_path / (stem + suffix))
            assert type(back) is type(result)
    back_c = rr.load(tmp_path / "c.nc")
    assert isinstance(back_c, rr.Continuation)
    assert np.array_equal(back_c.value, c.value) and np.array_equal(back_c.stable, c.stable)
    assert np.array_equal(back_c.multipliers, c.multipliers)
    assert back_c.branches == c.branches
    back_o = rr.load(tmp_path / "o.parquet")
    assert isinstance(back_o, rr.Orbit)
    assert np.array_equal(back_o.multipliers, o.multipliers)
    assert np.array_equal(back_o.monodromy, o.monodromy) and back_o.stable == o.stable
    df = c.to_pandas()
    assert list(df["value"]) == list(c.value)
    assert "modulus" in o.to_xarray() and "section_x" in o.to_xarray()


def test_progress_reports_the_range_covered() -> None:
    seen = []
    rr.continuation("speed_ratio", 1.6, 1.5, guess="free", max_period=1,
                    progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (100.0, 100.0)


def test_branches_plot(tmp_path: Path) -> None:
    c = rr.continuation("speed_ratio", 3.5, 2.9, max_period=2)
    sweep = rr.sweep("speed_ratio", np.linspace(2.9, 3.5, 7), transient=50, keep=5)
    for quantity in ("x", "max_radius"):
        ax = rplot.branches(c, sweep=sweep if quantity == "x" else None, quantity=quantity)
        labels = ax.get_legend_handles_labels()[1]
        assert "period doubling" in labels and "period-1 stable" in labels
        ax.figure.savefig(tmp_path / f"{quantity}.png", dpi=60)
        plt.close(ax.figure)
        assert (tmp_path / f"{quantity}.png").stat().st_size > 1000
    with pytest.raises(ValueError, match="quantity"):
        rplot.branches(c, quantity="speed")


def test_a_long_continuation_stops_at_the_watchs_next_poll() -> None:
    calls = []

    def stop(done: float, total: float) -> None:
        calls.append(done)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        rr.continuation("speed_ratio", 0.5, 4.0, max_period=2, progress=stop)
    assert len(calls) == 1
