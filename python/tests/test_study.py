"""Study-ready results (issue 33 item 2): every result carries its problem, plots need no extra
arguments, sweeps give response classes and Lyapunov exponents, continuation sweeps, pandas and
xarray, save/load (Parquet, NetCDF) round trips, progress reports."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any, Dict, List, Tuple

import numpy as np
import pytest

import rotor_rub as rr


def test_every_result_carries_its_problem() -> None:
    run = rr.simulate(periods=2, samples=11)
    p = run.problem
    assert p.params["offset_x"] == 0.3 and p.params["offset_y"] == -0.2
    assert p.params["speed_ratio"] == 1.5 and p.params["x0"] == 0.1
    assert (p.method, p.tol, p.contact_scheme) == ("analytic", 1e-9, "exprb43")
    assert p.version == rr.__version__ and p.call == "simulate"
    assert p.options["samples"] == 11 and p.options["periods"] == 2
    assert run.method == p.method_text == "analytic (exprb43, tol 1e-9)"
    section = rr.poincare(transient=5, keep=4, speed_ratio=3.0, tol=1e-8)
    assert (section.problem.method, section.problem.tol) == ("taylor", 1e-8)
    assert section.problem.params["speed_ratio"] == 3.0
    spec = rr.spectrum(transient=2, periods=6, preset="friction")
    assert spec.problem.params["friction_coefficient"] > 0
    sweep = rr.sweep("speed_ratio", [1.5, 2.5], transient=5, keep=2, damping_ratio=0.1)
    assert sweep.problem.params["damping_ratio"] == 0.1
    assert sweep.problem.options["swept"] == ["speed_ratio"]
    steps = rr.Stepper(dt=1e-2, speed_ratio=2.0).run(10)
    assert steps.problem.method == "stepper" and steps.problem.params["speed_ratio"] == 2.0


def test_orbit_draws_the_clearance_circle_at_the_stator_centre() -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import rotor_rub.plot as rplot

    for preset in ("paper", "paper-text"):
        run = rr.simulate(preset=preset, periods=3, samples=101)
        ax = rplot.orbit(run)
        circle = next(l for l in ax.get_lines() if l.get_label() == "clearance")
        x, y = circle.get_data()
        centre = (np.mean(np.asarray(x)[:-1]), np.mean(np.asarray(y)[:-1]))
        assert np.allclose(centre, run.problem.offset, atol=1e-12), (preset, centre)
        plt.close(ax.figure)


def test_sweep_responses_and_exponents_are_the_sections() -> None:
    """Each point's response class and Lyapunov exponent are rr.poincare's for that point."""
    values = [1.5, 2.5, 3.0]
    sweep = rr.sweep("speed_ratio", values, transient=30, keep=24, lyapunov=True,
                     method="hybrid")
    assert sweep.lyapunov is not None and sweep.response.shape == (3,)
    assert np.array_equal(sweep.points[:, 0], values)
    for i, v in enumerate(values):
        alone = rr.poincare(speed_ratio=v, transient=30, keep=24, lyapunov=True, method="hybrid")
        assert sweep.response[i] == alone.response
        assert sweep.lyapunov[i] == alone.lyapunov
        assert sweep.state[sweep.point == i].tobytes() == alone.state.tobytes()
    plain = rr.sweep("speed_ratio", values, transient=30, keep=24, method="hybrid")
    assert plain.lyapunov is None and plain.state.tobytes() == sweep.state.tobytes()
    # Without the exponent the class comes from the section alone, as in rr.poincare.
    assert list(plain.response) == [
        rr.poincare(speed_ratio=v, transient=30, keep=24, method="hybrid").response
        for v in values]


def test_continuation_starts_each_point_from_the_previous_end_state() -> None:
    values = [2.0, 2.4, 2.8, 2.4, 2.0]
    cont = rr.sweep("speed_ratio", values, transient=20, keep=3, continuation=True,
                    method="hybrid")
    start = rr.presets()["paper"]
    state = [start["x0"], start["y0"], start["vx0"], start["vy0"]]
    for i, v in enumerate(values):
        alone = rr.poincare(speed_ratio=v, transient=20, keep=3, method="hybrid",
                            x0=state[0], y0=state[1], vx0=state[2], vy0=state[3])
        rows = cont.state[cont.point == i]
        assert rows.tobytes() == alone.state.tobytes(), i
        assert cont.response[i] == alone.response
        state = list(rows[-1])
    independent = rr.sweep("speed_ratio", values, transient=20, keep=3, method="hybrid")
    assert independent.state.tobytes() != cont.state.tobytes()
    assert cont.problem.options["continuation"] is True
    # A grid: each line of the last parameter in continuation, from the initial state.
    grid = rr.sweep_grid({"damping_ratio": [0.1, 0.125], "speed_ratio": values[:3]},
                         transient=20, keep=3, continuation=True, method="hybrid")
    for line in range(2):
        one = rr.sweep("speed_ratio", values[:3], transient=20, keep=3, continuation=True,
                       method="hybrid", damping_ratio=[0.1, 0.125][line])
        assert grid.state[grid.point // 3 == line].tobytes() == one.state.tobytes()


def results() -> Dict[str, Any]:
    return {
        "run": rr.simulate(preset="dry-whip", periods=3, samples=64, method="hybrid"),
        "section": rr.poincare(transient=5, keep=6, lyapunov=True, speed_ratio=3.0),
        "spectrum": rr.spectrum(transient=2, periods=6),
        "whirl": rr.spectrum(transient=2, periods=6, whirl=True),
        "sweep": rr.sweep_grid({"speed_ratio": [1.5, 2.5], "k_xy": [0.0, 20.0]}, transient=5,
                               keep=2, lyapunov=True, method="dop853"),
        "skipped": rr.sweep("k_yx", [-10.0, 20.0], method="dop853", k_xy=15.0, transient=40,
                            keep=2, skip_errors=True),
        "steps": rr.Stepper(dt=1e-2, speed_ratio=2.5).run(300),
        "runup": rr.runup(from_speed=1.2, to_speed=2.8, rate=1e-2, method="hybrid"),
    }


def assert_same(a: Any, b: Any, where: str = "") -> None:
    """Equal field by field, arrays bit for bit."""
    assert type(a) is type(b), where
    if isinstance(a, np.ndarray):
        assert a.dtype.kind == b.dtype.kind and a.shape == b.shape, (where, a.dtype, b.dtype)
        if a.dtype.kind in "US":
            assert a.tolist() == b.tolist(), where
        else:
            assert a.tobytes() == b.astype(a.dtype).tobytes(), where
    elif hasattr(a, "__dataclass_fields__"):
        for name in a.__dataclass_fields__:
            assert_same(getattr(a, name), getattr(b, name), f"{where}.{name}")
    elif isinstance(a, tuple):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{where}[{i}]")
    else:
        assert a == b, (where, a, b)


@pytest.mark.parametrize("suffix", [".parquet", ".nc"])
def test_save_and_load_round_trip(tmp_path: Path, suffix: str) -> None:
    for name, result in results().items():
        path = tmp_path / f"{name}{suffix}"
        result.save(path)
        assert_same(result, rr.load(path), name)
    assert not list(tmp_path.glob(".rotor-rub-*"))


def test_pandas_and_xarray() -> None:
    r = results()
    run = r["run"]
    df = run.to_pandas()
    assert list(df.columns) == ["time", "x", "y", "vx", "vy", "regime"] and len(df) == 64
    assert df.attrs["rotor_rub"]["problem"]["params"]["friction_coefficient"] == 0.6
    events = run.to_pandas("event")
    assert list(events["kind"]) == list(run.events.kind)
    with pytest.raises(ValueError, match="table: 'nope'"):
        run.to_pandas("nope")
    sweep = r["sweep"].to_pandas()
    assert {"speed_ratio", "k_xy", "period", "x", "point"} <= set(sweep.columns)
    points = r["sweep"].to_pandas("point")
    assert list(points["response"]) == list(r["sweep"].response)
    ds = r["runup"].to_xarray()
    assert ds["max_radius"].dims == ("row",) and ds["event_time"].dims == ("event",)
    assert ds.attrs["method"] == r["runup"].method and ds.attrs["param_offset_x"] == 0.3
    section = r["section"].to_xarray()
    assert section.attrs["call"] == "poincare"


def test_files_are_refused_clearly(tmp_path: Path) -> None:
    run = rr.simulate(periods=1, samples=3)
    with pytest.raises(ValueError, match="use .parquet or .nc"):
        run.save(tmp_path / "run.csv")
    with pytest.raises(ValueError, match="not a regular file"):
        run.save(tmp_path, format="parquet")
    (tmp_path / "junk.parquet").write_bytes(b"junk")
    with pytest.raises(ValueError, match="neither"):
        rr.load(tmp_path / "junk.parquet")
    run.save(tmp_path / "a.nc")
    link = tmp_path / "link.nc"
    link.symlink_to(tmp_path / "a.nc")
    rr.simulate(periods=2, samples=3).save(link)  # writes the link's target
    assert link.is_symlink() and rr.load(tmp_path / "a.nc").end_time == 2 * run.end_time


def test_a_missing_optional_dependency_says_what_to_install(monkeypatch: Any) -> None:
    run = rr.simulate(periods=1, samples=3)
    for module, call in (("pandas", run.to_pandas), ("xarray", run.to_xarray)):
        monkeypatch.setitem(sys.modules, module, None)
        with pytest.raises(ImportError, match=f"pip install 'rotor_rub\\[{module}\\]'"):
            call()


def test_progress_reports() -> None:
    seen: List[Tuple[float, float]] = []
    rr.simulate(periods=200, samples=0, method="dop853", progress=lambda d, t: seen.append((d, t)))
    assert seen and seen[-1] == (200.0, 200.0)
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))

    class Bar:
        total = None
        n = 0

        def update(self, k: int) -> None:
            self.n += k

    bar = Bar()
    rr.sweep("speed_ratio", np.linspace(1, 3, 5), transient=5, keep=2, progress=bar)
    assert (bar.total, bar.n) == (5, 5)
    bar = Bar()
    rr.Stepper().run(5000, progress=bar)
    assert (bar.total, bar.n) == (5000, 5000)
    rr.poincare(transient=5, keep=5, progress=True)  # a tqdm bar
    with pytest.raises(ValueError, match="progress"):
        rr.simulate(periods=1, progress="yes")

    def stop(done: float, total: float) -> None:
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        rr.runup(progress=stop, method="hybrid")


def test_calls_report_progress_while_running() -> None:
    """A long call reports during the run (about every 50 ms), not only at the end."""
    seen: List[float] = []
    rr.sweep("speed_ratio", np.linspace(1.2, 3.2, 6), transient=5000, keep=2, method="hybrid",
             threads=1, progress=lambda d, t: seen.append(d))
    assert len(seen) >= 3 and seen[0] < 6

