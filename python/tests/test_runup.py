"""rr.runup: the CLI's run-up programs, the numbers of `rotor-rub runup`'s files bit for bit,
each branch's jumps, and rotor_rub.plot.runup."""

from __future__ import annotations

import re
from pathlib import Path
from typing import List

import numpy as np
import pytest

import rotor_rub as rr
from conftest import columns, run_cli

STATE = ["x", "y", "vx", "vy"]
RAMP = ["--from", "1.2", "--to", "2.8", "--rate", "4e-3", "--settle", "5", "--dwell", "5"]
KEYWORDS = dict(from_speed=1.2, to_speed=2.8, rate=4e-3, settle=5, dwell=5)


def same_as_files(result: rr.Runup, directory: Path) -> None:
    rows = columns(directory / "r.csv")
    events = columns(directory / "r-events.csv")
    assert list(result.direction) == list(rows["direction"])
    assert np.array_equal(result.period, rows["period"].astype(np.int64))
    for name, column in [("start", "start"), ("end", "end"), ("speed", "speed_ratio"),
                         ("speed_change", "speed_change"), ("max_radius", "max_radius"),
                         ("min_radius", "min_radius"), ("contact_fraction", "contact_fraction"),
                         ("whirl", "whirl")]:
        assert getattr(result, name).tobytes() == rows[column].tobytes(), name
    assert list(result.whirl_direction) == list(rows["whirl_direction"])
    assert np.array_equal(result.enters, rows["enters"].astype(np.int64))
    assert np.array_equal(result.exits, rows["exits"].astype(np.int64))
    # The switches of the whole forcing periods (a partial last period's switches are compared
    # in test_the_partial_last_period_keeps_its_switches: this CLI may leave them out).
    e = result.events
    ours = e.period < len(result)
    theirs = events["period"] < len(result)
    assert e.time[ours].tobytes() == events["time"][theirs].tobytes()
    assert e.speed[ours].tobytes() == events["speed_ratio"][theirs].tobytes()
    assert np.array_equal(e.period[ours], events["period"][theirs].astype(np.int64))
    assert list(e.direction[ours]) == list(events["direction"][theirs])
    assert list(e.kind[ours]) == list(events["kind"][theirs])
    state = np.stack([events[c] for c in STATE], axis=1)[theirs]
    assert e.state[ours].tobytes() == state.tobytes()


def cli_jumps(report: str) -> List[tuple]:
    """(direction, speed, before, after) of the report's jump lines."""
    out, direction = [], ""
    for line in report.splitlines():
        if line.startswith("run-up:"):
            direction = "up"
        elif line.startswith("coast-down:"):
            direction = "down"
        m = re.match(r"\s+jump at η = ([\d.]+): largest radius ([\d.]+) -> ([\d.]+)", line)
        if m:
            out.append((direction, *map(float, m.groups())))
    return out


@pytest.mark.parametrize("method", ["taylor", "analytic", "dop853"])
def test_ramp_equals_the_cli(cli: Path, tmp_path: Path, method: str) -> None:
    out = run_cli(cli, ["runup", *RAMP, "--method", method, "--out", "r.csv", "--no-plot"],
                  tmp_path)
    result = rr.runup(method=method, **KEYWORDS)  # type: ignore[arg-type]
    same_as_files(result, tmp_path)
    assert [(j.direction, round(j.speed, 4), round(j.before, 4), round(j.after, 4))
            for j in result.jumps] == cli_jumps(out.stdout)
    assert result.problem.call == "runup" and result.problem.method == method
    assert result.program.startswith("η 1.2 -> 2.8 -> 1.2")


def test_profile_file_and_array_equal_the_cli(cli: Path, tmp_path: Path) -> None:
    profile = np.array([[0.0, 1.0], [60.0, 1.0], [400.0, 2.6], [700.0, 2.6], [900.0, 1.8]])
    path = tmp_path / "p.csv"
    path.write_text("time,speed_ratio\n" + "".join(f"{t},{s}\n" for t, s in profile.tolist()))
    run_cli(cli, ["runup", "--profile", str(path), "--method", "hybrid", "--out", "r.csv",
                  "--no-plot"], tmp_path)
    from_file = rr.runup(profile=path, method="hybrid")
    from_array = rr.runup(profile=profile, method="hybrid")
    same_as_files(from_file, tmp_path)
    same_as_files(from_array, tmp_path)
    assert set(from_file.direction) == {"hold", "up", "down"}


