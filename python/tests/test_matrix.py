"""Rotors from matrices (issue 29): rr.Model.from_matrices / from_file / from_ross, rr.Rub,
validation (ValueError naming the value and the range), the model files agreeing with Python,
the reduction of the checked-in ROSS rotor, pickling, the result assembly and the plot."""

from __future__ import annotations

import json
import pickle
from pathlib import Path

import numpy as np
import pytest

import rotor_rub as rr
from rotor_rub import _core
from rotor_rub._model import _run_of, craig_bampton

ROOT = Path(__file__).resolve().parents[2]
TWO_DISK = ROOT / "examples" / "models" / "two_disk.toml"
TWO_DISK_NPZ = ROOT / "examples" / "models" / "two_disk.npz"
ROSS = ROOT / "tests" / "data" / "ross" / "rotor_example_with_damping.npz"
ROSS_NOTE = ROOT / "tests" / "data" / "ross" / "rotor_example_with_damping.json"


def jeffcott(**rub):
    """A Jeffcott rotor in SI: 2 kg, k = 2e4 N/m (ω_n = 100 rad/s), ζ = 0.01, at 150 rad/s with
    an unbalance whose free whirl (1.8 mm) exceeds the 1 mm clearance."""
    kw = dict(clearance=1e-3, contact_stiffness=1e6)
    kw.update(rub)
    return rr.Model.from_matrices(2 * np.eye(2), 4 * np.eye(2), 2e4 * np.eye(2),
                                  unbalance=[(0, 1, 2e-3, 0.0)], rub=rr.Rub(0, 1, **kw),
                                  speed=150.0, dofs=["x", "y"])


def test_from_matrices_states_the_model():
    m = jeffcott()
    assert m.n == 2 and m.dofs == ("x", "y")
    lam = m.modes()
    assert lam.dtype == np.complex128 and len(lam) == 4
    assert np.allclose(np.abs(lam), 100.0) and np.allclose(lam.real, -1.0)
    assert np.allclose(m.natural_frequencies(), np.sqrt(1e4 - 1))
    assert m.station.clearance == 1e-3 and m.station.stator is None
    assert m.columns() == ["x", "y", "vx", "vy", "rub_x", "rub_y"]
    text = repr(m)
    assert "n = 2" in text and "clearance 0.001 m" in text and "fixed stator" in text
    with pytest.raises(ValueError):
        m.M[0, 0] = 5.0  # read-only: a model does not change under its runs


def test_dof_names_and_stator_pairs():
    M = np.diag([1.0, 1.0, 3.0, 3.0])
    K = np.array([[2e4, 0, -1e4, 0], [0, 2e4, 0, -1e4], [-1e4, 0, 3e4, 0], [0, -1e4, 0, 3e4]])
    m = rr.Model.from_matrices(M, 0.001 * K, K, dofs=["x", "y", "xs", "ys"],
                               unbalance=[("x", "y", 1e-4, 0.0)], speed=100.0,
                               rub=rr.Rub("x", "y", 1e-3, [[1e6, 0], [0, 2e6]],
                                          stator=("xs", "ys")))
    assert m.station.dof_x == 0 and m.station.stator == (2, 3)
    assert m.station.contact_stiffness == ((1e6, 0.0), (0.0, 2e6))
    assert "stator point (xs, ys)" in repr(m)


