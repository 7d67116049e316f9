"""The FMUs in libcosim (the Open Simulation Platform's co-simulation library, through
libcosimpy): the dimensionless FMU against the library's stepper, the SI FMU against the same FMU
in FMPy, an input override, and the work cap reported instead of a blocked step. libcosimpy's
libcosim loads FMI 1.0 and 2.0 FMUs only ("Unsupported FMI version" for 3.0): the FMI 2.0 FMUs
are tested here, the 3.0 ones in FMPy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fmpy import simulate_fmu

import rotor_rub as rr
from fmu_helpers import FMUS, SI_FMUS

libcosim = pytest.importorskip("libcosimpy.CosimExecution")
from libcosimpy.CosimExecution import CosimExecution  # noqa: E402
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level  # noqa: E402
from libcosimpy.CosimManipulator import CosimManipulator  # noqa: E402
from libcosimpy.CosimObserver import CosimObserver  # noqa: E402
from libcosimpy.CosimSlave import CosimLocalSlave  # noqa: E402

log_output_level(CosimLogLevel.WARNING)

PERIOD = 2 * math.pi / 1.5  # the paper preset's forcing period
STATE = [1, 2, 3, 4]  # x, y, vx, vy
CONTACT_COUNT, MAX_INTERNAL_STEPS, FX, FY = 7, 202, 10, 11


class Run:
    """One FMU in a libcosim execution with a fixed step (nanoseconds)."""

    def __init__(self, fmu, step_ns: int) -> None:  # type: ignore[no-untyped-def]
        self.execution = CosimExecution.from_step_size(step_size=step_ns)
        self.slave = CosimLocalSlave(fmu_path=str(fmu), instance_name="rotor")
        assert self.slave.ptr(), "libcosim could not load the FMU"
        self.index = self.execution.add_local_slave(local_slave=self.slave)
        self.observer = CosimObserver.create_last_value()
        self.execution.add_observer(observer=self.observer)
        self.manipulator = CosimManipulator.create_override()
        self.execution.add_manipulator(manipulator=self.manipulator)

    def state(self) -> np.ndarray:
        return np.array(self.observer.last_real_values(slave_index=self.index,
                                                       variable_references=STATE))

    def contact_count(self) -> int:
        return int(self.observer.last_integer_values(
            slave_index=self.index, variable_references=[CONTACT_COUNT])[0])


def test_twenty_periods_in_libcosim_match_the_library_stepper() -> None:
    steps = int(20 * PERIOD / 1e-3)
    run = Run(FMUS["2.0"], step_ns=1_000_000)  # libcosim's clock in ns: "1 ms" = τ step 1e-3
    assert run.execution.step(step_count=steps)
    library = rr.Stepper(preset="paper", dt=1e-3).run(steps)
    worst = float(np.max(np.abs(run.state() - library.samples.state[-1])))
    print(f"libcosim, 20 periods: largest difference from the library stepper {worst:.1e}")
    assert worst <= 1e-12
    assert run.contact_count() == int(np.sum(library.events.kind == "enter")) > 40


def test_the_si_fmu_and_an_input_override_match_fmpy() -> None:
    """The SI FMU at 10 µs steps for 50 ms with fx, fy overridden by libcosim, against FMPy
    with the same inputs."""
    fx, fy = 150.0, -90.0  # N
    steps = 5000
    run = Run(SI_FMUS["2.0"], step_ns=10_000)
    run.manipulator.slave_real_values(slave_index=run.index, variable_references=[FX, FY],
                                      values=[fx, fy])
    assert run.execution.step(step_count=steps)
    fmpy = simulate_fmu(str(SI_FMUS["2.0"]), stop_time=steps * 1e-5, output_interval=1e-5,
                        start_values={"fx": fx, "fy": fy}, output=["x", "y", "vx", "vy"])
    expected = np.array([fmpy[n][-1] for n in ["x", "y", "vx", "vy"]])
    scale = np.max(np.abs(expected))
    relative = float(np.max(np.abs(run.state() - expected)) / scale)
    print(f"libcosim vs FMPy, SI FMU with an input force: relative difference {relative:.1e}")
    assert relative <= 1e-10
    free = simulate_fmu(str(SI_FMUS["2.0"]), stop_time=steps * 1e-5, output_interval=1e-5,
                        output=["x"])
    assert abs(free["x"][-1] - expected[0]) > 1e-3 * scale, "the override acted"


def test_a_huge_step_is_reported_by_the_work_cap_not_blocking() -> None:
    """A step of 1e5 time units: the FMU ends it at its work cap with fmi2Discard, which
    libcosim reports as a failed step (instead of a step that computes for minutes)."""
    run = Run(FMUS["2.0"], step_ns=10**14)  # 1e5 "seconds" of τ
    run.execution.integer_initial_value(slave_index=run.index,
                                        variable_reference=MAX_INTERNAL_STEPS, value=20_000)
    assert not run.execution.step(step_count=1)
