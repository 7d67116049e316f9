"""The FMUs with a real importer, FMPy (run by scripts/test after `cargo xtask fmu`):
FMPy's validation, the paper preset against the library's stepper, a PD controller in the loop,
early return at contact switches, FMU state rollback and serialization, and bad values refused
with a message that names them."""

from __future__ import annotations

import math
import os
import warnings
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

import rotor_rub as rr

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("ROTOR_RUB_FMU_DIR", ROOT / "target" / "fmu"))
FMUS = {"3.0": FMU_DIR / "rotor_rub_fmi3.fmu", "2.0": FMU_DIR / "rotor_rub_fmi2.fmu"}
sys.path.insert(0, str(ROOT / "examples" / "fmu"))

PERIOD = 2 * math.pi / 1.5  # the paper preset's forcing period


@pytest.mark.parametrize("version", FMUS)
def test_fmpy_validation_finds_nothing(version: str) -> None:
    assert FMUS[version].is_file(), "build the FMUs first: cargo xtask fmu"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning either
        assert validate_fmu(str(FMUS[version])) == []
        md = read_model_description(str(FMUS[version]), validate=True,
                                    validate_variable_names=True, validate_model_structure=True)
    assert md.fmiVersion == version
    names = {v.name: v for v in md.modelVariables}
    for output in ["x", "y", "vx", "vy", "in_contact", "normal_force", "contact_count",
                   "slip_regime"]:
        assert names[output].causality == "output"
    for name in ["fx", "fy", "speed_ratio"]:
        assert names[name].causality == "input"
    # Every entry of the parameter table but the start time is a variable, with its range (the
    # stator ring's too: stator_mass_ratio > 0 runs the ring with mass; outputs xs, ys, vxs, vys).
    for output in ["xs", "ys", "vxs", "vys"]:
        assert names[output].causality == "output"
    for p in rr.parameters():
        if p.name in ("start_time", "force_x", "force_y", "speed_ratio"):
            continue
        v = names[p.name]
        assert v.causality == "parameter" and float(v.start) == p.default
        assert v.unit == "1" and v.description


@pytest.mark.parametrize("version", FMUS)
def test_twenty_periods_match_the_library_stepper(version: str) -> None:
    """simulate_fmu at step 1e-3 against rotor_rub.Stepper at dt = 1e-3: the same arithmetic,
    so equal to 1e-12 (measured: bit for bit)."""
    steps = int(20 * PERIOD / 1e-3)
    stop = steps * 1e-3
    result = simulate_fmu(str(FMUS[version]), stop_time=stop, step_size=1e-3,
                          output_interval=1e-3, output=["x", "y", "vx", "vy", "contact_count"])
    fmu_states = np.column_stack([result[n] for n in ["x", "y", "vx", "vy"]])
    library = rr.Stepper(preset="paper", dt=1e-3).run(steps)
    expected = np.vstack([[0.1, 0.1, 0.0, 0.0], library.samples.state])
    assert fmu_states.shape == expected.shape
    worst = float(np.max(np.abs(fmu_states - expected)))
    print(f"FMI {version}: largest difference from the library stepper {worst:.1e}")
    assert worst <= 1e-12
    enters = int(np.sum(library.events.kind == "enter"))
    assert int(result["contact_count"][-1]) == enters > 40


@pytest.mark.parametrize("version", FMUS)
def test_a_pd_controller_through_fmpy_reduces_the_contact_count(version: str) -> None:
    from closed_loop import simulate

    open_loop = simulate(FMUS[version], 0.0, 0.0, periods=20)
    closed = simulate(FMUS[version], 0.5, 1.0, periods=20)
    print(f"FMI {version}: contacts open loop {open_loop.contact_count}, PD {closed.contact_count}")
    assert open_loop.contact_count >= 40
    assert closed.contact_count <= open_loop.contact_count // 4
    assert np.any(np.abs(closed.force) > 0.05), "the controller acts"