@pytest.mark.parametrize("change, needles", [
    (dict(M=np.eye(3)), ["C is 2 × 2", "3 × 3"]),
    (dict(M=np.array([[1.0, 0.5], [0.0, 1.0]])), ["M", "symmetric"]),
    (dict(M=-np.eye(2)), ["M", "positive definite"]),
    (dict(M=np.ones(2)), ["M", "2-D"]),
    (dict(C=np.full((2, 2), np.nan)), ["C", "not a finite number"]),
    (dict(speed=-3.0), ["speed = -3", "rad/s"]),
    (dict(speed="fast"), ["speed", "real number"]),
    (dict(unbalance=[(0, 0, 1e-4, 0.0)]), ["unbalance[0].dof_y", "two different"]),
    (dict(unbalance=[(0, 5, 1e-4, 0.0)]), ["unbalance[0].dof_y = 5", "[0, 1]"]),
    (dict(unbalance=[(0, 1, -1e-4, 0.0)]), ["unbalance[0].m_e", "≥ 0"]),
    (dict(unbalance=[(0, 1, 1e-4)]), ["unbalance[0]", "(dof_x, dof_y, m_e, phase)"]),
    (dict(unbalance=[(-1, 1, 1e-4, 0.0)]), ["unbalance[0].dof_x = -1", "≥ 0"]),
    (dict(dofs=["x"]), ["dofs has 1 names", "n = 2"]),
    (dict(rub="here"), ["rub", "rotor_rub.Rub"]),
])
def test_bad_matrices_are_value_errors_naming_the_value(change, needles):
    kw = dict(M=2 * np.eye(2), C=4 * np.eye(2), K=2e4 * np.eye(2),
              unbalance=[(0, 1, 1e-4, 0.0)], rub=rr.Rub(0, 1, 1e-3, 1e6), speed=150.0)
    kw.update(change)
    with pytest.raises(ValueError) as e:
        rr.Model.from_matrices(kw.pop("M"), kw.pop("C"), kw.pop("K"), **kw)
    for needle in needles:
        assert needle in str(e.value), (needle, str(e.value))


@pytest.mark.parametrize("rub, needles", [
    (dict(clearance=0.0), ["rub.clearance = 0", "> 0", "(m)"]),
    (dict(clearance=float("inf")), ["rub.clearance", "finite"]),
    (dict(contact_stiffness=-1.0), ["rub.contact_stiffness", "positive definite"]),
    (dict(contact_stiffness=[1.0, 2.0]), ["rub.contact_stiffness", "2 × 2"]),
    (dict(friction_coefficient=0.2), ["rub.radius", "missing"]),
    (dict(friction_coefficient=-0.2, radius=0.05), ["rub.friction_coefficient = -0.2"]),
    (dict(radius=-0.05), ["rub.radius = -0.05", "> 0"]),
    (dict(offset=(0.1, 0.0)), ["rub.offset", "clearances"]),
    (dict(offset=3.0), ["rub.offset", "pair"]),
    (dict(stator=(0, 1)), ["rub.stator", "four different"]),
    (dict(stator=(5,)), ["rub.stator", "pair"]),
    (dict(stator=3), ["rub.stator", "pair"]),
])
def test_bad_rubs_are_value_errors(rub, needles):
    with pytest.raises(ValueError) as e:
        jeffcott(**rub)
    for needle in needles:
        assert needle in str(e.value), (needle, str(e.value))


def test_rub_dofs_must_be_indices_or_names():
    with pytest.raises(ValueError, match="rub.dof_x = 1.5"):
        rr.Rub(1.5, 0, 1e-3, 1e6)
    with pytest.raises(ValueError, match="rub.dof_y = True"):
        rr.Rub(0, True, 1e-3, 1e6)
    with pytest.raises(ValueError, match="'z' is not a degree of freedom"):
        rr.Model.from_matrices(np.eye(2), np.eye(2), np.eye(2) * 1e4, dofs=["x", "y"],
                               rub=rr.Rub("z", "y", 1e-3, 1e6), speed=10.0)


def test_python_and_model_files_agree():
    toml = rr.Model.from_file(TWO_DISK)
    npz = rr.Model.from_file(TWO_DISK_NPZ)
    assert toml.n == 8 and toml.dofs == npz.dofs
    # The same model stated from its matrices in Python.
    py = rr.Model.from_matrices(toml.M, toml.C, toml.K, toml.G, unbalance=toml.unbalance,
                                rub=toml.station, speed=toml.speed, dofs=toml.dofs,
                                name=toml.name)
    assert py == toml
    assert np.array_equal(py.modes(), toml.modes())
    # The TOML prints the .npz's matrices to 10 digits.
    a, b = npz.modes(), toml.modes()
    assert np.allclose(np.sort(a.imag), np.sort(b.imag), rtol=1e-8)
    assert np.allclose(np.sort(a.real), np.sort(b.real), rtol=1e-8)
    assert abs(abs(toml.modes()[0]) - 302.75) < 0.01


def test_save_round_trips_through_the_cli_format(tmp_path):
    m = rr.Model.from_file(TWO_DISK)
    path = tmp_path / "model.npz"
    m.save(path)
    back = rr.Model.from_file(path)
    assert back.dofs == m.dofs and back.station == m.station and back.unbalance == m.unbalance
    for a, b in ((back.M, m.M), (back.C, m.C), (back.G, m.G), (back.K, m.K)):
        assert np.array_equal(a, b)


