"""The stator ring with mass through the FMUs (issue 28 item 3): a ring run's outputs `x`, `y`,
`xs`, `ys` against the CLI's samples of the same problem (`rotor-rub simulate --set
stator_mass_ratio=1 …`, the variable-step taylor method at tol 1e-12), in both FMI versions and
in the SI FMU scaled by hand; the massless ring's outputs are 0."""

from __future__ import annotations

import csv
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from fmpy import read_model_description, simulate_fmu

from fmu_helpers import FMUS, ROOT, SI_FMUS

RING = {"stator_mass_ratio": 1.0, "contact_stiffness": 100.0, "stator_damping": 0.5}
ETA = 1.25  # the paper preset's speed ratio
T_END = 5 * 2 * math.pi / ETA  # five forcing periods
SAMPLES = 501


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


def cli_samples(tmp_path: Path) -> dict[str, np.ndarray]:
    out = tmp_path / "samples.csv"
    sets = [arg for name, value in RING.items() for arg in ("--set", f"{name}={value}")]
    subprocess.run([str(cli()), "simulate", *sets, "--method", "taylor", "--tol", "1e-12",
                    "--t-end", repr(T_END), "--samples", str(out),
                    "--sample-count", str(SAMPLES)], check=True, capture_output=True)
    with out.open() as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in ("tau", "x", "y", "xs", "ys")}


@pytest.mark.parametrize("version", ["3.0", "2.0"])
def test_a_ring_run_matches_the_cli(version: str, tmp_path: Path) -> None:
    want = cli_samples(tmp_path)
    step = T_END / (SAMPLES - 1)
    got = simulate_fmu(str(FMUS[version]), stop_time=T_END, output_interval=step,
                       start_values=RING, output=["x", "y", "xs", "ys", "contact_count"])
    assert len(got) == SAMPLES
    np.testing.assert_allclose(got["time"], want["tau"], rtol=1e-12, atol=1e-12)
    worst = 0.0
    for name in ("x", "y", "xs", "ys"):
        error = float(np.max(np.abs(got[name] - want[name])))
        worst = max(worst, error)
        assert error < 1e-6, f"{name}: FMU and CLI differ by {error:.1e} clearances"
    ring = float(np.max(np.hypot(want["xs"], want["ys"])))
    print(f"FMI {version}: ring run vs CLI, largest difference {worst:.1e} clearances;"
          f" ring moves {ring:.2f}, {int(got['contact_count'][-1])} contacts")
    assert ring > 0.2 and got["contact_count"][-1] >= 5


def test_the_si_ring_run_is_the_dimensionless_one_scaled() -> None:
    """Every parameter of the dimensionless FMU (the paper preset with the ring) converted by
    hand to SI at scales unlike the defaults, by its declared unit: the ring's outputs are the
    dimensionless ones scaled (the ring entries' units and scales: k̂_c by M ω_n², ĉ by M ω_n,
    its start by δ and δ ω_n)."""
    w, delta, mass = 437.0, 2.5e-4, 7.3
    factor = {"1": 1.0, "rad": 1.0, "m": delta, "m/s": delta * w, "N/m": mass * w * w,
              "N": mass * w * w * delta, "rad/s": w, "N.s/m": mass * w}
    model_md = read_model_description(str(FMUS["3.0"]))
    si_md = read_model_description(str(SI_FMUS["3.0"]))
    si_by_vr = {v.valueReference: v for v in si_md.modelVariables}
    assert {"N.s/m", "N/m"} <= {u.name for u in si_md.unitDefinitions}
    start = dict(RING, xs0=0.05, vys0=-0.1)
    si_start: dict[str, float] = {"natural_frequency": w, "clearance": delta, "mass": mass}
    for v in model_md.modelVariables:
        # The table's entries (inputs 10-12, parameters 100+), not the FMU's settings (200+).
        if v.causality not in ("parameter", "input") or v.start is None or v.valueReference >= 200:
            continue
        si = si_by_vr.get(v.valueReference)
        if si is None or si.name in si_start:
            continue
        value = start.get(v.name, float(v.start))
        si_start[si.name] = value * factor[si.unit or "1"]
    step = T_END / (SAMPLES - 1)
    outputs = ["x", "xs", "ys", "vxs", "vys"]
    model = simulate_fmu(str(FMUS["3.0"]), stop_time=T_END, output_interval=step,
                         start_values=start, output=outputs)
    si = simulate_fmu(str(SI_FMUS["3.0"]), stop_time=T_END / w, output_interval=step / w,
                      start_values=si_start, output=outputs)
    assert len(si) == len(model) == SAMPLES
    scale = {"x": delta, "xs": delta, "ys": delta, "vxs": delta * w, "vys": delta * w}
    for name, f in scale.items():
        span = float(np.max(np.abs(model[name])))
        error = float(np.max(np.abs(si[name] / f - model[name]))) / span
        assert span > 0.05 and error < 1e-8, f"{name}: relative difference {error:.1e}"
    assert model["xs"][0] == 0.05 and si["xs"][0] == 0.05 * delta


def test_the_massless_rings_outputs_are_zero() -> None:
    got = simulate_fmu(str(FMUS["3.0"]), stop_time=20.0, output_interval=0.05,
                       output=["x", "xs", "ys", "vxs", "vys"])
    for name in ("xs", "ys", "vxs", "vys"):
        assert np.all(got[name] == 0.0), name
    assert np.max(np.abs(got["x"])) > 0.1
