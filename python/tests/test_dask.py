"""rotor_rub.dask.sweep on a LocalCluster of 2 workers: the single-machine result bit for bit,
resumable from its store."""

from __future__ import annotations

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
