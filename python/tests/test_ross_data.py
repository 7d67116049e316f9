"""ROSS's missed and invented switches on a Jeffcott rotor (issue 29 item 3: "where [ROSS's step]
is not [fine enough], show what it misses"), over the checked-in data of
``scripts/ross/run jeffcott_rubbing.py`` and ``scripts/ross/compare.py --jeffcott`` (ROSS is not
run here): rotor-rub on the same 20-DOF model still finds the recorded switches, every method
agrees on them, ROSS's default step misses contacts rotor-rub finds and invents others, and
ROSS's switch times converge to rotor-rub's at first order as its step shrinks."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import rotor_rub as rr

DATA = Path(__file__).resolve().parents[2] / "tests" / "data" / "ross"
ROSS = json.loads((DATA / "jeffcott_rubbing.json").read_text())
RECORD = json.loads((DATA / "jeffcott_comparison.json").read_text())


def model() -> rr.Model:
    rub, u = ROSS["rub"], ROSS["unbalance"]
    return rr.Model.from_ross(DATA / ROSS["rotor"]["matrices"], node=rub["node"],
                              clearance=rub["clearance_m"],
                              contact_stiffness=rub["contact_stiffness_N_per_m"],
                              friction_coefficient=0.0, modes=None,
                              unbalance=[(u["node"], u["m_e_kg_m"], u["phase_rad"])])


def intervals(times, directions, end):
    """Contact intervals from switch times and directions (+1 in, −1 out)."""
    out, start = [], None
    for t, d in zip(times, directions):
        if d > 0:
            start = t
        elif start is not None:
            out.append((start, t))
            start = None
    if start is not None:
        out.append((start, end))
    return out


def unmatched(these, those):
    """The intervals of `these` that no interval of `those` overlaps."""
    return [a for a in these if not any(a[0] < b[1] and b[0] < a[1] for b in those)]


@pytest.fixture(scope="module")
def ours():
    m = model()
    assert m.n == 20  # every lateral DOF: the model ROSS integrates, no reduction
    end = ROSS["periods"] * ROSS["period_s"]
    return rr.simulate(model=m, t_end=end, method="hybrid", tol=1e-12, samples=0), end


def test_rotor_rub_finds_the_recorded_switches(ours) -> None:
    run, _ = ours
    recorded = RECORD["rotor_rub"]
    assert len(run.events) == recorded["switches"] == 22
    assert np.abs(run.events.time - np.array(recorded["switch_times_s"])).max() < 1e-9
    assert [1 if k == "enter" else -1 for k in run.events.kind] == recorded["switch_directions"]


@pytest.mark.parametrize("method, tol", [("taylor", 1e-13), ("analytic", None)])
def test_another_method_agrees_on_the_switches(ours, method: str, tol) -> None:
    """(dop853 at 1e-13 agrees within 3.2e-11 too, but takes seconds: BENCHMARKS.md.)"""
    run, end = ours
    other = rr.simulate(model=model(), t_end=end, method=method, tol=tol, samples=0)
    assert list(other.events.kind) == list(run.events.kind)
    assert np.abs(other.events.time - run.events.time).max() < 1e-8


def test_ross_default_step_misses_and_invents_contacts(ours) -> None:
    run, end = ours
    contacts = intervals(run.events.time, [1 if k == "enter" else -1 for k in run.events.kind],
                         end)
    default = next(r for r in ROSS["runs"] if r["step_s"] == 1e-4)  # ROSS's tutorial step
    theirs = intervals(default["switch_times_s"], default["switch_directions"], end)
    missed, invented = unmatched(contacts, theirs), unmatched(theirs, contacts)
    assert default["switches"] == 19 != len(run.events)
    assert len(missed) == 2 and len(invented) == 4
    # The record says the same.
    entry = next(r for r in RECORD["ross"] if r["step_s"] == 1e-4)
    assert np.allclose(entry["missed_contacts_s"], missed, atol=1e-9)
    assert np.allclose(entry["invented_contacts_s"], invented, atol=1e-9)
    # And its orbit overshoots: 1.96 clearances against 1.33 at its finest step.
    assert default["max_radius_m"] > 1.4 * min(r["max_radius_m"] for r in ROSS["runs"])


def test_ross_converges_to_rotor_rub_at_first_order(ours) -> None:
    """Over the first five switches (before near-grazing contacts amplify the step's error)
    ROSS's switch times approach rotor-rub's like 4–8 h: first order (its contact force is
    taken at the step's start)."""
    run, _ = ours
    errors = []
    for r in sorted(ROSS["runs"], key=lambda r: -r["step_s"]):
        if r["step_s"] > 5e-5:
            continue
        gap = np.abs(np.array(r["switch_times_s"][:5]) - run.events.time[:5]).max()
        assert 2 * r["step_s"] < gap < 10 * r["step_s"], (r["step_s"], gap)
        errors.append(gap)
    assert len(errors) == 4 and errors == sorted(errors, reverse=True)
