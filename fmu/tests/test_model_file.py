"""The FMU built for a model file (issue 29 item 5): `cargo xtask fmu --model
fmu/tests/data/ring_rotor.toml` (the n = 4 rotor rubbing in a stator ring with mass) run by
FMPy's `simulate_fmu` in both FMI versions, its outputs `x, y, xs, ys, vx, rub_x, rub_y` (SI)
against the CLI's samples of the same file (`rotor-rub simulate --model … --method taylor`);
an input force held on `f_x` is the file's constant force (the CLI's run of the file with it)."""

from __future__ import annotations

import csv
import os
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from fmu_helpers import FMU_DIR, ROOT

MODEL = ROOT / "fmu" / "tests" / "data" / "ring_rotor.toml"
FMUS = {"3.0": FMU_DIR / "rotor_rub_ring_rotor_fmi3.fmu",
        "2.0": FMU_DIR / "rotor_rub_ring_rotor_fmi2.fmu"}
T_END = 0.2  # s: ~10 forcing periods at 330 rad/s
SAMPLES = 401
COLUMNS = ["x", "y", "xs", "ys", "vx", "rub_x", "rub_y"]


def cli() -> Path:
    """The CLI binary: $ROTOR_RUB_CLI, else the workspace's release build (built if missing)."""
    if "ROTOR_RUB_CLI" in os.environ:
        return Path(os.environ["ROTOR_RUB_CLI"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    binary = target / "release" / "rotor-rub"
    if not binary.is_file():
        subprocess.run(["cargo", "build", "--release", "-p", "rotor-rub-cli"], cwd=ROOT,
                       check=True)
    return binary


@pytest.fixture(scope="module", autouse=True)
def model_fmus() -> None:
    """The model file's FMUs, built with the host's toolchain when missing."""
    if not all(p.is_file() for p in FMUS.values()):
        subprocess.run(["cargo", "xtask", "fmu", "--host", "--model", str(MODEL)], cwd=ROOT,
                       check=True)


def cli_samples(tmp_path: Path) -> dict[str, np.ndarray]:
    out = tmp_path / "samples.csv"
    subprocess.run([str(cli()), "simulate", "--model", str(MODEL), "--method", "taylor",
                    "--tol", "1e-12", "--t-end", repr(T_END), "--samples", str(out),
                    "--sample-count", str(SAMPLES)], check=True, capture_output=True)
    with out.open() as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in ["t", *COLUMNS]}


@pytest.mark.parametrize("version", ["3.0", "2.0"])
def test_a_model_file_run_matches_the_cli(version: str, tmp_path: Path) -> None:
    want = cli_samples(tmp_path)
    step = T_END / (SAMPLES - 1)
    got = simulate_fmu(str(FMUS[version]), stop_time=T_END, output_interval=step,
                       output=[*COLUMNS, "contact_count"])
    assert len(got) == SAMPLES
    np.testing.assert_allclose(got["time"], want["t"], rtol=1e-12, atol=1e-15)
    clearance = 2e-4
    worst = 0.0
    for name in COLUMNS:
        scale = clearance * (330.0 if name.startswith("v") else 1.0)
        error = float(np.max(np.abs(got[name] - want[name]))) / scale
        worst = max(worst, error)
        assert error < 1e-8, f"{name}: FMU and CLI differ by {error:.1e} clearances"
    contacts = int(got["contact_count"][-1])
    print(f"FMI {version}: model-file FMU vs CLI, largest difference {worst:.1e} clearances;"
          f" {contacts} contacts")
    assert contacts >= 5
    assert float(np.max(np.hypot(want["rub_x"], want["rub_y"]))) > clearance


@pytest.mark.parametrize("version", ["3.0", "2.0"])
def test_the_model_description_is_valid(version: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning either
        assert validate_fmu(str(FMUS[version])) == []
        md = read_model_description(str(FMUS[version]), validate=True,
                                    validate_variable_names=True, validate_model_structure=True)
    assert md.fmiVersion == version
    assert md.coSimulation.canGetAndSetFMUstate and not md.coSimulation.canSerializeFMUstate


def test_the_description_names_the_dofs_and_a_held_force_is_the_file_s_force(
        tmp_path: Path) -> None:
    md = read_model_description(str(FMUS["3.0"]))
    names = {v.name: v for v in md.modelVariables}
    for dof in ["x", "y", "xs", "ys"]:
        assert names[dof].causality == "output" and names[dof].unit == "m"
        assert names[f"v{dof}"].unit == "m/s"
        assert names[f"f_{dof}"].causality == "input" and names[f"f_{dof}"].unit == "N"
    # The input f_x = 300 N held from the start: the CLI's run of the same file with
    # `force = [300, 0, 0, 0]` (the file's constant force per DOF).
    forced = tmp_path / "forced.toml"
    forced.write_text(MODEL.read_text().replace(
        "phase = 0.0\n\n[matrices]", "phase = 0.0\nforce = [300.0, 0.0, 0.0, 0.0]\n\n[matrices]"))
    out = tmp_path / "forced.csv"
    subprocess.run([str(cli()), "simulate", "--model", str(forced), "--method", "taylor",
                    "--tol", "1e-12", "--t-end", repr(T_END), "--samples", str(out),
                    "--sample-count", str(SAMPLES)], check=True, capture_output=True)
    with out.open() as f:
        rows = list(csv.DictReader(f))
    want = {k: np.array([float(r[k]) for r in rows]) for k in ["x", "y"]}
    got = simulate_fmu(str(FMUS["3.0"]), stop_time=T_END, output_interval=T_END / (SAMPLES - 1),
                       start_values={"f_x": 300.0}, output=["x", "y"])
    free = simulate_fmu(str(FMUS["3.0"]), stop_time=T_END,
                        output_interval=T_END / (SAMPLES - 1), output=["x"])
    for name in ("x", "y"):
        error = float(np.max(np.abs(got[name] - want[name]))) / 2e-4
        assert error < 1e-8, f"{name}: forced FMU and CLI differ by {error:.1e} clearances"
    moved = float(np.max(np.abs(got["x"] - free["x"]))) / 2e-4
    print(f"f_x = 300 N held: matches the CLI's forced file; moves x by up to {moved:.2f} clearances")
    assert moved > 0.1
