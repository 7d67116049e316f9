#!/usr/bin/env python3
"""Speed of the Python package, measured in one run (BENCHMARKS.md, "Python and Dask").

1. Call overhead: ``rotor_rub.simulate`` against the Rust pipeline it wraps
   (``_core.rust_simulate_seconds``: the same problem, options and pass in a Rust loop), on
   contact-sparse cases; minimum per call over rounds.
2. A 64×64 sweep over (speed_ratio, damping_ratio): ``rotor_rub.sweep_grid`` on 2 Rust threads
   against ``rotor_rub.dask.sweep`` on a LocalCluster of 2 single-threaded worker processes,
   same 2 cores; the results are checked to be bit-identical.

Run with the package installed (scripts/test makes .venv):
    .venv/bin/python scripts/bench_python.py [--grid 64] [--transient 200] [--keep 50]
"""

from __future__ import annotations

import argparse
import time
from typing import Any, Callable, Dict

import numpy as np

import rotor_rub as rr
from rotor_rub import _core


def best_per_call(call: Callable[[], Any], repeats: int, rounds: int) -> float:
    best = float("inf")
    for _ in range(rounds):
        started = time.perf_counter()
        for _ in range(repeats):
            call()
        best = min(best, (time.perf_counter() - started) / repeats)
    return best


def overhead() -> None:
    cases: Dict[str, Dict[str, Any]] = {
        "paper-text, η = 2, 20 periods, 1001 samples (no contact after the transient)":
            dict(preset="paper-text", periods=20.0, method="analytic", samples=1001,
                 params={"speed_ratio": 2.0}),
        "paper-text, η = 2, 20 periods, no samples":
            dict(preset="paper-text", periods=20.0, method="analytic", samples=0,
                 params={"speed_ratio": 2.0}),
        "paper, η = 2.5, 1 period, hybrid, 101 samples":
            dict(preset="paper", periods=1.0, method="hybrid", samples=101,
                 params={"speed_ratio": 2.5}),
    }
    print("| case | Rust call | Python call | added by Python |")
    print("|---|---:|---:|---:|")
    for name, case in cases.items():
        params = case["params"]
        kwargs = {k: v for k, v in case.items() if k != "params"}
        rr.simulate(**kwargs, **params)  # warm up
        rounds, repeats = 15, 200
        rust = _core.rust_simulate_seconds(repeats, rounds, **kwargs, params=params)
        python = best_per_call(lambda: rr.simulate(**kwargs, **params), repeats, rounds)
        rust2 = _core.rust_simulate_seconds(repeats, rounds, **kwargs, params=params)
        rust = min(rust, rust2)
        print(f"| {name} | {rust * 1e6:.1f} µs | {python * 1e6:.1f} µs | "
              f"{(python - rust) * 1e6:.1f} µs |")


def dask_sweep(size: int, transient: int, keep: int) -> None:
    import distributed

    import rotor_rub.dask as rdask

    grid = {"speed_ratio": np.linspace(1.0, 3.5, size),
            "damping_ratio": np.linspace(0.05, 0.2, size)}
    options = dict(transient=transient, keep=keep)
    started = time.perf_counter()
    local = rr.sweep_grid(grid, threads=2, **options)
    rust = time.perf_counter() - started
    started = time.perf_counter()
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    client.run(lambda: __import__("rotor_rub"))  # workers import the package before timing
    startup = time.perf_counter() - started
    started = time.perf_counter()
    on_dask = rdask.sweep(client, grid, **options)
    wall = time.perf_counter() - started
    client.close()
    cluster.close()
    identical = (on_dask.state.tobytes() == local.state.tobytes()
                 and on_dask.values.tobytes() == local.values.tobytes())
    print(f"\n{size}×{size} sweep (transient {transient}, keep {keep}, hybrid, "
          f"{len(local)} Poincaré points), 2 cores:")
    print("| run | wall time | ratio |")
    print("|---|---:|---:|")
    print(f"| Rust sweep (sweep_grid, 2 threads) | {rust:.2f} s | 1.00 |")
    print(f"| Dask, 2 workers (cluster running) | {wall:.2f} s | {wall / rust:.2f} |")
    print(f"| Dask incl. starting the cluster | {wall + startup:.2f} s | "
          f"{(wall + startup) / rust:.2f} |")
    print(f"bit-identical: {identical}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=64)
    parser.add_argument("--transient", type=int, default=200)
    parser.add_argument("--keep", type=int, default=50)
    parser.add_argument("--skip-dask", action="store_true")
    args = parser.parse_args()
    overhead()
    if not args.skip_dask:
        dask_sweep(args.grid, args.transient, args.keep)


if __name__ == "__main__":
    main()
