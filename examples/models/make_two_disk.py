"""Build the two-disk example rotor's matrices (examples/models/two_disk.toml and two_disk.npz).

A steel shaft (Ø 30 mm, 0.7 m) on two anisotropic, cross-coupled bearings at its ends, with two
disks (at 0.2 m and 0.5 m). Euler–Bernoulli beam elements with nodes at the bearings and the disks,
4 DOFs per node (x, y, θx, θy); the bearings' nodes are condensed statically (Guyan) onto the
disks' 8 DOFs (x1, y1, a1, b1, x2, y2, a2, b2: a = θx, b = θy), exact for the static stiffness.
Gyroscopic coupling from the disks' polar inertia: G acts on the tilt rates (M q'' + (C + ΩG) q' +
K q = f). Run: python3 examples/models/make_two_disk.py (numpy only); it prints the TOML matrix
blocks and writes two_disk.npz beside itself.
"""

import os

import numpy as np

E, rho, d = 2.1e11, 7850.0, 0.03
area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
nodes = np.array([0.0, 0.2, 0.5, 0.7])
disks = {1: (6.0, 0.015, 0.03), 2: (9.0, 0.025, 0.05)}  # node: (m kg, Id kg·m², Ip kg·m²)
bearings = {0: ((2.0e7, 1.0e6, -1.0e6, 1.2e7), (2000.0, 1500.0)),  # (kxx, kxy, kyx, kyy), (cxx, cyy)
            3: ((1.5e7, 8.0e5, -8.0e5, 0.9e7), (1800.0, 1200.0))}
ndof = 4 * len(nodes)
M, K, C, G = (np.zeros((ndof, ndof)) for _ in range(4))


def beam(L):
    """Bending stiffness and consistent mass of one plane, DOFs (w1, φ1, w2, φ2)."""
    k = E * inertia / L**3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L**2, -6 * L, 2 * L**2],
                                       [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L**2, -6 * L, 4 * L**2]])
    m = rho * area * L / 420 * np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * L**2, 13 * L, -3 * L**2],
                                          [54, 13 * L, 156, -22 * L], [-13 * L, -3 * L**2, -22 * L, 4 * L**2]])
    return k, m


for e in range(len(nodes) - 1):
    k, m = beam(nodes[e + 1] - nodes[e])
    # x–z plane: (x, θy); y–z plane: (y, −θx) (right-handed: θx turns y towards z).
    xz = [4 * e + 0, 4 * e + 3, 4 * e + 4, 4 * e + 7]
    yz = [4 * e + 1, 4 * e + 2, 4 * e + 5, 4 * e + 6]
    sign = np.array([1.0, -1.0, 1.0, -1.0])
    K[np.ix_(xz, xz)] += k
    M[np.ix_(xz, xz)] += m
    K[np.ix_(yz, yz)] += k * np.outer(sign, sign)
    M[np.ix_(yz, yz)] += m * np.outer(sign, sign)
for n, (m, Id, Ip) in disks.items():
    i = 4 * n
    M[i, i] += m
    M[i + 1, i + 1] += m
    M[i + 2, i + 2] += Id
    M[i + 3, i + 3] += Id
    G[i + 2, i + 3] += Ip
    G[i + 3, i + 2] -= Ip
for n, ((kxx, kxy, kyx, kyy), (cxx, cyy)) in bearings.items():
    i = 4 * n
    K[i:i + 2, i:i + 2] += [[kxx, kxy], [kyx, kyy]]
    C[i:i + 2, i:i + 2] += np.diag([cxx, cyy])
# Light structural damping of the shaft (1e-5 s of stiffness-proportional damping).
C += 1e-5 * (K - sum(np.pad(np.array(b[0]).reshape(2, 2), ((4 * n, ndof - 4 * n - 2),) * 2)
                     for n, b in bearings.items()))

master = [4 * n + j for n in disks for j in range(4)]
slave = [i for i in range(ndof) if i not in master]
T = np.zeros((ndof, len(master)))
T[master, range(len(master))] = 1.0
T[np.ix_(slave, range(len(master)))] = -np.linalg.solve(K[np.ix_(slave, slave)], K[np.ix_(slave, master)])
Mr, Cr, Kr, Gr = (T.T @ A @ T for A in (M, C, K, G))
Mr = 0.5 * (Mr + Mr.T)

here = os.path.dirname(os.path.abspath(__file__))
names = ["x1", "y1", "a1", "b1", "x2", "y2", "a2", "b2"]
np.savez(os.path.join(here, "two_disk.npz"), M=Mr, C=Cr, G=Gr, K=Kr, dofs=np.array(names),
         speed=np.array(300.0), unbalance=np.array([[4, 5, 4.0e-4, 0.0]]),
         rub=np.array([0, 1]), clearance=np.array(2.0e-4), contact_stiffness=np.array(5.0e7),
         friction_coefficient=np.array(0.1), radius=np.array(0.05), offset=np.array([0.0, 0.0]))


def block(name, A):
    rows = ",\n".join("    [" + ", ".join(f"{x:.10g}" for x in row) + "]" for row in A)
    return f"{name} = [\n{rows},\n]"


for name, A in (("mass", Mr), ("damping", Cr), ("gyroscopic", Gr), ("stiffness", Kr)):
    print(block(name, A))
lam = np.linalg.eigvals(np.block([[np.zeros((8, 8)), np.eye(8)],
                                  [-np.linalg.solve(Mr, Kr), -np.linalg.solve(Mr, Cr + 300.0 * Gr)]]))
print("# natural frequencies at 300 rad/s (rad/s):", np.sort(np.abs(lam[lam.imag > 0])))
