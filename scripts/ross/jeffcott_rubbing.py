"""ROSS's rubbing fault on a Jeffcott rotor built in ROSS, where its fixed step misses and invents
switches (issue 29 item 3: "where [ROSS's step] is not [fine enough], show what it misses").

The rotor (``jeffcott()``): a steel shaft of 0.6 m and 30 mm diameter in 4 elements (nodes
0 … 4), one disk (o.d. 0.3 m, width 0.05 m, 27.3 kg) at midspan (node 2), two isotropic bearings
(k = 1e7 N/m, c = 2e3 N·s/m) at the ends: a Jeffcott rotor, its first natural frequency
241.8 rad/s at rest, with gyroscopic coupling. Run at 1.5 times it (the paper's η = 1.5,
362.7 rad/s) with an unbalance of 8.5e-4 kg·m at the disk, whose steady whirl (1.2 times the
0.1 mm clearance) just exceeds the clearance of a stator at the disk, and a contact stiffness of
4e6 N/m (2.5 times the rotor's modal stiffness): the contacts are short and some are near
grazing — the case a fixed step resolves worst. The rub is frictionless without contact damping (the law both codes state:
see common.py).

The script exports the model (M, C, K, G over the 20 lateral DOFs at the run's speed:
tests/data/ross/jeffcott.npz, the format ``rr.Model.from_ross`` reads) and runs
``rotor.run_rubbing`` over ``--periods`` forcing periods at each ``--steps`` time step, writing
tests/data/ross/jeffcott_rubbing.json: per step, the contact crossings of r(t) = δ located by
linear interpolation (all ROSS gives), their directions, the wall time and the largest radius.
rotor-rub's side (event-located switches on the same matrices) is computed by the test
(python/tests/test_ross_data.py) and by ``compare.py --jeffcott``; no ROSS is needed for either.

    scripts/ross/run jeffcott_rubbing.py [--periods 20] [--steps 1e-4,5e-5,...]
"""

import argparse
import os
import time

import numpy as np

import common as c
from run_rubbing import crossings

LENGTH = 0.6            # m, shaft
DIAMETER = 0.03         # m, shaft
ELEMENTS = 4            # shaft elements: nodes 0 … 4
DISK_NODE = 2
DISK_OD = 0.3           # m
DISK_WIDTH = 0.05       # m
BEARING_K = 1e7         # N/m, both bearings, isotropic
BEARING_C = 2e3         # N·s/m
RUB_ELEMENT = 2         # its left node is the disk's
RUB_NODE = 2
CLEARANCE = 1e-4        # m
CONTACT_STIFFNESS = 4e6  # N/m: 2.5 times the rotor's modal stiffness m ω_n² = 1.6e6 N/m
UNBALANCE = 8.5e-4      # kg·m at the disk: free steady whirl 1.2 δ at the disk
UNBALANCE_PHASE = 0.0
SPEED_OVER_CRITICAL = 1.5
STEPS = "1e-4,5e-5,2.5e-5,1e-5,5e-6"


def jeffcott():
    import ross as rs

    steel = rs.materials.steel
    shaft = [rs.ShaftElement(LENGTH / ELEMENTS, idl=0.0, odl=DIAMETER, material=steel,
                             shear_effects=True, rotary_inertia=True, gyroscopic=True)
             for _ in range(ELEMENTS)]
    disk = rs.DiskElement.from_geometry(n=DISK_NODE, material=steel, width=DISK_WIDTH,
                                        i_d=DIAMETER, o_d=DISK_OD)
    bearings = [rs.BearingElement(n, kxx=BEARING_K, cxx=BEARING_C) for n in (0, ELEMENTS)]
    return rs.Rotor(shaft, [disk], bearings)


