"""A sweep on a Dask cluster, resumable from its store (docs/PYTHON.md shows this file).
Run: python examples/python/dask_sweep.py [STORE_DIR]"""

# mypy: allow-untyped-calls
# (distributed's Client and LocalCluster carry no annotations; the rest is checked --strict)
from __future__ import annotations

import sys

import numpy as np
from distributed import Client, LocalCluster

import rotor_rub as rr
import rotor_rub.dask


def main(store: str) -> None:
    grid = {"speed_ratio": np.linspace(1.0, 3.5, 48), "damping_ratio": np.linspace(0.05, 0.2, 4)}
    # Worker processes start by importing this script: the cluster must be made under the
    # `if __name__ == "__main__":` guard below, never at import.
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        result = rotor_rub.dask.sweep(client, grid, transient=100, keep=20, store=store)
    local = rr.sweep_grid(grid, transient=100, keep=20)
    assert result.state.tobytes() == local.state.tobytes()  # identical, bit for bit
    classes, counts = np.unique(result.response, return_counts=True)
    print(", ".join(f"{n} {c}" for c, n in zip(classes, counts)), f"(chunks kept in {store})")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sweep-store")
