"""The FMU's reliability classes through FMPy (issue 32, items 5, 9 and 11): a long doStep is
cut by the work cap instead of blocking, every single-byte corruption of a real serialized state
is refused, a tunable parameter set takes effect as a whole whatever the order of its sets, and
array counts beyond memory are refused."""

from __future__ import annotations

import ctypes

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from fmu_helpers import FMUS, SI_FMUS, get_real, instance, set_real

STATE = ["x", "y", "vx", "vy", "normal_force"]


def run(fmi, t: float, steps: int, h: float = 1e-3) -> float:  # type: ignore[no-untyped-def]
    for _ in range(steps):
        fmi.slave.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        t += h
    return t


def test_the_issues_1e5_time_unit_step_is_discarded_not_blocking() -> None:
    """FMI 3.0 without early return: Discard, the FMU back at the step's start, usable."""
    fmi = instance(FMUS["3.0"])
    try:
        before = get_real(fmi, STATE)
        with pytest.raises(FMICallException) as refused:
            fmi.slave.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e5)
        assert refused.value.status == 2  # fmi3Discard
        assert "max_internal_steps" in fmi.messages[-1]
        assert get_real(fmi, STATE) == before
        run(fmi, 0.0, 10)
    finally:
        fmi.close()


def test_capped_steps_with_early_return_and_in_fmi2() -> None:
    fmi = instance(FMUS["3.0"], early_return=True, initialize=False)
    try:
        fmi.slave.setInt32([fmi.vr["max_internal_steps"]], [250])
        fmi.slave.enterInitializationMode(startTime=0.0)
        fmi.slave.exitInitializationMode()
        _, _, early, last = fmi.slave.doStep(currentCommunicationPoint=0.0,
                                             communicationStepSize=1e5)
        assert early and last == pytest.approx(0.25, abs=1e-12)
        _, _, _, later = fmi.slave.doStep(currentCommunicationPoint=last,
                                          communicationStepSize=1e5)
        assert later > last
    finally:
        fmi.close()
    fmi2 = instance(FMUS["2.0"], initialize=False)
    try:
        fmi2.slave.setInteger([fmi2.vr["max_internal_steps"]], [1000])
        fmi2.slave.setupExperiment(startTime=0.0)
        fmi2.slave.enterInitializationMode()
        fmi2.slave.exitInitializationMode()
        with pytest.raises(FMICallException) as refused:
            fmi2.slave.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e5)
        assert refused.value.status == 2  # fmi2Discard: computed a subinterval
        reached = fmi2.slave.getRealStatus(2)  # fmi2LastSuccessfulTime
        assert 0.0 < reached <= 1.0 + 1e-9
        fmi2.slave.doStep(currentCommunicationPoint=reached, communicationStepSize=1e-3)
    finally:
        fmi2.close()


@pytest.mark.parametrize("fmu", [FMUS["3.0"], SI_FMUS["3.0"]], ids=["dimensionless", "si"])
def test_every_single_byte_corruption_of_a_real_state_is_refused(fmu) -> None:  # type: ignore[no-untyped-def]
    fmi = instance(fmu)
    try:
        h = 1e-3 if fmu == FMUS["3.0"] else 1e-6
        run(fmi, 0.0, 3000, h)
        state = fmi.slave.getFMUState()
        data = bytes(fmi.slave.serializeFMUState(state))
        fmi.slave.freeFMUState(state)
        accepted = []
        for k in range(len(data)):
            for flip in (0x01, 0x80, 0xFF):
                corrupt = bytearray(data)
                corrupt[k] ^= flip
                try:
                    restored = fmi.slave.deserializeFMUState(bytes(corrupt))
                except FMICallException:
                    continue
                accepted.append((k, flip))
                fmi.slave.freeFMUState(restored)
        assert not accepted, f"{len(accepted)} of {3 * len(data)} corruptions accepted"
        assert "corrupted" in fmi.messages[-1] or "marker" in fmi.messages[-1] \
            or "version" in fmi.messages[-1]
        fmi.slave.freeFMUState(fmi.slave.deserializeFMUState(data))
    finally:
        fmi.close()


def after_sets(sets: list[tuple[str, float]]) -> tuple[list[float], list[str]]:
    """The state after 3000 steps of 1e-3 following `sets`, made one call at a time right after
    initialization, and the messages of refused steps."""
    fmi = instance(FMUS["3.0"])
    try:
        for name, value in sets:
            set_real(fmi, name, value)
        run(fmi, 0.0, 3000)
        return get_real(fmi, STATE), fmi.messages
    finally:
        fmi.close()


def test_a_parameter_set_takes_effect_as_a_whole_whatever_the_order() -> None:
    forward = after_sets([("friction_coefficient", 0.2), ("k_xy", 50.0), ("k_yx", -50.0)])
    backward = after_sets([("k_yx", -50.0), ("k_xy", 50.0), ("friction_coefficient", 0.2)])
    assert forward == backward
    # Set before initialization, as one set: the same run as set after it, before any step.
    fmi = instance(FMUS["3.0"], start={"friction_coefficient": 0.2, "k_xy": 50.0,
                                       "k_yx": -50.0})
    try:
        run(fmi, 0.0, 3000)
        assert get_real(fmi, STATE) == forward[0]
    finally:
        fmi.close()
    # An inconsistent set is refused where it would take effect, and changes nothing.
    fmi = instance(FMUS["3.0"])
    try:
        set_real(fmi, "friction_coefficient", 0.2)
        set_real(fmi, "k_xy", 50.0)
        before = get_real(fmi, STATE)
        with pytest.raises(FMICallException):
            fmi.slave.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
        assert "friction_coefficient = 0.2" in fmi.messages[-1] and "k_xy = 50" in fmi.messages[-1]
        assert get_real(fmi, STATE) == before
        set_real(fmi, "k_yx", -50.0)
        run(fmi, 0.0, 3000)
        assert get_real(fmi, STATE) == forward[0]
    finally:
        fmi.close()


def test_array_counts_beyond_memory_are_refused() -> None:
    fmi = instance(FMUS["3.0"])
    try:
        huge = 2**62
        vr = (ctypes.c_uint32 * 1)(fmi.vr["x"])
        out = (ctypes.c_double * 1)()
        with pytest.raises(FMICallException):
            fmi.slave.fmi3GetFloat64(fmi.slave.component, vr, huge, out, huge)
        assert "cannot exist in memory" in fmi.messages[-1]
        with pytest.raises(FMICallException):
            fmi.slave.fmi3SetFloat64(fmi.slave.component, vr, huge, out, huge)
        run(fmi, 0.0, 10)
        assert np.isfinite(get_real(fmi, STATE)).all()
    finally:
        fmi.close()