def lateral(rotor, speed):
    """M, C, K, G over the lateral DOFs (x, y, α, β of each node), after checking that the axial
    and torsional DOFs are decoupled from them; the DOF names and nodes."""
    ndof = rotor.number_dof
    M, K, C, G = rotor.M(speed), rotor.K(speed), rotor.C(speed), rotor.G()
    keep = [i for i in range(rotor.ndof) if i % ndof in c.LATERAL]
    other = [i for i in range(rotor.ndof) if i % ndof not in c.LATERAL]
    for name, A in (("M", M), ("K", K), ("C", C), ("G", G)):
        if other and max(np.abs(A[np.ix_(keep, other)]).max(),
                         np.abs(A[np.ix_(other, keep)]).max()) != 0.0:
            raise SystemExit(f"{name} couples lateral and axial/torsional DOFs")
    pick = np.ix_(keep, keep)
    names = np.array([f"{c.LATERAL_NAMES[c.LATERAL.index(i % ndof)]}_{i // ndof}" for i in keep])
    nodes = np.array([i // ndof for i in keep])
    return M[pick], C[pick], K[pick], G[pick], names, nodes


def first_natural_frequency(rotor):
    """The lowest damped natural frequency at rest (rad/s), from ROSS's model."""
    M, C, K, G, _, _ = lateral(rotor, 0.0)
    n = len(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam = np.linalg.eigvals(A)
    return float(np.min(lam.imag[lam.imag > 1e-6]))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--periods", type=float, default=20.0)
    p.add_argument("--steps", default=STEPS, help=f"time steps h, s (default {STEPS})")
    p.add_argument("--contact-stiffness", type=float, default=CONTACT_STIFFNESS, help="N/m")
    p.add_argument("--unbalance", type=float, default=UNBALANCE, help="kg·m at the disk")
    p.add_argument("--tag", default="", help="name the output jeffcott_rubbing<TAG>.json")
    a = p.parse_args()
    rotor = jeffcott()
    omega_n = first_natural_frequency(rotor)
    speed = SPEED_OVER_CRITICAL * omega_n
    period = 2 * np.pi / speed
    M, C, K, G, names, nodes = lateral(rotor, speed)
    np.savez_compressed(os.path.join(c.DATA, "jeffcott.npz"), M=M, C=C, K=K, G=G, dofs=names,
                        nodes=nodes, speed=np.array(speed))
    note = {
        "what": "ROSS's rubbing fault (Rotor.run_rubbing, Newmark, fixed step) on a Jeffcott rotor "
                "built in ROSS (scripts/ross/jeffcott_rubbing.py), frictionless, no contact damping",
        "made_by": f"scripts/ross/run jeffcott_rubbing.py --periods {a.periods:g} --steps {a.steps} "
                   f"--contact-stiffness {a.contact_stiffness:g} --unbalance {a.unbalance:g}",
        "versions": c.versions(),
        "rotor": {"shaft_length_m": LENGTH, "shaft_diameter_m": DIAMETER, "elements": ELEMENTS,
                  "disk_node": DISK_NODE, "disk_od_m": DISK_OD, "disk_width_m": DISK_WIDTH,
                  "disk_mass_kg": float(rotor.disk_elements[0].m),
                  "bearing_k_N_per_m": BEARING_K, "bearing_c_N_s_per_m": BEARING_C,
                  "lateral_dofs": len(M), "matrices": "jeffcott.npz"},
        "first_natural_frequency_rad_s": omega_n,
        "rub": {"element": RUB_ELEMENT, "node": RUB_NODE, "clearance_m": CLEARANCE,
                "contact_stiffness_N_per_m": a.contact_stiffness, "contact_damping_N_s_per_m": 0.0,
                "friction": 0.0},
        "unbalance": {"node": DISK_NODE, "m_e_kg_m": a.unbalance, "phase_rad": UNBALANCE_PHASE},
        "speed_rad_s": speed, "period_s": period, "periods": a.periods,
        "runs": [],
    }
    ndof = rotor.number_dof
    for h in [float(s) for s in a.steps.split(",")]:
        steps = int(round(a.periods * period / h))
        t = np.arange(steps + 1) * h
        wall = time.perf_counter()
        res = rotor.run_rubbing(
            n=RUB_ELEMENT, distance=CLEARANCE, contact_stiffness=a.contact_stiffness,
            contact_damping=0.0, friction_coeff=0.0, node=[DISK_NODE],
            unbalance_magnitude=[a.unbalance], unbalance_phase=[UNBALANCE_PHASE], speed=speed, t=t)
        wall = time.perf_counter() - wall
        x = res.yout[:, RUB_NODE * ndof + 0]
        y = res.yout[:, RUB_NODE * ndof + 1]
        r = np.hypot(x, y)
        cross = crossings(t, r, CLEARANCE)
        note["runs"].append({
            "step_s": h, "steps": steps, "wall_s": wall, "switches": len(cross),
            "switch_times_s": [tc for tc, _ in cross],
            "switch_directions": [d for _, d in cross],
            "max_radius_m": float(r.max()),
        })
        print(f"h = {h:g} s: {steps} steps, {wall:.1f} s wall, {len(cross)} switches, "
              f"max r/δ = {r.max() / CLEARANCE:.4f}", flush=True)
        c.write_json(f"jeffcott_rubbing{a.tag}.json", note)


if __name__ == "__main__":
    main()
