"""simulate: the issue's call shape, results equal to the CLI's on every preset and method."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotor_rub as rr
from conftest import columns, run_cli

STATE = ["x", "y", "vx", "vy"]
#: A ring preset's columns after the rotor's (stator_mass_ratio > 0).
RING = ["xs", "ys", "vxs", "vys"]


def test_issue_call_shape() -> None:
    run = rr.simulate(preset="paper", periods=20, method="hybrid", samples=1001, speed_ratio=2.5)
    n = len(run.events)
    assert n > 0
    assert run.events.time.shape == (n,) and run.events.time.dtype == np.float64
    assert run.events.kind.shape == (n,)
    assert set(run.events.kind) <= set(rr.EVENT_KINDS)
    assert run.events.state.shape == (n, 4)
    assert run.samples.time.shape == (1001,) and run.samples.state.shape == (1001, 4)
    assert np.all(np.diff(run.events.time) > 0)
    assert run.end_time == pytest.approx(20 * 2 * np.pi / 2.5, rel=1e-15)
    assert run.time_free + run.time_contact + run.time_rolling == pytest.approx(run.end_time)
    assert 0.0 < run.contact_fraction < 1.0
    assert run.method.startswith("hybrid")


def test_t_end_tol_and_config(tmp_path: Path) -> None:
    a = rr.simulate(t_end=30.0, tol=1e-8, samples=0, method="dop853", speed_ratio=2.0)
    assert a.end_time == 30.0 and len(a.samples) == 0
    config = tmp_path / "c.toml"
    config.write_text('preset = "paper"\nspeed_ratio = 2.0\n')
    b = rr.simulate(config=config, t_end=30.0, tol=1e-8, samples=0, method="dop853")
    assert np.array_equal(a.events.time, b.events.time)
    # Keywords override the config file.
    c = rr.simulate(config=config, t_end=30.0, tol=1e-8, samples=0, method="dop853",
                    speed_ratio=3.0)
    assert not np.array_equal(a.events.time, c.events.time)


def test_every_parameter_is_a_keyword() -> None:
    base = rr.simulate(periods=2, samples=11, method="hybrid")
    for p in rr.parameters():
        same = rr.simulate(periods=2, samples=11, method="hybrid",
                           **{p.name: rr.presets()["paper"][p.name]})
        assert np.array_equal(same.samples.state, base.samples.state), p.name


@pytest.mark.parametrize("preset", sorted(rr.presets()))
@pytest.mark.parametrize("method", ["analytic", "hybrid", "taylor", "dop853", "rk45"])
def test_equals_the_cli(cli: Path, tmp_path: Path, preset: str, method: str) -> None:
    run_cli(cli, ["simulate", "--preset", preset, "--method", method, "--periods", "6",
                  "--events", "e.csv", "--samples", "s.csv", "--sample-count", "257"], tmp_path)
    events = columns(tmp_path / "e.csv")
    samples = columns(tmp_path / "s.csv")
    run = rr.simulate(preset=preset, method=method, periods=6, samples=257)
    state = STATE + (RING if rr.presets()[preset]["stator_mass_ratio"] > 0 else [])
    assert np.array_equal(run.events.time, events["tau"])
    assert list(run.events.kind) == list(events["kind"])
    assert np.array_equal(run.events.state, np.stack([events[c] for c in state], axis=1))
    assert np.array_equal(run.samples.time, samples["tau"])
    assert np.array_equal(run.samples.state, np.stack([samples[c] for c in state], axis=1))
    assert list(run.samples.regime) == list(samples["regime"])
    assert np.array_equal(run.samples.contact.astype(float), samples["contact"])


def test_friction_event_kinds() -> None:
    run = rr.simulate(preset="dry-whip", periods=10, method="hybrid", samples=101)
    kinds = set(run.events.kind)
    assert {"roll", "enter"} <= kinds
    assert run.time_rolling > 0
    assert "rolling" in set(run.samples.regime)


def test_presets_and_parameters_match_the_table(cli: Path, tmp_path: Path) -> None:
    listing = run_cli(cli, ["params"], tmp_path).stdout
    for p in rr.parameters():
        line = next(l for l in listing.splitlines() if l.startswith(p.name + " "))
        assert p.range in line and p.doc in line and p.symbol in line
    presets = rr.presets()
    cli_presets = run_cli(cli, ["presets"], tmp_path).stdout
    for name in presets:
        assert name in cli_presets
    assert presets["paper"]["speed_ratio"] == 1.5
    assert presets["dry-whip"]["friction_coefficient"] == 0.6
    assert presets["stator-mass"]["stator_mass_ratio"] == 1.0
    assert presets["ring-whirl"]["friction_coefficient"] == 0.5


def test_help_reads_well() -> None:
    doc = rr.simulate.__doc__ or ""
    for word in ("preset", "t_end", "periods", "method", "tol", "samples", "speed_ratio",
                 "Returns"):
        assert word in doc, word
    assert "Events" in (rr.Run.__doc__ or "") or "events" in (rr.Run.__doc__ or "")
    assert rr.Stepper.__doc__
