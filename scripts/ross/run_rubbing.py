"""Run ROSS's rubbing fault on its example rotor at its default step and at finer steps (issue 29
items 3 and 4), and save what the comparison with rotor-rub needs.

The rotor, rub and unbalance are common.py's (ROSS's rubbing tutorial, frictionless and without
contact damping: the law both codes state). For each time step h the script runs
``rotor.run_rubbing`` (ROSS's Newmark integration of the full 204-DOF model with the contact force
added to the right-hand side at each step) over ``--periods`` forcing periods and writes to
tests/data/ross/rubbing.json:

- the wall time of the run (ROSS's own, this machine, this load: see ``host`` in the note),
- the contact intervals the step implies: the times where r(t) = |(x, y)| of the rub node crosses
  the clearance δ, located by linear interpolation between steps (all ROSS can give: it locates no
  event), and their count,
- the rub node's largest radial displacement and the largest penetration r − δ,

and to tests/data/ross/rubbing_h<h>.npz the rub node's (x, y) every ``--keep``-th step (float32:
the checked-in data stay small).

    scripts/ross/run run_rubbing.py [--quick] [--periods P] [--steps 1e-4,5e-5,...] [--tag T]

What is checked in: ``--periods 10 --steps 1e-4,5e-5,2.5e-5,1e-5`` (rubbing.json: the
comparison of steps) and ``--periods 100 --steps 1e-4 --tag _100`` (rubbing_100.json: the time
for 100 forcing periods at the tutorial's step, issue 29 item 4).

rotor-rub's side of the comparison (events located to rounding, the same model from
tests/data/ross/rotor_example_with_damping.npz) is the lead's, when the matrix propagator lands.
"""

import argparse
import json
import os
import platform
import time

import numpy as np

import common as c


def crossings(t, r, delta):
    """Times where r − δ changes sign, by linear interpolation, with their direction (+1 in)."""
    g = r - delta
    idx = np.nonzero(np.sign(g[1:]) != np.sign(g[:-1]))[0]
    out = []
    for i in idx:
        if g[i] == g[i + 1]:
            continue
        s = g[i] / (g[i] - g[i + 1])
        out.append((float(t[i] + s * (t[i + 1] - t[i])), 1 if g[i + 1] > g[i] else -1))
    return out


def run(rotor, h, periods):
    steps = int(round(periods * c.PERIOD / h))
    t = np.arange(steps + 1) * h
    wall = time.perf_counter()
    res = rotor.run_rubbing(
        n=c.RUB_ELEMENT, distance=c.CLEARANCE, contact_stiffness=c.CONTACT_STIFFNESS,
        contact_damping=c.CONTACT_DAMPING, friction_coeff=c.FRICTION, node=[c.UNBALANCE_NODE],
        unbalance_magnitude=[c.UNBALANCE], unbalance_phase=[c.UNBALANCE_PHASE], speed=c.SPEED,
        t=t)
    wall = time.perf_counter() - wall
    ndof = rotor.number_dof
    x = res.yout[:, c.RUB_NODE * ndof + 0]
    y = res.yout[:, c.RUB_NODE * ndof + 1]
    return t, x, y, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="2 periods, the default step only")
    parser.add_argument("--periods", type=float, default=10.0,
                        help="forcing periods (1200 rpm: 0.05 s each); default 10")
    parser.add_argument("--steps", default="1e-4,5e-5,2.5e-5",
                        help="time steps h, s (ROSS's tutorial: 1e-4)")
    parser.add_argument("--tag", default="",
                        help="name the outputs rubbing<TAG>.json, rubbing<TAG>_h<h>.npz")
    parser.add_argument("--keep", type=int, default=0,
                        help="save every k-th step of (x, y) (default: 100 points per period)")
    a = parser.parse_args()
    steps = [c.DEFAULT_STEP] if a.quick else [float(s) for s in a.steps.split(",")]
    periods = 2.0 if a.quick else a.periods
    rotor = c.rotor()
    note = {
        "what": "ROSS's rubbing fault (Rotor.run_rubbing, Newmark, fixed step) on "
                "rotor_example_with_damping, frictionless, no contact damping",
        "made_by": "scripts/ross/run run_rubbing.py" + (" --quick" if a.quick else
                                                        f" --periods {a.periods} --steps {a.steps}"),
        "versions": c.versions(),
        "host": {"cpus": os.cpu_count(), "platform": platform.platform(),
                 "note": "wall times on a machine shared by several jobs: ratios, not absolutes"},
        "rub": {"element": c.RUB_ELEMENT, "node": c.RUB_NODE, "clearance_m": c.CLEARANCE,
                "tutorial_clearance_m": c.TUTORIAL_CLEARANCE,
                "contact_stiffness_N_per_m": c.CONTACT_STIFFNESS,
                "contact_damping_N_s_per_m": c.CONTACT_DAMPING, "friction": c.FRICTION},
        "unbalance": {"node": c.UNBALANCE_NODE, "m_e_kg_m": c.UNBALANCE,
                      "phase_rad": c.UNBALANCE_PHASE},
        "speed_rad_s": c.SPEED, "period_s": c.PERIOD, "periods": periods,
        "runs": [],
    }
    for h in steps:
        t, x, y, wall = run(rotor, h, periods)
        r = np.hypot(x, y)
        cross = crossings(t, r, c.CLEARANCE)
        keep = a.keep or max(1, int(round(c.PERIOD / h / 100)))
        name = f"rubbing{a.tag}_h{h:g}.npz"
        np.savez_compressed(os.path.join(c.DATA, name), t=t[::keep].astype(np.float32),
                            x=x[::keep].astype(np.float32), y=y[::keep].astype(np.float32),
                            step=np.array(h), keep=np.array(keep))
        entry = {
            "step_s": h, "steps": len(t) - 1, "wall_s": wall,
            "wall_per_period_s": wall / periods,
            "switches": len(cross), "contact_starts": sum(1 for _, d in cross if d > 0),
            "switch_times_s": [tc for tc, _ in cross],
            "switch_directions": [d for _, d in cross],
            "max_radius_m": float(r.max()),
            "max_penetration_m": float(max(0.0, r.max() - c.CLEARANCE)),
            "series": name,
        }
        note["runs"].append(entry)
        print(f"h = {h:g} s: {len(t) - 1} steps, {wall:.1f} s wall, {len(cross)} switches, "
              f"max r/δ = {r.max() / c.CLEARANCE:.4f}", flush=True)
        c.write_json(f"rubbing{a.tag}.json", note)


if __name__ == "__main__":
    main()
