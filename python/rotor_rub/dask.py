"""Sweeps on a Dask cluster: :func:`sweep` splits a one- or two-parameter grid into chunks, runs
them on the workers of a ``dask.distributed`` client and gathers one :class:`rotor_rub.Sweep`,
identical bit for bit to :func:`rotor_rub.sweep_grid` on one machine (each point's result
depends on that point alone, and the chunks are gathered in grid order).

With ``store=DIR`` every finished chunk is written there as a Parquet file (pyarrow; written to a
temporary and renamed, so a file is complete or absent) and a rerun of the same sweep loads the
finished chunks and computes only the rest: an interrupted sweep restarts where it stopped. The
directory remembers which sweep it holds (a key over every input) and refuses another.

Needs ``pip install 'rotor_rub[dask]'`` (dask.distributed and pyarrow). On a real cluster, hand
in its client, e.g. for SLURM with dask-jobqueue::

    from dask_jobqueue import SLURMCluster
    from distributed import Client
    cluster = SLURMCluster(cores=32, processes=32, memory="64GB", walltime="02:00:00")
    cluster.scale(jobs=4)                  # 4 nodes × 32 single-threaded workers
    client = Client(cluster)
    result = rotor_rub.dask.sweep(client, {"speed_ratio": np.linspace(1, 3.5, 512),
                                           "damping_ratio": np.linspace(0.02, 0.2, 64)},
                                  store="/scratch/me/sweep-1")

Every worker needs the same ``rotor_rub`` version installed (the key includes it).
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import Sweep, __version__, _path, _sweep_points, grid_points
from .results import FloatArray, PathLike

__all__ = ["sweep", "chunk_bounds"]

#: Chunks per worker when ``chunk_size`` is not given: enough for the scheduler to balance
#: contact-heavy (slow) against contact-free (fast) regions of the grid.
CHUNKS_PER_WORKER = 8


def chunk_bounds(count: int, chunk_size: int) -> List[Tuple[int, int]]:
    """[start, stop) of each chunk of ``count`` points, ``chunk_size`` points each (the last may
    be shorter)."""
    if chunk_size < 1:
        raise ValueError(f"chunk_size: {chunk_size} is out of range: it must be an integer >= 1")
    return [(start, min(start + chunk_size, count)) for start in range(0, count, chunk_size)]


def _run_chunk(names: Sequence[str], points: np.ndarray, options: Dict[str, Any]) -> Dict[str, Any]:
    """One chunk on a worker: the single-machine sweep of these points (one thread: the worker
    is the unit of parallelism). Rows carry their points' values, so chunks concatenate."""
    result = _sweep_points(names, points, **options)
    return {
        "rows": {"values": result.values, "period": result.period, "state": result.state},
        "skipped": list(result.skipped),
    }


def _key(names: Sequence[str], points: np.ndarray, chunk_size: int,
         options: Mapping[str, Any]) -> str:
    """A key over everything that decides the sweep's bits: rotor_rub version, the grid, the
    chunking and every option (a config file by its contents)."""
    digest = hashlib.sha256()
    config = options.get("config")
    described = dict(options)
    if config is not None:
        with open(config, "rb") as f:
            described["config"] = hashlib.sha256(f.read(1 << 20)).hexdigest()
    text = json.dumps(
        {"version": __version__, "names": list(names), "chunk_size": chunk_size,
         "options": described}, sort_keys=True, default=repr)
    digest.update(text.encode())
    digest.update(np.ascontiguousarray(points, dtype=np.float64).tobytes())
    return digest.hexdigest()