def test_model_file_errors_are_value_errors(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(TWO_DISK.read_text().replace("clearance = 2.0e-4", "clearance = -2.0e-4"))
    with pytest.raises(ValueError, match=r"bad.toml: line \d+: rub.clearance = -2e-4 is out of range"):
        rr.Model.from_file(bad)
    with pytest.raises(ValueError, match="cannot read"):
        rr.Model.from_file(tmp_path / "absent.toml")


def test_speed_dependent_matrices():
    m = jeffcott()
    k = np.eye(2)
    sd = rr.Model.from_matrices(m.M, m.C, m.K, unbalance=m.unbalance, rub=m.station,
                                speed=150.0, speed_dependent=[(100.0, None, 1e4 * k),
                                                              (200.0, None, 3e4 * k)])
    # K(150) = 2e4 I: the same modes as the speed-independent model.
    assert np.allclose(sd.modes(), m.modes())
    assert np.allclose(sd.with_speed(100.0).natural_frequencies(), np.sqrt(5e3 - 1))
    with pytest.raises(ValueError, match=r"speed = 250.*\[100, 200\]"):
        sd.with_speed(250.0)


def test_pickling_keeps_the_model():
    m = rr.Model.from_file(TWO_DISK)
    back = pickle.loads(pickle.dumps(m))
    assert back == m and repr(back) == repr(m)
    assert not back.M.flags.writeable
    assert np.array_equal(back.modes(), m.modes())
    r = pickle.loads(pickle.dumps(rr.Rub(0, 1, 1e-3, [[1e6, 0], [0, 1e6]])))
    assert r.contact_stiffness == ((1e6, 0.0), (0.0, 1e6))


def ross_model(modes):
    return rr.Model.from_ross(ROSS, node=12, clearance=7.95e-5, contact_stiffness=1.1e6,
                              unbalance=[(12, 2e-4, -np.pi / 2)], modes=modes)


def test_from_ross_reduces_the_checked_in_rotor():
    note = json.loads(ROSS_NOTE.read_text())
    full = np.array([im for _, im in note["eigenvalues_rad_s"]])
    m = ross_model(12)
    assert m.n == 2 + 12 and m.dofs[:2] == ("x_12", "y_12")
    assert m.station.dof_x == 0 and m.station.dof_y == 1 and m.unbalance[0][:2] == (0, 1)
    assert m.reduction["full_dofs"] == 136 and m.reduction["physical"] == ["x_12", "y_12"]
    f = m.natural_frequencies()
    # The reduction keeps the first six damped natural frequencies within 1e-3 of ROSS's model.
    rel = np.abs(f[:6] - full[:6]) / full[:6]
    assert rel.max() < 1e-3, rel
    for fr, rd, err in m.reduction["frequency_error"]:
        assert err == pytest.approx(abs(rd - fr) / fr)
    # More modes, smaller error.
    more = ross_model(24).natural_frequencies()
    assert (np.abs(more[:6] - full[:6]) / full[:6]).max() <= rel.max() * 1.0001
    assert "reduced from 136 DOFs" in repr(m)


def test_from_ross_refuses_what_it_cannot_do():
    with pytest.raises(ValueError, match="136 lateral DOFs.*modes="):
        ross_model(None)
    with pytest.raises(ValueError, match="node = 99 is not a node of the rotor"):
        rr.Model.from_ross(ROSS, node=99, clearance=7.95e-5, contact_stiffness=1.1e6,
                           modes=4)
    with pytest.raises(ValueError, match="modes = -1"):
        ross_model(-1)
    with pytest.raises(ValueError, match="export holds the matrices at"):
        rr.Model.from_ross(ROSS, node=12, clearance=7.95e-5, contact_stiffness=1.1e6,
                           speed=10.0, modes=4)
    with pytest.raises(ValueError, match="not a ross.Rotor"):
        rr.Model.from_ross(object(), node=12, clearance=7.95e-5, contact_stiffness=1.1e6,
                           speed=10.0, modes=4)


class FakeRoss:
    """A ross.Rotor's interface over the exported matrices padded to 6 DOFs per node (z and θ
    decoupled), to test the ROSS path without ROSS."""

    number_dof = 6

    def __init__(self):
        with np.load(ROSS) as d:
            self.lat = {k: d[k] for k in ("M", "C", "K", "G")}
        nodes = 34
        self.ndof = 6 * nodes
        lateral = [i for i in range(self.ndof) if i % 6 in (0, 1, 3, 4)]
        self.full = {}
        for k, a in self.lat.items():
            f = np.zeros((self.ndof, self.ndof))
            f[np.ix_(lateral, lateral)] = a
            other = [i for i in range(self.ndof) if i % 6 in (2, 5)]
            if k in ("M", "K"):
                f[other, other] = 1.0
            self.full[k] = f

    def M(self, speed):
        return self.full["M"]

    def K(self, speed):
        return self.full["K"]

    def C(self, speed):
        return self.full["C"]

    def G(self):
        return self.full["G"]


def test_from_ross_reads_a_rotor_object_like_its_export():
    with np.load(ROSS) as d:
        speed = float(d["speed"])
    a = rr.Model.from_ross(FakeRoss(), node=12, clearance=7.95e-5, contact_stiffness=1.1e6,
                           speed=speed, modes=8, unbalance=[(12, 2e-4, 0.0)])
    b = rr.Model.from_ross(ROSS, node=12, clearance=7.95e-5, contact_stiffness=1.1e6,
                           modes=8, unbalance=[(12, 2e-4, 0.0)])
    assert a.dofs == b.dofs
    assert np.allclose(a.M, b.M) and np.allclose(a.K, b.K) and np.allclose(a.G, b.G)


def test_craig_bampton_keeps_statics_exactly():
    rng = np.random.default_rng(1)
    A = rng.normal(size=(10, 10))
    K = A @ A.T + 10 * np.eye(10)
    M = np.eye(10) + 0.1 * (lambda B: B @ B.T)(rng.normal(size=(10, 10)))
    C = 0.01 * K
    G = np.zeros((10, 10))
    G[0, 1], G[1, 0] = 1.0, -1.0
    keep = [3, 7]
    Mr, Cr, Kr, Gr, T = craig_bampton(M, C, K, G, keep, 3)
    # A static load at the kept DOFs: the reduced model's displacement there is exact.
    f = np.zeros(10)
    f[3], f[7] = 1.0, -2.0
    exact = np.linalg.solve(K, f)[keep]
    reduced = np.linalg.solve(Kr, T.T @ f)[:2]
    assert np.allclose(reduced, exact, rtol=1e-12)
    assert np.allclose(Gr, -Gr.T) and np.allclose(Mr, Mr.T)
    # All modes kept: the same eigenvalues as the full model.
    Mf, Cf, Kf, Gf, _ = craig_bampton(M, C, K, G, keep, 8)
    full = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    red = np.sort(np.linalg.eigvals(np.linalg.solve(Mf, Kf)).real)
    assert np.allclose(full, red, rtol=1e-9)
    with pytest.raises(ValueError, match="modes = 9 is out of range"):
        craig_bampton(M, C, K, G, keep, 9)


def test_simulate_routes_model_runs():
    m = jeffcott()
    with pytest.raises(ValueError, match="preset do"):
        rr.simulate(model=m, preset="paper")
    with pytest.raises(ValueError, match="speed_ratio"):
        rr.simulate(model=m, speed_ratio=2.0)
    with pytest.raises(ValueError, match="initial= needs model="):
        rr.simulate(initial=[0.0, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="must be a rotor_rub.Model"):
        rr.simulate(model="two_disk.toml")
    with pytest.raises(ValueError, match="initial has 3 entries"):
        rr.simulate(model=m, periods=2, initial=[0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="t_end or periods, not both"):
        rr.simulate(model=m, t_end=1.0, periods=2)
    with pytest.raises(ValueError, match="method"):
        rr.simulate(model=m, method="euler")


def test_simulate_a_model_run():
    m = jeffcott()
    run = rr.simulate(model=m, periods=20, samples=201, method="hybrid")
    assert isinstance(run, rr.MatrixRun) and isinstance(run, rr.Run)
    assert run.columns == tuple(m.columns())
    assert run.samples.state.shape == (201, 6)
    assert run.end_time == pytest.approx(20 * 2 * np.pi / 150.0)
    # Above the critical speed the unbalance whirls the rotor beyond the clearance: it rubs.
    assert len(run.events) > 0 and set(run.events.kind[:2]) == {"enter", "exit"}
    r = np.hypot(run.events.state[:, 4], run.events.state[:, 5])
    assert np.allclose(r, 1e-3, rtol=1e-9)  # every switch on the clearance circle, SI
    assert np.array_equal(run.column("rub_x"), run.column("x"))  # fixed stator: P = q
    assert run.problem.method == "hybrid" and run.problem.params["clearance"] == 1e-3
    assert 0.0 < run.contact_fraction < 1.0
    # Every method finds the same switches.
    ref = rr.simulate(model=m, periods=20, samples=0, method="dop853", tol=1e-12)
    assert len(ref.events) == len(run.events)
    gap = np.abs(ref.events.time - run.events.time)
    assert gap[:10].max() < 1e-9 and gap.max() < 1e-6, gap  # s; heavy rub: errors grow
    # A start: positions then velocities, SI.
    moved = rr.simulate(model=m, periods=1, samples=2, initial=[5e-4, 0, 0, 0])
    assert moved.samples.state[0, 0] == pytest.approx(5e-4)


def test_simulate_a_model_file_as_the_cli_does(cli, tmp_path):
    import subprocess

    events = tmp_path / "ev.csv"
    subprocess.run([str(cli), "simulate", "--model", str(TWO_DISK), "--periods", "5",
                    "--method", "hybrid", "--events", str(events)], check=True,
                   capture_output=True)
    lines = events.read_text().splitlines()
    header = lines[0].split(",")
    run = rr.simulate(model=rr.Model.from_file(TWO_DISK), periods=5, method="hybrid",
                      samples=0)
    assert header == ["t", "kind"] + list(run.columns)
    rows = [line.split(",") for line in lines[1:]]
    assert [float(r[0]) for r in rows] == list(run.events.time)
    assert [r[1] for r in rows] == list(run.events.kind)
    assert np.array_equal(np.array([[float(x) for x in r[2:]] for r in rows]),
                          run.events.state)


def synthetic_run(model):
    """A run assembled from synthetic events and samples by the same code as a real one."""
    w = len(model.columns())
    n = model.n
    t = np.linspace(0.0, 0.2, 101)
    samples = []
    for ti in t:
        q = np.zeros(2 * n)
        q[model.station.dof_x] = 1.2e-3 * np.cos(150 * ti)
        q[model.station.dof_y] = 1.2e-3 * np.sin(150 * ti)
        if model.station.stator is not None:
            q[model.station.stator[0]] = 2e-4 * np.cos(150 * ti)
            q[model.station.stator[1]] = 2e-4 * np.sin(150 * ti)
        p = q[[model.station.dof_x, model.station.dof_y]]
        if model.station.stator is not None:
            p = p - q[list(model.station.stator)]
        row = list(q) + list(p)
        assert len(row) == w
        samples.append((float(ti), 1 if np.hypot(*p) > 1e-3 else 0, row))
    events = [(samples[10][0], 0, samples[10][2]), (samples[20][0], 1, samples[20][2])]
    return _run_of(_core.matrix_result_of(model._core_dict(), events, samples), model, {})


def test_the_result_assembly():
    m = jeffcott()
    run = synthetic_run(m)
    assert run.samples.state.shape == (101, 6) and run.events.state.shape == (2, 6)
    assert list(run.events.kind) == ["enter", "exit"]
    assert run.end_time == pytest.approx(0.2) and run.forcing_period == pytest.approx(
        2 * np.pi / 150)
    assert run.time_contact == pytest.approx(0.2) and run.contact_fraction == pytest.approx(1)
    assert run.problem.params["clearance"] == 1e-3 and run.problem.method == "hybrid"
    assert np.array_equal(run.column("x"), run.samples.state[:, 0])
    with pytest.raises(ValueError, match="'z' is not a state column"):
        run.column("z")
    with pytest.raises(ValueError, match="a state row has 3 entries"):
        _core.matrix_result_of(m._core_dict(), [(0.0, 0, [0.0, 0.0, 0.0])], [])


def test_rub_orbit_plot(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rotor_rub import plot

    ax = plot.rub_orbit(synthetic_run(jeffcott()))
    assert ax.get_title().startswith("Rub station (x, y)")
    ax.figure.savefig(tmp_path / "rub.png")
    plt.close(ax.figure)
    M = np.diag([1.0, 1.0, 3.0, 3.0])
    K = np.array([[2e4, 0, -1e4, 0], [0, 2e4, 0, -1e4], [-1e4, 0, 3e4, 0],
                  [0, -1e4, 0, 3e4]])
    ring = rr.Model.from_matrices(M, 0.001 * K, K, dofs=["x", "y", "xs", "ys"],
                                  unbalance=[("x", "y", 1e-4, 0.0)], speed=150.0,
                                  rub=rr.Rub("x", "y", 1e-3, 1e6, stator=("xs", "ys")))
    ax = plot.rub_orbit(synthetic_run(ring))
    axes = ax.figure.axes
    assert len(axes) == 2 and axes[1].get_title() == "Rotor and stator orbits"
    ax.figure.savefig(tmp_path / "ring.png")
    assert (tmp_path / "ring.png").stat().st_size > 1000
    plt.close(ax.figure)


def test_the_stator_ring_with_mass_runs_as_the_cli(cli, tmp_path):
    """stator_mass_ratio > 0: the n = 4 ring model; the rotor's columns first, the ring's
    after them, the same switches as `rotor-rub simulate --set stator_mass_ratio=…`."""
    import subprocess

    run = rr.simulate(stator_mass_ratio=1.0, periods=10, samples=11, method="hybrid")
    assert run.samples.state.shape == (11, 8) and run.events.state.shape[1] == 8
    assert run.problem.params["stator_mass_ratio"] == 1.0
    xs = run.events.state[:, 4:6]
    assert np.hypot(xs[:, 0], xs[:, 1]).max() > 0.01  # the ring moves
    events = tmp_path / "ring.csv"
    subprocess.run([str(cli), "simulate", "--set", "stator_mass_ratio=1", "--periods", "10",
                    "--method", "hybrid", "--events", str(events)], check=True,
                   capture_output=True)
    lines = events.read_text().splitlines()
    assert lines[0] == "tau,kind,x,y,vx,vy,xs,ys,vxs,vys"
    assert [float(r.split(",")[0]) for r in lines[1:]] == list(run.events.time)
    with pytest.raises(ValueError, match="contact_stiffness"):
        rr.simulate(contact_stiffness=10.0, periods=1)


def test_the_docs_examples_run(monkeypatch):
    """docs/PYTHON.md's "Rotors from matrices" examples, as shown, from the repository root
    (the one that needs ROSS only where ROSS is installed)."""
    import importlib.util

    page = (ROOT / "docs" / "PYTHON.md").read_text()
    blocks = page.split("<!-- matrix-example")[1:]
    assert len(blocks) == 3
    monkeypatch.chdir(ROOT)
    for block in blocks:
        code = block[block.index("```python\n") + 10:]
        code = code[:code.index("```")]
        if block.startswith(": needs ross") and importlib.util.find_spec("ross") is None:
            continue
        exec(compile(code, "docs/PYTHON.md", "exec"), {})


def test_the_orbit_plot_draws_the_ring(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rotor_rub import plot

    run = rr.simulate(stator_mass_ratio=1.0, periods=5, samples=201, method="hybrid")
    ax = plot.orbit(run)
    lines = {line.get_label(): line for line in ax.get_lines()}
    assert "ring centre" in lines
    # The relative orbit is the one the clearance circle bounds: at every contact start it
    # is on the circle (|x − xs − ε̂| = 1), where the rotor's own orbit is not once the ring
    # moves.
    relative = lines["rotor − ring (in contact outside the circle)"].get_xydata()
    s = run.samples.state
    assert np.allclose(relative, np.column_stack([s[:, 0] - s[:, 4], s[:, 1] - s[:, 5]]))
    enters = run.events.state[run.events.kind == "enter"]
    assert len(enters) > 0
    ox, oy = run.problem.offset
    rel = np.hypot(enters[:, 0] - enters[:, 4] - ox, enters[:, 1] - enters[:, 5] - oy)
    assert np.allclose(rel, 1.0, atol=1e-9)
    ax.figure.savefig(tmp_path / "ring_orbit.png")
    plt.close(ax.figure)
