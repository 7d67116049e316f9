#!/usr/bin/env python3
"""A yardstick outside Rust: SciPy's solve_ivp (DOP853 and RK45) on the benchmark cases.

Usage: scripts/scipy_yardstick.py [--periods 100] [--tol 1e-10] [--repeat 3]

Same model and cases as `benches/propagation.rs` (docs/MODEL.md §1; `paper` preset; contact-sparse:
η = 1.5 with offset (0, 0); contact-heavy: η = 2.5): the piecewise right-hand side with the
regime chosen by the sign of h = z² − 1, switches found by solve_ivp's event location on h, the
Poincaré section from `t_eval`, rtol = atol = tol and the same largest step as ours (a quarter of
the shorter of the forcing period and 2π). Prints the median wall time per run and the number of
switches found. Needs numpy and scipy (`pip install scipy`); not part of CI.
"""
import argparse
import math
import statistics
import sys
import time

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError:  # pragma: no cover - optional tool
    sys.exit("scipy_yardstick: needs numpy and scipy (pip install scipy)")

# The `paper` preset (runtime/params.rs): ν, η_m, ρ̂, φ0, K̂, ε̂ and the initial state.
PAPER = dict(nu=0.125, mass_ratio=0.005, rho=70.0, phase=0.0,
             kxx=20.0, kxy=20.0, kyx=20.0, kyy=40.0, ex=0.3, ey=-0.2,
             state=(0.1, 0.1, 0.0, 0.0))
CASES = {
    "contact-sparse": dict(eta=1.5, ex=0.0, ey=0.0),
    "contact-heavy": dict(eta=2.5),
}


def problem(case):
    p = dict(PAPER)
    p.update(CASES[case])
    p["f"] = p["mass_ratio"] * p["rho"] * p["eta"] ** 2
    return p


def rhs(p):
    nu2, f, eta, phase = 2.0 * p["nu"], p["f"], p["eta"], p["phase"]
    kxx, kxy, kyx, kyy, ex, ey = p["kxx"], p["kxy"], p["kyx"], p["kyy"], p["ex"], p["ey"]

    def field(t, w):
        x, y, vx, vy = w
        theta = eta * t + phase
        ax = f * math.cos(theta) - nu2 * vx - x
        ay = f * math.sin(theta) - nu2 * vy - y
        u, v = x - ex, y - ey
        z = math.hypot(u, v)
        if z > 1.0:
            s = 1.0 - 1.0 / z
            gx, gy = s * u, s * v
            ax -= kxx * gx + kxy * gy
            ay -= kyx * gx + kyy * gy
        return [vx, vy, ax, ay]

    def h(t, w):
        return (w[0] - ex) ** 2 + (w[1] - ey) ** 2 - 1.0

    return field, h


def run(case, method, tol, periods):
    p = problem(case)
    field, h = rhs(p)
    period = 2.0 * math.pi / p["eta"]
    t_end = periods * period
    t_eval = np.arange(1, periods + 1) * period
    t_eval[-1] = t_end
    h_max = 0.25 * min(period, 2.0 * math.pi)
    start = time.perf_counter()
    sol = solve_ivp(field, (0.0, t_end), p["state"], method=method, rtol=tol, atol=tol,
                    max_step=h_max, t_eval=t_eval, events=h)
    elapsed = time.perf_counter() - start
    if not sol.success:
        raise RuntimeError(f"{case} {method}: {sol.message}")
    return elapsed, len(sol.t_events[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--periods", type=int, default=100)
    ap.add_argument("--tol", type=float, default=1e-10)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    print(f"| case | solve_ivp method | tol | median wall time ({a.periods} periods) | switches |")
    print("|---|---|---:|---:|---:|")
    for case in CASES:
        for method in ("DOP853", "RK45"):
            runs = [run(case, method, a.tol, a.periods) for _ in range(a.repeat)]
            t = statistics.median(r[0] for r in runs)
            print(f"| {case} | {method} | {a.tol:g} | {t * 1e3:.1f} ms | {runs[0][1]} |")


if __name__ == "__main__":
    main()
