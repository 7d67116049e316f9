"""Sweeps on a Dask cluster: :func:`sweep` splits a one- or two-parameter grid into chunks, runs
them on the workers of a ``dask.distributed`` client and gathers one :class:`rotor_rub.Sweep`,
identical bit for bit to :func:`rotor_rub.sweep_grid` on one machine (each point's result
depends on that point alone, and the chunks are gathered in grid order) — response classes and
Lyapunov exponents included.

The chunking depends on the grid alone (:func:`default_chunk_size`), never on how many workers
are connected when ``sweep`` is called: a sweep started right after ``cluster.scale()`` is
submitted as many small tasks that the scheduler hands to every worker as it joins, and a rerun
on an allocation with another worker count finds the same chunks.

With ``store=DIR`` every finished chunk is written there as a Parquet file (pyarrow; written to a
temporary and renamed, so a file is complete or absent) and a rerun of the same sweep loads the
finished chunks and computes only the rest: an interrupted sweep restarts where it stopped. The
directory remembers which sweep it holds (a key over every input that decides the result) and
refuses another.

Needs ``pip install 'rotor_rub[dask]'`` (dask.distributed and pyarrow). On a real cluster, hand
in its client, e.g. for SLURM with dask-jobqueue (in a script, under ``if __name__ ==
"__main__":``, as every Dask script that starts worker processes)::

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
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from . import Sweep, __version__, _progress
from ._sweeps import _path, _sweep_points, grid_points
from .results import Count, PathLike, Real, Values

__all__ = ["sweep", "chunk_bounds", "default_chunk_size"]

#: The number of chunks a grid is cut into when ``chunk_size`` is not given (fewer when it has
#: fewer points): enough to spread over a few hundred workers and to balance slow
#: contact-heavy regions against fast free ones, few enough that a task's overhead (~1 ms)
#: stays small against its work.
TARGET_CHUNKS = 1024


def default_chunk_size(count: int) -> int:
    """Points per chunk for a grid of ``count`` points: about :data:`TARGET_CHUNKS` chunks.
    Depends on the grid alone, so the chunking and the store's key do not change with the
    cluster."""
    return max(1, -(-count // TARGET_CHUNKS))


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
        "rows": {"values": result.values, "period": result.period, "state": result.state,
                 "point": result.point},
        "response": [str(r) for r in result.response],
        "lyapunov": None if result.lyapunov is None else [float(x) for x in result.lyapunov],
        "skipped": list(result.skipped),
    }


def _key(names: Sequence[str], points: np.ndarray, chunk_size: int,
         options: Mapping[str, Any]) -> str:
    """A key over everything that decides the sweep's bits: rotor_rub version, the grid, the
    chunking and every option (a config file by its contents)."""
    digest = hashlib.sha256()
    config = options.get("config")
    described = {k: v for k, v in options.items() if k not in ("progress",)}
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
        points = json.loads(meta[b"rotor_rub.points"].decode())
        return {
            "rows": {"values": values.reshape(-1, width),
                     "period": table.column("period").to_numpy(),
                     "state": state.reshape(-1, 4),
                     "point": table.column("point").to_numpy()},
            "response": points["response"],
            "lyapunov": points["lyapunov"],
            "skipped": json.loads(meta.get(b"rotor_rub.skipped", b"[]").decode()),
        }

    def save(self, chunk: int, result: Dict[str, Any]) -> None:
        import pyarrow as pa

        pq = self._pq

        rows = result["rows"]
        columns = {f"value{j}": rows["values"][:, j] for j in range(rows["values"].shape[1])}
        columns["period"] = rows["period"]
        columns["point"] = rows["point"]
        for j, c in enumerate(("x", "y", "vx", "vy")):
            columns[c] = rows["state"][:, j]
        points = {"response": result["response"], "lyapunov": result["lyapunov"]}
        table = pa.table(columns).replace_schema_metadata({
            "rotor_rub.key": self.key,
            "rotor_rub.chunk": str(chunk),
            "rotor_rub.skipped": json.dumps(result["skipped"]),
            "rotor_rub.points": json.dumps(points),
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
    grid: Mapping[str, Values],
    *,
    chunk_size: Optional[Count] = None,
    store: Optional[PathLike] = None,
    on_chunk: Optional[Callable[[int, int], None]] = None,
    progress: Any = None,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    transient: Count = 200,
    keep: Count = 50,
    lyapunov: bool = False,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    skip_errors: bool = False,
    max_work: Optional[Real] = None,
    **params: Real,
) -> Sweep:
    """:func:`rotor_rub.sweep_grid` on the workers of ``client`` (a ``distributed.Client``).

    grid: ``{name: values}`` with one or two parameters (every combination, the first varying
    slowest). chunk_size: grid points per task (default :func:`default_chunk_size`, from the
    grid alone). store: directory for finished chunks (Parquet), making the sweep resumable.
    on_chunk: called as ``on_chunk(chunk, chunks)`` on the client after each chunk computed here
    has arrived (and been stored). progress: True, a callable ``progress(done, total)`` or a
    tqdm-style bar, in grid points (stored chunks count as done at once). The other keywords as
    in :func:`rotor_rub.sweep_grid` (``continuation`` excepted: it runs points in sequence);
    each chunk runs single-threaded on its worker, the max_work limit per chunk.

    The input is checked on the client before any task is sent (the first point's problem and
    the options), so a typo fails at once with ValueError; a chunk that fails on a worker raises
    its error here (finished chunks stay in ``store``). Ctrl-C (or an exception from on_chunk or
    progress) cancels the tasks not yet finished.
    """
    names, points = grid_points(grid)
    options: Dict[str, Any] = dict(
        preset=preset, config=_path(config), transient=transient, keep=keep,
        lyapunov=lyapunov, method=method, tol=tol, contact_scheme=contact_scheme, step=step,
        skip_errors=skip_errors, threads=1, max_work=max_work, params=dict(params),
        call="sweep_grid")
    # Validate every input on the client: one point, no period kept beyond one.
    probe = _sweep_points(names, points[:1], **{**options, "transient": 0, "keep": 1,
                                                 "lyapunov": False})
    size = default_chunk_size(len(points)) if chunk_size is None else chunk_size
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)):
        raise ValueError(f"chunk_size: {size!r} is not an integer")
    bounds = chunk_bounds(len(points), int(size))
    key = _key(names, points, int(size), {k: v for k, v in options.items()})
    saved = None if store is None else _Store(os.fspath(store), key, len(bounds))
    results: List[Optional[Dict[str, Any]]] = [None] * len(bounds)
    report, close = _progress.reporter(progress, "dask sweep", "points")
    try:
        done = 0
        for i in range(len(bounds)):
            if saved is not None:
                results[i] = saved.load(i, len(names))
                if results[i] is not None:
                    done += bounds[i][1] - bounds[i][0]
        if report is not None:
            report(float(done), float(len(points)))
        pending = {}
        for i, (start, stop) in enumerate(bounds):
            if results[i] is None:
                future = client.submit(_run_chunk, list(names), points[start:stop], options,
                                       pure=False, key=f"rotor-rub-{key[:16]}-{i}")
                pending[future] = i
        if pending:
            from distributed import as_completed

            try:
                for future in as_completed(list(pending)):  # type: ignore[no-untyped-call]
                    i = pending[future]
                    result = future.result()
                    if saved is not None:
                        saved.save(i, result)
                    results[i] = result
                    done += bounds[i][1] - bounds[i][0]
                    if on_chunk is not None:
                        on_chunk(i, len(bounds))
                    if report is not None:
                        report(float(done), float(len(points)))
            except BaseException:
                client.cancel([f for f, i in pending.items() if results[i] is None])
                raise
    finally:
        close()
    return _gathered(names, points, bounds, results, probe, options)


def _gathered(names: Sequence[str], points: np.ndarray, bounds: List[Tuple[int, int]],
              results: List[Optional[Dict[str, Any]]], probe: Sweep,
              options: Mapping[str, Any]) -> Sweep:
    """The chunks' results as one Sweep, in grid order (row point indices made global)."""
    width = len(names)
    done = [(start, r) for (start, _), r in zip(bounds, results) if r is not None]
    rows = [r["rows"] for _, r in done]
    response = [x for _, r in done for x in r["response"]]
    with_exponents = [r["lyapunov"] for _, r in done if r["lyapunov"] is not None]
    problem = probe.problem.from_dict({
        **probe.problem.to_dict(),
        "options": {**probe.problem.options, "transient": int(options["transient"]),
                    "keep": int(options["keep"]), "lyapunov": bool(options["lyapunov"]),
                    "dask": True}})
    return Sweep(
        params=tuple(names),
        values=(np.concatenate([r["values"] for r in rows]).reshape(-1, width) if rows
                else np.empty((0, width))),
        period=(np.concatenate([r["period"] for r in rows]).astype(np.int64) if rows
                else np.empty(0, np.int64)),
        state=(np.concatenate([r["state"] for r in rows]).reshape(-1, 4) if rows
               else np.empty((0, 4))),
        skipped=tuple(m for _, r in done for m in r["skipped"]),
        point=(np.concatenate([start + np.asarray(r["rows"]["point"], dtype=np.int64)
                               for start, r in done]) if rows else np.empty(0, np.int64)),
        points=points,
        response=np.array(response, dtype=np.str_),
        lyapunov=(np.array([x for xs in with_exponents for x in xs], dtype=np.float64)
                  if options["lyapunov"] else None),
        problem=problem,
    )