def slave(early_return: bool) -> tuple[FMU3Slave, dict[str, int], str]:
    md = read_model_description(str(FMUS["3.0"]))
    unzipped = extract(str(FMUS["3.0"]))
    s = FMU3Slave(guid=md.guid, unzipDirectory=unzipped,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="test")
    s.instantiate(earlyReturnAllowed=early_return)
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    return s, {v.name: v.valueReference for v in md.modelVariables}, unzipped


def test_early_return_stops_at_each_switch_where_it_happened() -> None:
    s, vr, unzipped = slave(early_return=True)
    try:
        reference = rr.Stepper(preset="paper", dt=1e-3).run(int(6 * PERIOD / 1e-3))
        switch_times = list(reference.events.time)
        t, end, seen = 0.0, 6 * PERIOD - 1e-3, []
        while t < end and len(seen) < 12:
            _, _, early, last = s.doStep(currentCommunicationPoint=t,
                                         communicationStepSize=min(0.25, end - t))
            if early:
                seen.append(last)
            t = last
        assert len(seen) == 12
        # Each early return is at a switch of the library's stepper (dt = 1e-3 there, steps of
        # up to 1e-3 cut at the switch here: the same switch to within the sub-step accuracy).
        for time in seen:
            assert min(abs(time - r) for r in switch_times) < 1e-9, time
        in_contact = s.getBoolean([vr["in_contact"]])[0]
        assert in_contact in (True, False)
    finally:
        s.freeInstance()
        shutil.rmtree(unzipped, ignore_errors=True)


def test_state_rollback_and_serialization_repeat_the_run_bit_for_bit() -> None:
    s, vr, unzipped = slave(early_return=False)
    names = ["x", "y", "vx", "vy", "normal_force"]
    try:
        t = 0.0
        for _ in range(3000):
            s.doStep(currentCommunicationPoint=t, communicationStepSize=1e-3)
            t += 1e-3
        saved = s.getFMUState()
        data = s.serializeFMUState(saved)
        t0 = t

        def run() -> list[float]:
            tt = t0
            s.setFloat64([vr["fx"], vr["fy"]], [0.2, -0.1])
            for _ in range(2000):
                s.doStep(currentCommunicationPoint=tt, communicationStepSize=1e-3)
                tt += 1e-3
            out = s.getFloat64([vr[n] for n in names])
            out.append(float(s.getInt64([vr["contact_count"]])[0]))
            return out

        first = run()
        s.setFMUState(saved)
        s.setFloat64([vr["fx"], vr["fy"]], [0.0, 0.0])
        second = run()
        restored = s.deserializeFMUState(data)
        s.setFMUState(restored)
        third = run()
        assert first == second == third
        s.freeFMUState(saved)
        s.freeFMUState(restored)
    finally:
        s.freeInstance()
        shutil.rmtree(unzipped, ignore_errors=True)


