"""Export ROSS's example rotor's matrices for rotor-rub's tests (issue 29 item 3).

Writes tests/data/ross/rotor_example_with_damping.npz: M, C, K, G at the tutorial's 1200 rpm over
the lateral DOFs (x, y, α, β of each of the 34 nodes: n = 136; axial and torsional DOFs are
decoupled from them and dropped, the coupling checked to be exactly 0), the DOF names
(``x_12``, …), the node of each DOF, and the tutorial's rub and unbalance; and
rotor_example_with_damping.json: versions, units, the layout, the eigenvalues of the full lateral
model (rad/s), so that a test needs no ROSS to check a reduction against ROSS's own model.

    scripts/ross/run export_rotor.py
"""

import os

import numpy as np

import common as c


def main():
    rotor = c.rotor()
    ndof = rotor.number_dof
    M, K, C, G = rotor.M(c.SPEED), rotor.K(c.SPEED), rotor.C(c.SPEED), rotor.G()
    lateral = [i for i in range(rotor.ndof) if i % ndof in c.LATERAL]
    other = [i for i in range(rotor.ndof) if i % ndof not in c.LATERAL]
    for name, A in (("M", M), ("K", K), ("C", C), ("G", G)):
        coupling = max(np.abs(A[np.ix_(lateral, other)]).max(), np.abs(A[np.ix_(other, lateral)]).max())
        if coupling != 0.0:
            raise SystemExit(f"{name} couples lateral and axial/torsional DOFs ({coupling}): cannot drop them")
    pick = np.ix_(lateral, lateral)
    M, K, C, G = M[pick], K[pick], C[pick], G[pick]
    names = np.array([f"{c.LATERAL_NAMES[c.LATERAL.index(i % ndof)]}_{i // ndof}" for i in lateral])
    nodes = np.array([i // ndof for i in lateral])
    n = len(lateral)
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C + c.SPEED * G)]])
    lam = np.linalg.eigvals(A)
    lam = lam[np.argsort(np.abs(lam))]
    path = os.path.join(c.DATA, "rotor_example_with_damping.npz")
    np.savez_compressed(path, M=M, C=C, K=K, G=G, dofs=names, nodes=nodes,
                        speed=np.array(c.SPEED))
    c.write_json("rotor_example_with_damping.json", {
        "what": "ross.rotor_example_with_damping(): M, C, K, G at the speed below over the lateral DOFs",
        "made_by": "scripts/ross/run export_rotor.py",
        "versions": c.versions(),
        "units": {"M": "kg (kg·m² on rotations)", "C": "N·s/m", "K": "N/m",
                  "G": "kg·m² (multiplied by the speed in rad/s: C + ΩG)", "speed": "rad/s",
                  "dofs": "x, y in m; alpha = θx, beta = θy in rad"},
        "equation": "M q'' + (C + speed·G) q' + K q = f (ROSS's convention)",
        "speed_rad_s": c.SPEED, "speed_rpm": c.SPEED_RPM,
        "dofs": "x_N, y_N, alpha_N, beta_N for nodes N = 0 … 33 (ROSS's x, y, α, β of each 6-DOF node; z and θ dropped: decoupled, coupling exactly 0)",
        "n": n,
        "rub": {"node": c.RUB_NODE, "element": c.RUB_ELEMENT, "clearance_m": c.CLEARANCE,
                "contact_stiffness_N_per_m": c.CONTACT_STIFFNESS},
        "unbalance": {"node": c.UNBALANCE_NODE, "m_e_kg_m": c.UNBALANCE, "phase_rad": c.UNBALANCE_PHASE},
        "eigenvalues_rad_s": [[float(l.real), float(l.imag)] for l in lam if l.imag >= 0][:24],
    })
    print(f"wrote {path} ({os.path.getsize(path)} bytes), n = {n}")


if __name__ == "__main__":
    main()
