"""Bad input: ValueError with the CLI's message (exit 2 there); failed runs: PropagationError."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, List

import pytest

import rotor_rub as rr
from conftest import as_keywords, cli_error

# (CLI arguments after `simulate`, the same input as Python keywords)
CASES: List[tuple] = [
    (["--set", "speed_ratio=-1"], {"speed_ratio": -1.0}),
    (["--set", "damping_ratio=11"], {"damping_ratio": 11.0}),
    (["--set", "k_xx=1e6"], {"k_xx": 1e6}),
    (["--set", "friction_coefficient=0.2", "--set", "k_xy=50", "--set", "k_yx=50"],
     {"friction_coefficient": 0.2, "k_xy": 50.0, "k_yx": 50.0}),
    (["--set", "nonsense=1"], {"nonsense": 1.0}),
    (["--preset", "nope"], {"preset": "nope"}),
    (["--method", "euler"], {"method": "euler"}),
    (["--method", "rk45", "--tol", "10"], {"method": "rk45", "tol": 10.0}),
    (["--method", "dop853", "--tol", "1e-20"], {"method": "dop853", "tol": 1e-20}),
    (["--step", "1e-300"], {"step": 1e-300}),
    (["--step", "1e300"], {"step": 1e300}),
    (["--method", "hybrid", "--step", "0.01"], {"method": "hybrid", "step": 0.01}),
    (["--contact-scheme", "rk4"], {"contact_scheme": "rk4"}),
]


@pytest.mark.parametrize("args,keywords", CASES)
def test_value_errors_carry_the_cli_message(cli: Path, tmp_path: Path, args: List[str],
                                            keywords: Dict[str, Any]) -> None:
    expected = cli_error(cli, ["simulate", "--periods", "1", *args], tmp_path)
    with pytest.raises(ValueError) as error:
        rr.simulate(periods=1, **keywords)
    # The CLI says which flag a value came from (clap's "invalid value 'X' for '--set …': ");
    # the message itself is the same, with the keyword arguments where the CLI names --set and
    # each keyword where the CLI names its flag.
    message = str(error.value)
    assert "--" not in message, message
    expected = as_keywords(expected)
    assert expected == message or expected.endswith(": " + message), (expected, message)


def test_config_errors(cli: Path, tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text("speed_ratio = 'fast'\n")
    for config in (bad, tmp_path / "missing.toml", tmp_path):
        expected = cli_error(cli, ["simulate", "--config", str(config)], tmp_path)
        with pytest.raises(ValueError) as error:
            rr.simulate(config=config)
        assert str(error.value) == as_keywords(expected)


def test_counts_and_lengths() -> None:
    for keywords in ({"samples": 1}, {"samples": -5}, {"periods": 0.0}, {"t_end": -1.0},
                     {"t_end": float("nan")}, {"periods": float("inf")},
                     {"t_end": 1.0, "periods": 1.0}, {"max_work": 0.5}):
        with pytest.raises(ValueError):
            rr.simulate(**keywords)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="keep"):
        rr.poincare(keep=0)
    with pytest.raises(ValueError, match="samples_per_period"):
        rr.spectrum(samples_per_period=1)
    with pytest.raises(ValueError, match="one or two"):
        rr.sweep_grid({})
    with pytest.raises(ValueError, match="no values"):
        rr.sweep("speed_ratio", [])
    with pytest.raises(ValueError, match="speed_ratio = 500"):
        rr.sweep("speed_ratio", [1.0, 500.0], transient=1, keep=1)
    with pytest.raises(ValueError, match=r"speed_ratio: 'fast' \(str\) is not a number"):
        rr.simulate(speed_ratio="fast")  # type: ignore[arg-type]


def test_work_limit_is_refused_up_front() -> None:
    with pytest.raises(ValueError, match="max_work"):
        rr.simulate(samples=1000, max_work=10)


def test_divergence_is_a_propagation_error() -> None:
    with pytest.raises(rr.PropagationError, match="diverged"):
        rr.simulate(method="dop853", periods=40, k_xy=15.0, k_yx=-10.0)
    assert issubclass(rr.PropagationError, RuntimeError)


def test_sweep_skips_or_fails_like_the_cli() -> None:
    args: Dict[str, Any] = dict(method="dop853", k_xy=15.0, transient=40, keep=2)
    with pytest.raises(rr.PropagationError, match="k_yx = -10"):
        rr.sweep("k_yx", [-10.0, 20.0], **args)
    kept = rr.sweep("k_yx", [-10.0, 20.0], skip_errors=True, **args)
    assert set(kept.value) == {20.0} and len(kept) == 2
    assert len(kept.skipped) == 1 and "diverged" in kept.skipped[0]


def test_stepper_errors() -> None:
    with pytest.raises(ValueError, match="speed_ratio"):
        rr.Stepper(speed_ratio=0.0)
    with pytest.raises(ValueError, match="max_substeps"):
        rr.Stepper(max_substeps=0)
    stepper = rr.Stepper()
    for dt in (0.0, -1e-3, 2.0, float("nan")):
        with pytest.raises(ValueError, match="step dt"):
            stepper.step(dt)
    assert stepper.time == 0.0
    with pytest.raises(ValueError, match="damping_ratio"):
        stepper.set_params(damping_ratio=-1.0)
    with pytest.raises(ValueError, match="dt: 'x'"):
        stepper.step("x")  # type: ignore[arg-type]
