"""The SI FMUs (seconds, metres, newtons, rad/s) against the dimensionless FMUs scaled by hand,
and the units and display units their model descriptions declare (issue 33, item 6)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import warnings

from fmpy import read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from fmu_helpers import FMUS, SI_FMUS, instance

# A rotor unlike the defaults: ω_n = 437 rad/s (4173 rpm), δ = 0.25 mm, M = 7.3 kg.
W, DELTA, MASS = 437.0, 2.5e-4, 7.3
K = MASS * W * W  # the rotor's stiffness, N/m
F = K * DELTA  # the force unit: the model's forces are per unit mass, in clearances·ω_n²

# The paper preset with an input force and friction, in model units ...
MODEL = {"speed_ratio": 1.5, "damping_ratio": 0.125, "mass_ratio": 0.005,
         "eccentricity_ratio": 70.0, "k_xx": 20.0, "k_xy": 5.0, "k_yx": 5.0, "k_yy": 40.0,
         "offset_x": 0.3, "offset_y": -0.2, "friction_coefficient": 0.1, "radius_ratio": 50.0,
         "x0": 0.1, "y0": 0.1, "vx0": 0.2, "vy0": -0.1, "fx": 0.3, "fy": -0.2}
# ... and the same rotor in SI units, converted here by hand.
SI = {"natural_frequency": W, "clearance": DELTA, "mass": MASS, "speed": 1.5 * W,
      "damping_ratio": 0.125, "mass_ratio": 0.005, "eccentricity": 70.0 * DELTA,
      "k_xx": 20.0 * K, "k_xy": 5.0 * K, "k_yx": 5.0 * K, "k_yy": 40.0 * K,
      "offset_x": 0.3 * DELTA, "offset_y": -0.2 * DELTA, "friction_coefficient": 0.1,
      "rotor_radius": 50.0 * DELTA, "x0": 0.1 * DELTA, "y0": 0.1 * DELTA,
      "vx0": 0.2 * DELTA * W, "vy0": -0.1 * DELTA * W, "fx": 0.3 * F, "fy": -0.2 * F}
OUTPUTS = ["x", "y", "vx", "vy", "normal_force", "contact_count", "slip_regime"]
TAU_END, TAU_STEP = 6 * 2 * math.pi / 1.5, 0.01


@pytest.mark.parametrize("version", ["3.0", "2.0"])
def test_the_si_fmu_is_the_dimensionless_one_scaled_by_hand(version: str) -> None:
    model = simulate_fmu(str(FMUS[version]), stop_time=TAU_END, output_interval=TAU_STEP,
                         start_values=MODEL, output=OUTPUTS)
    si = simulate_fmu(str(SI_FMUS[version]), stop_time=TAU_END / W,
                      output_interval=TAU_STEP / W, start_values=SI, output=OUTPUTS)
    assert len(si) == len(model) > 500
    np.testing.assert_allclose(si["time"] * W, model["time"], rtol=1e-12, atol=1e-12)
    scale = {"x": DELTA, "y": DELTA, "vx": DELTA * W, "vy": DELTA * W, "normal_force": F}
    worst = 0.0
    for name, factor in scale.items():
        reference = model[name]
        span = float(np.max(np.abs(reference)))
        error = float(np.max(np.abs(si[name] / factor - reference))) / span
        worst = max(worst, error)
        assert error < 1e-9, f"{name}: relative difference {error:.1e}"
    print(f"FMI {version}: SI / scale vs dimensionless, largest relative difference {worst:.1e}")
    assert np.array_equal(si["contact_count"], model["contact_count"])
    assert np.array_equal(si["slip_regime"], model["slip_regime"])
    assert model["contact_count"][-1] >= 3 and set(model["slip_regime"]) & {2, 3, 4}


@pytest.mark.parametrize("version", ["3.0", "2.0"])
def test_fmpy_validation_finds_nothing_in_the_si_fmus(version: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert validate_fmu(str(SI_FMUS[version])) == []
        md = read_model_description(str(SI_FMUS[version]), validate=True,
                                    validate_variable_names=True, validate_model_structure=True)
    assert md.fmiVersion == version and md.modelName == "rotor_rub_si"


@pytest.mark.parametrize("version", ["3.0", "2.0"])
def test_units_and_display_units_are_declared(version: str) -> None:
    md = read_model_description(str(SI_FMUS[version]), validate=True)
    units = {u.name: u for u in md.unitDefinitions}
    variables = {v.name: v for v in md.modelVariables}
    expected = {"x": "m", "vx": "m/s", "normal_force": "N", "fx": "N", "speed": "rad/s",
                "k_xy": "N/m", "natural_frequency": "rad/s", "clearance": "m", "mass": "kg",
                "eccentricity": "m", "rotor_radius": "m", "phase": "rad", "damping_ratio": "1"}
    if version == "3.0":
        expected["time"] = "s"  # FMI 2.0 leaves time implicit, in seconds
    for name, unit in expected.items():
        assert variables[name].unit == unit, name
        assert unit in units, unit
    shown = {u: {d.name: d.factor for d in units[u].displayUnits} for u in units}
    assert variables["speed"].displayUnit == "rpm"
    assert shown["rad/s"]["rpm"] == pytest.approx(60 / (2 * math.pi), rel=1e-15)
    assert variables["x"].displayUnit == "um" and shown["m"]["um"] == 1e6
    base = units["N"].baseUnit
    assert (base.kg, base.m, base.s) == (1, 1, -2)
    # The dimensionless FMU stays available, every quantity of unit "1".
    plain = read_model_description(str(FMUS[version]), validate=True)
    assert {u.name for u in plain.unitDefinitions} == {"1"}
    assert {v.unit for v in plain.modelVariables if v.type == "Real" or v.type == "Float64"} \
        == {"1"}


def test_si_values_are_checked_against_the_scaled_ranges() -> None:
    """The model's ranges scaled by ω_n, δ, M: a stator of 2e5 rotor stiffnesses is refused in
    N/m (at initialization, since the scales may be set after it), an offset of 11 clearances
    in m; a negative clearance at once."""
    fmi = instance(SI_FMUS["3.0"], initialize=False,
                   start={"natural_frequency": W, "clearance": DELTA, "mass": MASS,
                          "k_xx": 2e5 * K})
    try:
        with pytest.raises(FMICallException):
            fmi.slave.setFloat64([fmi.vr["clearance"]], [-1e-3])
        assert "clearance = -0.001 is out of range" in fmi.messages[-1]
        fmi.slave.enterInitializationMode(startTime=0.0)
        with pytest.raises(FMICallException):
            fmi.slave.exitInitializationMode()
        message = fmi.messages[-1]
        assert "k_xx" in message and "N/m" in message and "out of range" in message, message
        assert f"{1e5 * K:e}"[:5] in f"{float(message.split('[0, ')[1].split(']')[0]):e}"
    finally:
        fmi.close()
    fmi = instance(SI_FMUS["3.0"], start={"clearance": DELTA})
    try:
        with pytest.raises(FMICallException):
            fmi.slave.setFloat64([fmi.vr["offset_x"]], [11 * DELTA])
        assert "offset_x" in fmi.messages[-1] and " m " in fmi.messages[-1] + " "
        with pytest.raises(FMICallException):
            fmi.slave.setFloat64([fmi.vr["mass"]], [2.0])
        assert "fixed" in fmi.messages[-1]
    finally:
        fmi.close()


def test_the_readmes_si_example_runs() -> None:
    """README, "Use it in a HIL rig": a 12 kg rotor, critical speed 2400 rpm, 0.2 mm clearance,
    at 3600 rpm — the paper preset in SI units: it rubs, within a few clearances."""
    run = simulate_fmu(str(SI_FMUS["3.0"]), stop_time=0.5, output_interval=1e-4,
                       start_values={"natural_frequency": 251.3, "clearance": 2e-4,
                                     "mass": 12.0, "speed": 377.0, "eccentricity": 0.014,
                                     "x0": 2e-5, "y0": 2e-5, "k_xx": 1.5e7, "k_xy": 1.5e7,
                                     "k_yx": 1.5e7, "k_yy": 3.0e7, "offset_x": 6e-5,
                                     "offset_y": -4e-5},
                       output=["x", "y", "normal_force", "contact_count"])
    radius = np.hypot(run["x"] - 6e-5, run["y"] + 4e-5)
    assert run["time"][-1] == pytest.approx(0.5)
    assert run["contact_count"][-1] > 10
    assert 2e-4 < radius.max() < 1e-3
    assert run["normal_force"].max() > 0 and np.all(run["normal_force"][radius < 2e-4] == 0)
