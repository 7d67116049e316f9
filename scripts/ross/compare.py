"""rotor-rub against ROSS's rubbing fault on the same rotor and rub (issue 29 items 3 and 4).

Reads what run_rubbing.py saved (tests/data/ross/rubbing*.json: ROSS's contact crossings at
each time step, its wall times) and runs rotor-rub on the same model: the exported matrices
(tests/data/ross/rotor_example_with_damping.npz) reduced to ``--modes`` modes (Craig-Bampton,
the rub node physical), the same unbalance, clearance and contact stiffness, frictionless. It
prints, per ROSS step, how far ROSS's switch times are from rotor-rub's (located to rounding),
and the wall times for the same span, and writes tests/data/ross/comparison.json.

Needs the rotor_rub package (``pip install ./python``), not ROSS:

    python scripts/ross/compare.py [--modes 24] [--method hybrid] [--tol 1e-12]

Wall times are this machine's under its load: ratios within one run, not absolutes. For the
speed ratio (item 4) build the package in release mode (``pip install ./python``, not
``maturin develop``).
"""

import argparse
import json
import os
import time

import numpy as np

import rotor_rub as rr

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "tests", "data", "ross"))


def model(note, modes):
    u = note["unbalance"]
    rub = note["rub"]
    return rr.Model.from_ross(os.path.join(DATA, "rotor_example_with_damping.npz"),
                              node=rub["node"], clearance=rub["clearance_m"],
                              contact_stiffness=rub["contact_stiffness_N_per_m"],
                              friction_coefficient=0.0, modes=modes,
                              unbalance=[(u["node"], u["m_e_kg_m"], u["phase_rad"])])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--modes", type=int, default=24)
    p.add_argument("--method", default="hybrid")
    p.add_argument("--tol", type=float, default=1e-12)
    a = p.parse_args()
    out = {"what": "rotor-rub vs ROSS's rubbing fault (scripts/ross/compare.py)",
           "rotor_rub": {"version": rr.__version__, "method": a.method, "tol": a.tol,
                         "modes": a.modes}, "comparisons": []}
    for name in ("rubbing.json", "rubbing_100.json"):
        path = os.path.join(DATA, name)
        if not os.path.exists(path):
            continue
        note = json.load(open(path))
        m = model(note, a.modes)
        t_end = note["periods"] * note["period_s"]
        clock = time.perf_counter()
        run = rr.simulate(model=m, t_end=t_end, method=a.method, tol=a.tol, samples=0)
        wall = time.perf_counter() - clock
        ours = run.events.time
        entry = {"ross_file": name, "periods": note["periods"], "switches": len(ours),
                 "switch_times_s": list(map(float, ours)), "wall_s": wall, "ross": []}
        print(f"{name}: {note['periods']:g} periods; rotor-rub ({a.method}, tol {a.tol:g}, "
              f"n = {m.n}): {len(ours)} switches in {wall:.3f} s")
        for r in note["runs"]:
            theirs = np.array(r["switch_times_s"])
            k = min(len(theirs), len(ours))
            gap = float(np.abs(theirs[:k] - ours[:k]).max()) if k else None
            entry["ross"].append({"step_s": r["step_s"], "switches": r["switches"],
                                  "max_switch_time_error_s": gap, "wall_s": r["wall_s"],
                                  "speedup": r["wall_s"] / wall})
            print(f"  ROSS h = {r['step_s']:g} s: {r['switches']} switches, max |Δt| = "
                  f"{gap if gap is None else f'{gap:.2e}'} s, {r['wall_s']:.1f} s "
                  f"({r['wall_s'] / wall:.0f}× rotor-rub's)")
        out["comparisons"].append(entry)
    with open(os.path.join(DATA, "comparison.json"), "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