def test_the_partial_last_period_keeps_its_switches() -> None:
    """Issue 32 item 12's class: no switch dropped. A profile that ends inside a forcing period
    reports that period's switches (period = the number of rows) — the same switches as a run
    on the profile held on past that end."""
    profile = np.array([[0.0, 2.5], [100.0, 2.5]])  # 39.8 turns: a partial 40th
    longer = np.array([[0.0, 2.5], [100.0, 2.5], [130.0, 2.5]])
    short = rr.runup(profile=profile, method="hybrid")
    full = rr.runup(profile=longer, method="hybrid")
    assert len(short) == 39
    tail = short.events.period == 39
    assert tail.any() and np.all(short.events.time[tail] <= 100.0)
    assert set(short.events.direction[tail]) == {"hold"}
    before = full.events.time <= 100.0
    assert short.events.time.tobytes() == full.events.time[before].tobytes()
    assert short.events.state.tobytes() == full.events.state[before].tobytes()


def test_the_paper_program_and_its_hysteresis() -> None:
    """The default program (paper-hysteresis): the run-up falls off the rub branch near
    η = 2.47, the coast-down jumps back onto it near η = 1.40 (README)."""
    result = rr.runup(method="hybrid")
    assert len(result) == 1929
    up = [j for j in result.jumps if j.direction == "up" and j.after < j.before]
    down = [j for j in result.jumps if j.direction == "down" and j.after > j.before]
    assert up and abs(max(up, key=lambda j: j.before - j.after).speed - 2.474) < 0.01
    assert down and abs(max(down, key=lambda j: j.after - j.before).speed - 1.404) < 0.01
    assert result.max_radius.max() > 3.0
    assert set(result.events.kind) == {"enter", "exit"}
    by_name = rr.runup(preset="paper-hysteresis", method="hybrid", from_speed=0.5,
                       to_speed=3.5, one_way=True)
    assert set(by_name.direction) == {"hold", "up"}
    rotor = rr.runup(preset="paper", method="hybrid", from_speed=1.0, to_speed=1.5, rate=1e-2)
    assert rotor.problem.params["offset_x"] == 0.3


def test_runup_errors() -> None:
    with pytest.raises(ValueError, match="from_speed: a ramp option"):
        rr.runup(profile=[[0.0, 1.0], [100.0, 2.0]], from_speed=1.0)
    with pytest.raises(ValueError, match="rate or ramp_periods"):
        rr.runup(rate=1e-3, ramp_periods=100)
    with pytest.raises(ValueError, match="unknown preset 'nope'.*paper-hysteresis"):
        rr.runup(preset="nope")
    with pytest.raises(ValueError, match="friction"):
        rr.runup(preset="friction", from_speed=1.0, to_speed=1.5, rate=1e-2)
    with pytest.raises(ValueError, match="profile row 1"):
        rr.runup(profile=[[0.0, 1.0], [-5.0, 2.0]])
    with pytest.raises(ValueError, match="shape"):
        rr.runup(profile=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="rate"):
        rr.runup(rate=2.0)
    with pytest.raises(ValueError, match="shorter than one forcing period"):
        rr.runup(profile=[[0.0, 1.0], [1.0, 1.0]])


def test_plot_runup(tmp_path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import rotor_rub.plot as rplot

    result = rr.runup(method="hybrid", **KEYWORDS)  # type: ignore[arg-type]
    ax = rplot.runup(result)
    labels = ax.get_legend_handles_labels()[1]
    assert "run-up" in labels and "coast-down" in labels
    assert result.program in ax.get_title()
    ax.figure.savefig(tmp_path / "runup.png", dpi=60)
    plt.close(ax.figure)
    assert (tmp_path / "runup.png").stat().st_size > 1000
