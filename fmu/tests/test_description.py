"""What the FMUs declare (issue 33, item 7): each output's dependencies on the inputs (no direct
feedthrough of the states, so the README's PD loop has no algebraic loop), the log categories,
and the documentation inside each FMU."""

from __future__ import annotations

import zipfile

import pytest
from fmpy import read_model_description

from fmu_helpers import ALL_FMUS, FMUS, instance

CATEGORIES = {"logEvents", "logStatusDiscard", "logStatusError", "logStatusFatal"}


@pytest.mark.parametrize("name", ALL_FMUS)
def test_each_output_declares_its_dependencies(name: str) -> None:
    md = read_model_description(str(ALL_FMUS[name]), validate=True,
                                validate_model_structure=True)
    speed = "speed" if "_si_" in name else "speed_ratio"
    declared = {o.variable.name: o.dependencies for o in md.outputs}
    assert set(declared) == {"x", "y", "vx", "vy", "in_contact", "normal_force",
                             "contact_count", "slip_regime", "xs", "ys", "vxs", "vys"}
    for output, depends in declared.items():
        assert depends is not None, f"{output}: dependencies not declared (means: on all)"
        names = {d.name for d in depends}
        if output in ("in_contact", "slip_regime"):
            assert names == {speed}, output
        else:
            assert names == set(), output


@pytest.mark.parametrize("name", ALL_FMUS)
def test_the_pd_loop_over_positions_and_velocities_has_no_algebraic_loop(name: str) -> None:
    """A controller that sets fx, fy from x, y, vx, vy (the README's loop): the loop is
    algebraic only if one of those outputs depends directly on fx or fy."""
    md = read_model_description(str(ALL_FMUS[name]))
    measured = {"x", "y", "vx", "vy"}
    for o in md.outputs:
        if o.variable.name in measured:
            assert not {d.name for d in o.dependencies} & {"fx", "fy"}


def test_the_outputs_do_not_move_when_the_force_inputs_change() -> None:
    """The declaration checked against the FMU: setting fx, fy at a communication point
    changes none of the outputs there (FMI 2.0 allows a get after a set)."""
    fmi = instance(FMUS["2.0"])
    try:
        t = 0.0
        for _ in range(2500):
            fmi.slave.doStep(currentCommunicationPoint=t, communicationStepSize=1e-3)
            t += 1e-3
        names = ["x", "y", "vx", "vy", "normal_force"]
        refs = [fmi.vr[n] for n in names]
        before = fmi.slave.getReal(refs), fmi.slave.getInteger([fmi.vr["contact_count"]])
        fmi.slave.setReal([fmi.vr["fx"], fmi.vr["fy"]], [50.0, -80.0])
        after = fmi.slave.getReal(refs), fmi.slave.getInteger([fmi.vr["contact_count"]])
        assert before == after
        fmi.slave.doStep(currentCommunicationPoint=t, communicationStepSize=1e-3)
        assert fmi.slave.getReal(refs) != before[0], "the inputs act over the next step"
    finally:
        fmi.close()


def test_slip_regime_moves_with_the_speed_input_as_declared() -> None:
    """The declared dependency is real: rolling (dry whip: isotropic K = 300, mu = 0.6,
    R/clearance = 2), a new speed re-decides the slip at once, before any step."""
    fmi = instance(FMUS["2.0"], start={"k_xx": 300.0, "k_xy": 0.0, "k_yx": 0.0, "k_yy": 300.0,
                                       "offset_x": 0.0, "offset_y": 0.0,
                                       "friction_coefficient": 0.6, "radius_ratio": 2.0})
    try:
        regime = fmi.vr["slip_regime"]
        t = 0.0
        while t < 40.0 and not (t > 2.0 and fmi.slave.getInteger([regime])[0] == 4):
            fmi.slave.doStep(currentCommunicationPoint=t, communicationStepSize=1e-3)
            t += 1e-3
        assert fmi.slave.getInteger([regime])[0] == 4, "rolling"
        fmi.slave.setReal([fmi.vr["speed_ratio"]], [0.5])
        assert fmi.slave.getInteger([regime])[0] == 3, "slipping backward at once"
    finally:
        fmi.close()


@pytest.mark.parametrize("name", ALL_FMUS)
def test_log_categories_and_documentation_are_in_the_fmu(name: str) -> None:
    md = read_model_description(str(ALL_FMUS[name]))
    assert {c.name if hasattr(c, "name") else c for c in md.logCategories} >= CATEGORIES
    with zipfile.ZipFile(ALL_FMUS[name]) as z:
        page = z.read("documentation/index.html").decode()
    for v in md.modelVariables:
        assert f"<code>{v.name}</code>" in page, v.name
    for topic in ["max_internal_steps", "Lyapunov", "Discard", "CRC-32", "algebraic loop"]:
        assert topic in page, topic
    for category in CATEGORIES:
        assert category in page