class _Store:
    """A directory of finished chunks (Parquet), with the sweep's key in ``sweep.json``."""

    def __init__(self, directory: str, key: str, chunks: int) -> None:
        import pyarrow.parquet as pq  # imported here: fails before any task is sent

        self._pq = pq

        if os.path.exists(directory) and not os.path.isdir(directory):
            raise ValueError(f"store: {directory} exists and is not a directory")
        os.makedirs(directory, exist_ok=True)
        self.directory = directory
        self.key = key
        manifest = os.path.join(directory, "sweep.json")
        if os.path.exists(manifest):
            with open(manifest, encoding="utf-8") as f:
                held = json.load(f)
            if held.get("key") != key:
                raise ValueError(
                    f"store: {directory} holds another sweep (different grid, options or "
                    "rotor_rub version); use a new directory or empty this one")
        else:
            self._atomic(manifest, json.dumps({"key": key, "chunks": chunks}).encode())

    def _atomic(self, path: str, data: bytes) -> None:
        fd, tmp = tempfile.mkstemp(prefix=".rotor-rub-", dir=self.directory)
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise

    def path(self, chunk: int) -> str:
        return os.path.join(self.directory, f"chunk-{chunk:06d}.parquet")

    def load(self, chunk: int, width: int) -> Optional[Dict[str, Any]]:
        """The stored chunk, or None when absent or not of this sweep."""
        pq = self._pq
        path = self.path(chunk)
        if not os.path.isfile(path):
            return None
        table = pq.read_table(path)
        meta = table.schema.metadata or {}
        if meta.get(b"rotor_rub.key", b"").decode() != self.key:
            return None
        values = np.stack([table.column(f"value{j}").to_numpy() for j in range(width)], axis=1)
        state = np.stack([table.column(c).to_numpy() for c in ("x", "y", "vx", "vy")], axis=1)
        return {
            "rows": {"values": values.reshape(-1, width),
                     "period": table.column("period").to_numpy(),
                     "state": state.reshape(-1, 4)},
            "skipped": json.loads(meta.get(b"rotor_rub.skipped", b"[]").decode()),
        }

    def save(self, chunk: int, result: Dict[str, Any]) -> None:
        import pyarrow as pa

        pq = self._pq

        rows = result["rows"]
        columns = {f"value{j}": rows["values"][:, j] for j in range(rows["values"].shape[1])}
        columns["period"] = rows["period"]
        for j, c in enumerate(("x", "y", "vx", "vy")):
            columns[c] = rows["state"][:, j]
        table = pa.table(columns).replace_schema_metadata({
            "rotor_rub.key": self.key,
            "rotor_rub.chunk": str(chunk),
            "rotor_rub.skipped": json.dumps(result["skipped"]),
        })
        fd, tmp = tempfile.mkstemp(prefix=".rotor-rub-", suffix=".parquet", dir=self.directory)
        os.close(fd)
        try:
            pq.write_table(table, tmp)
            os.replace(tmp, self.path(chunk))
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise


def sweep(
    client: Any,
    grid: Mapping[str, Union[Sequence[float], FloatArray]],
    *,
    chunk_size: Optional[int] = None,
    store: Optional[PathLike] = None,
    on_chunk: Optional[Callable[[int, int], None]] = None,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: int = 200,
    keep: int = 50,
    method: Optional[str] = None,
    tol: Optional[float] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[float] = None,
    skip_errors: bool = False,
    max_work: Optional[float] = None,
    **params: float,
) -> Sweep:
    """:func:`rotor_rub.sweep_grid` on the workers of ``client`` (a ``distributed.Client``).

    grid: ``{name: values}`` with one or two parameters (every combination, the first varying
    slowest). chunk_size: grid points per task (default: about
    :data:`CHUNKS_PER_WORKER` chunks per worker). store: directory for finished chunks (Parquet),
    making the sweep resumable. on_chunk: called as ``on_chunk(chunk, chunks)`` on the client
    after each chunk computed here has arrived (and been stored). The other keywords as in
    :func:`rotor_rub.sweep_grid`; each chunk runs single-threaded on its worker.

    The input is checked on the client before any task is sent (the first point's problem and
    the options), so a typo fails at once with ValueError; a chunk that fails on a worker raises
    its error here (finished chunks stay in ``store``).
    """
    names, points = grid_points(grid)
    options: Dict[str, Any] = dict(
        preset=preset, config=_path(config), transient=transient, keep=keep, method=method,
        tol=tol, contact_scheme=contact_scheme, step=step, skip_errors=skip_errors,
        threads=1, max_work=max_work, params=dict(params))
    # Validate every input on the client: one point, no period kept beyond one.
    _sweep_points(names, points[:1], **{**options, "transient": 0, "keep": 1})
    if chunk_size is None:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        chunk_size = max(1, -(-len(points) // (CHUNKS_PER_WORKER * workers)))
    bounds = chunk_bounds(len(points), int(chunk_size))
    key = _key(names, points, int(chunk_size), options)
    saved = None if store is None else _Store(os.fspath(store), key, len(bounds))
    results: List[Optional[Dict[str, Any]]] = [None] * len(bounds)
    pending = {}
    for i, (start, stop) in enumerate(bounds):
        if saved is not None:
            results[i] = saved.load(i, len(names))
        if results[i] is None:
            future = client.submit(_run_chunk, list(names), points[start:stop], options,
                                   pure=False, key=f"rotor-rub-{key[:16]}-{i}")
            pending[future] = i
    if pending:
        from distributed import as_completed

        for future in as_completed(list(pending)):  # type: ignore[no-untyped-call]
            i = pending[future]
            result = future.result()
            if saved is not None:
                saved.save(i, result)
            results[i] = result
            if on_chunk is not None:
                on_chunk(i, len(bounds))
    width = len(names)
    values = [r["rows"]["values"] for r in results if r is not None]
    period = [r["rows"]["period"] for r in results if r is not None]
    state = [r["rows"]["state"] for r in results if r is not None]
    skipped = [m for r in results if r is not None for m in r["skipped"]]
    return Sweep(
        params=tuple(names),
        values=np.concatenate(values).reshape(-1, width) if values else np.empty((0, width)),
        period=np.concatenate(period).astype(np.int64) if period else np.empty(0, np.int64),
        state=np.concatenate(state).reshape(-1, 4) if state else np.empty((0, 4)),
        skipped=tuple(skipped),
    )
