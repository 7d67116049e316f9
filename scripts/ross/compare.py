"""rotor-rub against ROSS's rubbing fault on the same rotor and rub (issue 29 items 3 and 4).

Reads what run_rubbing.py saved (tests/data/ross/rubbing*.json: ROSS's contact crossings at
each time step, its wall times) and runs rotor-rub on the same model: the exported matrices
(tests/data/ross/rotor_example_with_damping.npz) reduced to ``--modes`` modes (Craig-Bampton,
the rub node physical), the same unbalance, clearance and contact stiffness, frictionless. It
prints, per ROSS step, how far ROSS's switch times are from rotor-rub's (located to rounding),
and the wall times for the same span, and writes tests/data/ross/comparison.json.

Needs the rotor_rub package (``pip install ./python``), not ROSS:

    python scripts/ross/compare.py [--modes 24] [--method hybrid] [--tol 1e-12]
    python scripts/ross/compare.py --jeffcott   # the Jeffcott case: jeffcott_comparison.json

``--jeffcott`` compares instead ROSS's runs of jeffcott_rubbing.py (a Jeffcott rotor built in
ROSS, near grazing, where ROSS's default step misses and invents contacts) with rotor-rub on the
same 20 lateral DOFs (no reduction), contact by contact: a contact of one run is *found* by the
other when a contact interval of the other overlaps it; rotor-rub's contacts that ROSS does not
find are *missed*, ROSS's that rotor-rub does not have are *invented*.

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


def intervals(times, directions, end):
    """Contact intervals [in, out] from switch times and directions (+1 in, −1 out); a contact
    still open at `end` closes there."""
    out, start = [], None
    for t, d in zip(times, directions):
        if d > 0:
            start = t
        elif start is not None:
            out.append((start, t))
            start = None
    if start is not None:
        out.append((start, end))
    return out


def unmatched(these, those):
    """The intervals of `these` that no interval of `those` overlaps."""
    return [a for a in these if not any(a[0] < b[1] and b[0] < a[1] for b in those)]


def jeffcott_model(note):
    rub, u = note["rub"], note["unbalance"]
    return rr.Model.from_ross(os.path.join(DATA, note["rotor"]["matrices"]), node=rub["node"],
                              clearance=rub["clearance_m"],
                              contact_stiffness=rub["contact_stiffness_N_per_m"],
                              friction_coefficient=0.0, modes=None,
                              unbalance=[(u["node"], u["m_e_kg_m"], u["phase_rad"])])


def jeffcott(a):
    note = json.load(open(os.path.join(DATA, "jeffcott_rubbing.json")))
    m = jeffcott_model(note)
    t_end = note["periods"] * note["period_s"]
    clock = time.perf_counter()
    run = rr.simulate(model=m, t_end=t_end, method=a.method, tol=a.tol, samples=0)
    wall = time.perf_counter() - clock
    ours_t = [float(t) for t in run.events.time]
    ours_d = [1 if k == "enter" else -1 for k in run.events.kind]
    ours = intervals(ours_t, ours_d, t_end)
    out = {"what": "rotor-rub vs ROSS's rubbing fault on the Jeffcott rotor of jeffcott_rubbing.py "
                   "(scripts/ross/compare.py --jeffcott)",
           "rotor_rub": {"version": rr.__version__, "method": a.method, "tol": a.tol, "n": m.n,
                         "switches": len(ours_t), "switch_times_s": ours_t,
                         "switch_directions": ours_d, "wall_s": wall},
           "period_s": note["period_s"], "periods": note["periods"], "ross": []}
    print(f"Jeffcott, {note['periods']:g} periods: rotor-rub ({a.method}, tol {a.tol:g}, "
          f"n = {m.n}): {len(ours_t)} switches ({len(ours)} contacts) in {wall:.3f} s")
    for r in note["runs"]:
        theirs = intervals(r["switch_times_s"], r["switch_directions"], t_end)
        missed, invented = unmatched(ours, theirs), unmatched(theirs, ours)
        entry = {"step_s": r["step_s"], "switches": r["switches"], "contacts": len(theirs),
                 "missed_contacts_s": missed, "invented_contacts_s": invented,
                 "max_radius_over_clearance": r["max_radius_m"] / note["rub"]["clearance_m"],
                 "wall_s": r["wall_s"]}
        if r["switches"] == len(ours_t) and not missed and not invented:
            entry["max_switch_time_error_s"] = float(np.abs(np.array(r["switch_times_s"])
                                                            - np.array(ours_t)).max())
        out["ross"].append(entry)
        print(f"  ROSS h = {r['step_s']:g} s: {r['switches']} switches, {len(missed)} contacts "
              f"missed {[(round(x, 5), round(y, 5)) for x, y in missed]}, {len(invented)} "
              f"invented {[(round(x, 5), round(y, 5)) for x, y in invented]}"
              + (f", max |Δt| = {entry['max_switch_time_error_s']:.2e} s"
                 if "max_switch_time_error_s" in entry else ""))
    with open(os.path.join(DATA, "jeffcott_comparison.json"), "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--modes", type=int, default=24)
    p.add_argument("--method", default="hybrid")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--jeffcott", action="store_true",
                   help="compare the Jeffcott case (jeffcott_rubbing.json) instead")
    a = p.parse_args()
    if a.jeffcott:
        jeffcott(a)
        return
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