def test_bad_values_are_refused_with_a_message_naming_them() -> None:
    messages: list[str] = []

    def logger(env, status, category, message) -> None:  # type: ignore[no-untyped-def]
        messages.append(message.decode())

    md = read_model_description(str(FMUS["3.0"]))
    unzipped = extract(str(FMUS["3.0"]))
    s = FMU3Slave(guid=md.guid, unzipDirectory=unzipped,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bad")
    vr = {v.name: v.valueReference for v in md.modelVariables}
    try:
        s.instantiate(logMessage=logger)
        with pytest.raises(FMICallException):
            s.setFloat64([vr["speed_ratio"]], [-1.0])
        assert "speed_ratio = -1 is out of range" in messages[-1] and "[0.001, 100]" in messages[-1]
        with pytest.raises(FMICallException):
            s.setFloat64([vr["k_xx"]], [math.nan])
        assert "k_xx" in messages[-1] and "NaN" in messages[-1]
        with pytest.raises(FMICallException):
            s.setFloat64([12345], [1.0])
        assert "12345" in messages[-1]
        s.enterInitializationMode(startTime=0.0)
        s.exitInitializationMode()
        with pytest.raises(FMICallException):
            s.setFloat64([vr["fx"]], [math.inf])
        assert "force_x" in messages[-1] or "fx" in messages[-1]
        with pytest.raises(FMICallException):
            s.setFloat64([vr["x0"]], [0.5])
        assert "x0" in messages[-1] and "fixed" in messages[-1]
        with pytest.raises(FMICallException):
            s.doStep(currentCommunicationPoint=0.0, communicationStepSize=-1e-3)
        assert "-0.001" in messages[-1]
        with pytest.raises(FMICallException):
            s.doStep(currentCommunicationPoint=5.0, communicationStepSize=1e-3)
        assert "does not match" in messages[-1]
        # Still usable after refused values.
        s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    finally:
        s.freeInstance()
        shutil.rmtree(unzipped, ignore_errors=True)


def test_accuracy_does_not_depend_on_the_communication_step() -> None:
    """Communication steps of 1e-3, 1e-2 and 0.1 are covered by the same internal steps of
    1e-3: the outputs at common times agree to rounding."""
    stop = 10.0
    runs = {
        h: simulate_fmu(str(FMUS["3.0"]), stop_time=stop, step_size=h, output_interval=0.1,
                        output=["x", "y", "vx", "vy", "contact_count"])
        for h in (1e-3, 1e-2, 0.1)
    }
    base = np.column_stack([runs[1e-3][n] for n in ["x", "y", "vx", "vy"]])
    for h, r in runs.items():
        states = np.column_stack([r[n] for n in ["x", "y", "vx", "vy"]])
        assert states.shape == base.shape
        worst = float(np.max(np.abs(states - base)))
        print(f"communication step {h}: largest difference {worst:.1e}")
        assert worst <= 1e-12
        assert r["contact_count"][-1] == runs[1e-3]["contact_count"][-1]


def test_a_tolerance_shortens_long_internal_steps() -> None:
    """internal_step = 0.05 with a tight tolerance halves the contact steps until the error
    estimate meets it: closer to the dt = 1e-3 run than with a loose tolerance."""
    steps = int(5 * PERIOD / 1e-3)
    stop = steps * 1e-3
    fine = rr.Stepper(preset="paper", dt=1e-3).run(steps).samples.state[-1]

    def end(tolerance: float) -> np.ndarray:
        r = simulate_fmu(str(FMUS["3.0"]), stop_time=stop, step_size=stop / 10,
                         start_values={"internal_step": 0.05, "tolerance": tolerance},
                         output=["x", "y", "vx", "vy"])
        return np.array([r[n][-1] for n in ["x", "y", "vx", "vy"]])

    loose = float(np.max(np.abs(end(1e-2) - fine)))
    tight = float(np.max(np.abs(end(1e-10) - fine)))
    print(f"internal step 0.05: error {loose:.1e} (tolerance 1e-2), {tight:.1e} (1e-10)")
    assert tight < 1e-6 and tight < loose / 10


def test_slip_regime_reports_friction() -> None:
    """The friction preset's stator (isotropic K = 100, mu = 0.2): in contact the rotor slips
    (2 forward, 3 backward) or rolls (4); free is 0."""
    r = simulate_fmu(str(FMUS["3.0"]), stop_time=40.0, step_size=1e-3,
                     start_values={"k_xx": 100.0, "k_xy": 0.0, "k_yx": 0.0, "k_yy": 100.0,
                                   "friction_coefficient": 0.2},
                     output=["in_contact", "slip_regime", "normal_force"])
    contact = r["in_contact"].astype(bool)
    assert contact.any() and (~contact).any()
    assert set(np.unique(r["slip_regime"][contact])) <= {2, 3, 4}
    assert set(np.unique(r["slip_regime"][~contact])) == {0}
    assert np.all(r["normal_force"][contact] >= 0) and np.all(r["normal_force"][~contact] == 0)
