"""rotor_rub.dask.sweep on a LocalCluster of 2 workers: the single-machine result bit for bit,
resumable from its store."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Iterator, List

import numpy as np
import pytest

import rotor_rub as rr
import rotor_rub.dask as rdask

distributed = pytest.importorskip("distributed")

GRID = {"speed_ratio": np.linspace(1.0, 3.5, 7), "damping_ratio": [0.05, 0.125, 0.2]}
OPTIONS = dict(transient=20, keep=3)


@pytest.fixture(scope="module")
def client() -> Iterator["distributed.Client"]:
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def same(a: rr.Sweep, b: rr.Sweep) -> None:
    assert a.params == b.params
    assert a.values.tobytes() == b.values.tobytes()
    assert a.period.tobytes() == b.period.tobytes()
    assert a.state.tobytes() == b.state.tobytes()
    assert a.skipped == b.skipped
    assert a.point.tobytes() == b.point.tobytes()
    assert a.points.tobytes() == b.points.tobytes()
    assert list(a.response) == list(b.response)
    assert (a.lyapunov is None) == (b.lyapunov is None)
    if a.lyapunov is not None and b.lyapunov is not None:
        assert a.lyapunov.tobytes() == b.lyapunov.tobytes()
    assert a.problem.params == b.problem.params and a.problem.tol == b.problem.tol


def test_two_parameter_grid_is_bit_identical(client: "distributed.Client") -> None:
    local = rr.sweep_grid(GRID, **OPTIONS)
    assert len(local) == 21 * 3
    for chunk_size in (None, 1, 4, 100):
        same(rdask.sweep(client, GRID, chunk_size=chunk_size, **OPTIONS), local)
    assert len(client.scheduler_info()["workers"]) == 2


def test_one_parameter_grid_equals_sweep(client: "distributed.Client") -> None:
    values = np.linspace(1.0, 3.5, 9)
    same(rdask.sweep(client, {"speed_ratio": values}, chunk_size=2, method="dop853",
                     preset="friction", **OPTIONS),
         rr.sweep("speed_ratio", values, method="dop853", preset="friction", **OPTIONS))
    same(rdask.sweep(client, {"speed_ratio": values}, chunk_size=4, lyapunov=True, **OPTIONS),
         rr.sweep("speed_ratio", values, lyapunov=True, **OPTIONS))
    skipping = dict(method="dop853", k_xy=15.0, transient=40, keep=2, skip_errors=True)
    same(rdask.sweep(client, {"k_yx": [20.0, -10.0, 20.0]}, chunk_size=2, **skipping),
         rr.sweep("k_yx", [20.0, -10.0, 20.0], **skipping))


def test_bad_input_fails_before_any_task(client: "distributed.Client") -> None:
    with pytest.raises(ValueError, match="unknown parameter"):
        rdask.sweep(client, {"speed_rate": [1.0]})
    with pytest.raises(ValueError, match="tol"):
        rdask.sweep(client, GRID, method="rk45", tol=1.0)
    with pytest.raises(ValueError, match="chunk_size"):
        rdask.sweep(client, GRID, chunk_size=0, **OPTIONS)


class Interrupt(Exception):
    pass


def test_interrupted_sweep_resumes(client: "distributed.Client", tmp_path: Path) -> None:
    store = tmp_path / "store"
    done: List[int] = []

    def stop_after_three(chunk: int, chunks: int) -> None:
        done.append(chunk)
        if len(done) == 3:
            raise Interrupt

    with pytest.raises(Interrupt):
        rdask.sweep(client, GRID, chunk_size=2, store=store, on_chunk=stop_after_three,
                    **OPTIONS)
    stored = sorted(p.name for p in store.glob("chunk-*.parquet"))
    assert len(stored) == 3
    assert not list(store.glob(".rotor-rub-*"))
    again: List[int] = []
    result = rdask.sweep(client, GRID, chunk_size=2, store=store,
                         on_chunk=lambda i, n: again.append(i), **OPTIONS)
    total = -(-21 // 2)
    assert len(again) == total - 3 and not set(again) & set(done)
    same(result, rr.sweep_grid(GRID, **OPTIONS))
    # A third run computes nothing.
    nothing: List[int] = []
    same(rdask.sweep(client, GRID, chunk_size=2, store=store,
                     on_chunk=lambda i, n: nothing.append(i), **OPTIONS), result)
    assert nothing == []
    # Another sweep in the same store is refused.
    with pytest.raises(ValueError, match="another sweep"):
        rdask.sweep(client, GRID, chunk_size=2, store=store, transient=21, keep=3)


def test_chunking_does_not_depend_on_the_workers(client: "distributed.Client",
                                                  tmp_path: Path) -> None:
    """Issue 33 item 4: the default chunking and the store's key come from the grid alone, so a
    sweep interrupted on a 2-worker cluster resumes on a 1-worker one (a new allocation)."""
    assert rdask.default_chunk_size(63) == 1 and rdask.default_chunk_size(4096) == 4
    store = tmp_path / "store"
    done: List[int] = []

    def stop_after_five(chunk: int, chunks: int) -> None:
        done.append(chunk)
        if len(done) == 5:
            raise Interrupt

    with pytest.raises(Interrupt):
        rdask.sweep(client, GRID, store=store, on_chunk=stop_after_five, **OPTIONS)
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                       dashboard_address=None)
    with distributed.Client(cluster) as other:
        again: List[int] = []
        result = rdask.sweep(other, GRID, store=store, on_chunk=lambda i, n: again.append(i),
                             **OPTIONS)
    cluster.close()
    assert len(again) == 21 - 5
    assert not set(again) & set(done[:5])
    same(result, rr.sweep_grid(GRID, **OPTIONS))


def test_a_sweep_right_after_scale_spreads_over_every_worker() -> None:
    """Issue 33 item 4: a sweep submitted while no worker has joined yet (right after
    `cluster.scale()`, workers still starting) goes to every worker that joins — more than the
    8 chunks the old worker-count rule made on an empty cluster could ever reach."""
    from concurrent.futures import ThreadPoolExecutor

    cluster = distributed.LocalCluster(n_workers=0, threads_per_worker=1, processes=False,
                                       dashboard_address=None)
    with distributed.Client(cluster) as c, ThreadPoolExecutor(1) as pool:
        grid = {"speed_ratio": np.linspace(1.2, 3.4, 60)}
        with distributed.get_task_stream(c) as stream:
            running = pool.submit(rdask.sweep, c, grid, transient=3000, keep=2,
                                  method="hybrid")
            deadline = time.monotonic() + 30
            while not c.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks)):
                assert time.monotonic() < deadline, "the sweep submitted nothing"
                time.sleep(0.05)
            assert not c.scheduler_info()["workers"]
            cluster.scale(10)
            result = running.result(timeout=120)
        workers = {t["worker"] for t in stream.data if str(t["key"]).startswith("rotor-rub")}
        assert len(workers) == 10, workers
        assert len(result.response) == 60
    cluster.close()
