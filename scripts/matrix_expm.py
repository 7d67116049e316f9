#!/usr/bin/env python3
"""Independent references for the exact free flight of rotors from matrices (tests/matrix_free.rs).

For each model below (matrices M, C, G, K, running speed, unbalances, input force, rub station,
start state) this writes tests/data/matrix_free/<case>.txt with
  * `state t y…`: the free-flight state at absolute time t from a 30-digit mpmath `expm` of the
    *augmented* first-order matrix: the forcing (cos θ, sin θ, 1) is three more states, so no
    particular solution, no modal form and nothing of the Rust code is involved; the matrices
    are the stored doubles, used exactly;
  * `scipy t y…`: the same from scipy's `expm` (Al-Mohy & Higham) in double precision, and
    `expm_check`: its largest relative difference from the 30-digit states (scipy's own
    rounding, up to ~‖A‖s·ε: 5e-13 on the undamped ring at s = 25);
  * `contact t` / `nocontact T`: the first time z = |B q − ε̂| reaches 1 (or none up to T), from
    the same 30-digit augmented system (a matrix exponential step, then a Taylor series to any
    time), scanned densely with cubic Hermite checks between samples and refined by mpmath's
    root finder; grazing cases are built so that the flight's maximum of z is 1 + δ exactly at
    a known time.

Run:  scripts/matrix_expm.py            (creates scripts/.venv-matrix-expm with numpy, scipy,
                                          mpmath from PyPI on first use, then re-runs itself)
      scripts/matrix_expm.py --check    (recompute and compare with the checked-in files)
The venv path can be set with $ROTOR_RUB_EXPM_VENV.
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
OUT = os.path.join(ROOT, "tests", "data", "matrix_free")


def ensure_environment():
    try:
        import mpmath  # noqa: F401
        import numpy  # noqa: F401
        import scipy  # noqa: F401
        return
    except ImportError:
        pass
    venv = os.environ.get("ROTOR_RUB_EXPM_VENV", os.path.join(HERE, ".venv-matrix-expm"))
    py = os.path.join(venv, "bin", "python")
    if os.path.abspath(sys.executable) == os.path.abspath(py):
        sys.exit("the venv at %s lacks numpy/scipy/mpmath" % venv)
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", venv])
    subprocess.check_call([py, "-m", "pip", "install", "-q", "--disable-pip-version-check",
                           "numpy>=1.22", "scipy>=1.9", "mpmath>=1.3"])
    os.execv(py, [py] + sys.argv)


ensure_environment()

import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402
from scipy.linalg import expm  # noqa: E402

mp.mp.dps = 30


# ---------------------------------------------------------------------------------------------
# Models
# ---------------------------------------------------------------------------------------------

class Model:
    def __init__(self, name, M, C, G, K, speed, phase, unbalances, station, y0, t0=0.0,
                 inputs=None, note=""):
        self.name = name
        self.M, self.C, self.G, self.K = (np.array(a, dtype=float) for a in (M, C, G, K))
        self.n = self.M.shape[0]
        self.speed = float(speed)
        self.phase = float(phase)
        self.unbalances = unbalances  # (x dof, y dof, amount m·e, phase)
        self.inputs = np.zeros(self.n) if inputs is None else np.array(inputs, dtype=float)
        # station: rotor (x, y), stator (x, y) or None, offset (εx, εy)
        self.station = station
        self.y0 = np.array(y0, dtype=float)
        self.t0 = float(t0)
        self.note = note

    def copy(self, name, **changes):
        m = Model(self.name, self.M, self.C, self.G, self.K, self.speed, self.phase,
                  self.unbalances, dict(self.station), self.y0, self.t0, self.inputs, self.note)
        m.name = name
        for k, v in changes.items():
            if k == "offset":
                m.station["offset"] = v
            else:
                setattr(m, k, np.array(v, dtype=float) if k == "y0" else v)
        return m


def jeffcott(nu=0.125):
    return np.eye(2), 2 * nu * np.eye(2), np.zeros((2, 2)), np.eye(2)


def ring(mass, damping, ks, nu=0.125):
    """The stator ring with mass in free flight: rotor (x, y) and ring (x_s, y_s), uncoupled."""
    M = np.diag([1.0, 1.0, mass, mass])
    C = np.diag([2 * nu, 2 * nu, damping, damping])
    K = np.zeros((4, 4))
    K[:2, :2] = np.eye(2)
    K[2:, 2:] = ks
    return M, C, np.zeros((4, 4)), K


def gyroscopic_disk():
    """A disk on a shaft: (x, y, tilt α, tilt β), gyroscopic coupling of the tilts, bearings
    with cross-coupled (non-symmetric) stiffness and damping."""
    ip = 0.8
    M = np.diag([1.0, 1.0, 0.4, 0.4])
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = ip, -ip
    k, c, kt = 1.0, 0.3, 0.9
    K = np.array([[k, 0.25, 0.0, c],
                  [-0.35, k, -c, 0.0],
                  [0.0, -c, kt, 0.1],
                  [c, 0.0, -0.05, kt]])
    C = np.array([[0.10, 0.02, 0.0, 0.0],
                  [0.01, 0.12, 0.0, 0.0],
                  [0.0, 0.0, 0.02, 0.0],
                  [0.0, 0.0, 0.0, 0.03]])
    return M, C, G, K


def bearing_nonsymmetric():
    M = np.eye(2)
    K = np.array([[1.0, 0.4], [-0.3, 1.5]])
    C = np.array([[0.1, 0.02], [0.03, 0.15]])
    return M, C, np.zeros((2, 2)), K


def rigid_body():
    """Two points (x1, y1, x2, y2) joined by a spring and a damper, nothing to ground: K and C
    singular, a defective zero eigenvalue (free translation)."""
    k, c = 2.0, 0.1
    M = np.diag([1.0, 1.0, 0.5, 0.5])
    J = np.array([[1.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, -1.0],
                  [-1.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 1.0]])
    return M, c * J, np.zeros((4, 4)), k * J


def repeated_modes():
    """Two isotropic points (x1, y1, x2, y2) coupled by springs: every mode twice."""
    M = np.diag([1.0, 1.0, 1.0, 1.0])
    K = np.array([[2.0, 0.0, -1.0, 0.0], [0.0, 2.0, 0.0, -1.0],
                  [-1.0, 0.0, 2.0, 0.0], [0.0, -1.0, 0.0, 2.0]])
    return M, 0.05 * K, np.zeros((4, 4)), K


def chain(nodes=10):
    """A shaft of `nodes` stations (x_i, y_i): consistent masses, shaft springs between
    neighbours, bearings at both ends with cross-coupled stiffness, gyroscopic x–y coupling at
    each station, Rayleigh damping plus bearing damping. n = 2·nodes."""
    n = 2 * nodes
    M = np.zeros((n, n))
    K = np.zeros((n, n))
    G = np.zeros((n, n))
    k = 40.0
    for i in range(nodes):
        m = 1.0 + 0.1 * i
        for d in range(2):
            M[2 * i + d, 2 * i + d] += 2.0 * m / 3.0
        if i + 1 < nodes:
            mm = 1.0 + 0.1 * (i + 0.5)
            for d in range(2):
                a, b = 2 * i + d, 2 * (i + 1) + d
                M[a, b] += mm / 6.0
                M[b, a] += mm / 6.0
                M[a, a] += mm / 6.0
                M[b, b] += mm / 6.0
                K[a, a] += k
                K[b, b] += k
                K[a, b] -= k
                K[b, a] -= k
        g = 0.05 * (1.0 + 0.2 * i)
        G[2 * i, 2 * i + 1] += g
        G[2 * i + 1, 2 * i] -= g
    C = 0.004 * (K + K.T) / 2 + 0.01 * M
    for node in (0, nodes - 1):
        x, y = 2 * node, 2 * node + 1
        K[x, x] += 8.0
        K[y, y] += 10.0
        K[x, y] += 1.5
        K[y, x] -= 1.0
        C[x, x] += 0.3
        C[y, y] += 0.35
        C[x, y] += 0.05
    return M, C, G, K


def models():
    out = []
    M, C, G, K = jeffcott()
    fixed = {"rotor": (0, 1), "stator": None, "offset": (0.0, 0.0)}
    out.append(Model("jeffcott", M, C, G, K, 2.5, 0.0, [(0, 1, 0.35, 0.0)], fixed,
                     [0.2, -0.1, 0.3, 0.1], t0=0.7))
    # The paper's first contact (the `paper` preset's start at η = 3.5): its 30-digit switch
    # list (tests/data/switches_30digit.csv) is a second reference for this one.
    out.append(Model("jeffcott_contact", M, C, G, K, 3.5, 0.0, [(0, 1, 0.35, 0.0)],
                     {"rotor": (0, 1), "stator": None, "offset": (0.3, -0.2)},
                     [0.1, 0.1, 0.0, 0.0]))
    M, C, G, K = bearing_nonsymmetric()
    out.append(Model("bearing", M, C, G, K, 1.1, 0.4, [(0, 1, 0.05, 0.3)], fixed,
                     [0.1, 0.2, -0.2, 0.05], t0=0.3))
    M, C, G, K = gyroscopic_disk()
    gyro = Model("gyroscopic", M, C, G, K, 1.7, 0.3, [(0, 1, 0.04, 0.0), (2, 3, 0.02, 1.0)],
                 fixed, [0.1, -0.05, 0.05, 0.02, 0.0, 0.1, -0.1, 0.05], t0=1.25,
                 inputs=[0.01, -0.02, 0.0, 0.0])
    out.append(gyro)
    out.append(gyro.copy("gyroscopic_contact", offset=(0.3, 0.2),
                         y0=[0.5, -0.3, 0.1, 0.05, 0.6, 0.8, -0.2, 0.1]))
    ks_nonsym = np.array([[20.0, 12.0], [-8.0, 40.0]])
    station = {"rotor": (0, 1), "stator": (2, 3), "offset": (0.0, 0.0)}
    M, C, G, K = ring(1.0, 0.3, ks_nonsym)
    out.append(Model("ring_nonsymmetric", M, C, G, K, 2.5, 0.0, [(0, 1, 0.35, 0.0)], station,
                     [0.1, 0.1, 0.05, -0.03, 0.0, 0.2, 0.3, -0.4], t0=2.0))
    M, C, G, K = ring(1.0, 0.0, np.array([[20.0, 5.0], [-5.0, 20.0]]))
    undamped = Model("ring_undamped", M, C, G, K, 2.5, 0.0, [(0, 1, 0.35, 0.0)], station,
                     [0.1, 0.1, 0.05, -0.03, 0.0, 0.2, 0.3, -0.4], t0=0.5)
    out.append(undamped)
    out.append(undamped.copy("ring_undamped_contact", offset=(0.3, -0.2),
                             y0=[0.1, 0.1, 0.1, -0.2, 0.0, 0.0, 0.8, 0.9]))
    M, C, G, K = ring(1.0, 0.0, 20.0 * np.eye(2))
    out.append(Model("ring_repeated", M, C, G, K, 2.5, 0.0, [(0, 1, 0.35, 0.0)], station,
                     [0.1, 0.1, 0.05, -0.03, 0.0, 0.2, 0.3, -0.4], t0=0.0))
    # ĉ = 0 and K_s/m̂ = η² exactly (6.25 = 2.5²): the ring's modes sit at the forcing frequency,
    # unforced; the dynamic stiffness is singular and consistent.
    M, C, G, K = ring(1.0, 0.0, 6.25 * np.eye(2))
    out.append(Model("ring_resonant_unforced", M, C, G, K, 2.5, 0.2, [(0, 1, 0.35, 0.0)],
                     station, [0.1, 0.1, 0.05, -0.03, 0.0, 0.2, 0.3, -0.4], t0=0.0))
    M, C, G, K = rigid_body()
    out.append(Model("rigid_body", M, C, G, K, 1.5, 0.0, [(0, 1, 0.05, 0.0)],
                     {"rotor": (0, 1), "stator": (2, 3), "offset": (0.0, 0.0)},
                     [0.05, 0.0, -0.1, 0.0, 0.1, -0.2, -0.2, 0.4], t0=0.0))
    M, C, G, K = repeated_modes()
    out.append(Model("repeated", M, C, G, K, 0.8, 0.0, [(0, 1, 0.05, 0.0), (2, 3, 0.05, 2.0)],
                     {"rotor": (2, 3), "stator": None, "offset": (0.0, 0.0)},
                     [0.1, 0.1, -0.1, 0.05, 0.0, 0.1, 0.2, -0.1], t0=0.0))
    M, C, G, K = chain(10)
    n = M.shape[0]
    y0 = [0.02 * np.sin(0.7 * i + 0.3) for i in range(n)] + \
         [0.05 * np.cos(1.3 * i) for i in range(n)]
    chain20 = Model("chain20", M, C, G, K, 1.3, 0.1, [(8, 9, 0.05, 0.0), (12, 13, 0.03, 1.5)],
                    {"rotor": (8, 9), "stator": None, "offset": (0.0, 0.0)}, y0, t0=0.4)
    out.append(chain20)
    y0c = [0.3 * np.sin(0.7 * i + 0.3) for i in range(n)] + \
          [1.5 * np.cos(1.3 * i) for i in range(n)]
    out.append(chain20.copy("chain20_contact", offset=(0.65, -0.5), y0=y0c))
    return out


# ---------------------------------------------------------------------------------------------
# The augmented system: z = (y, cos θ, sin θ, 1), z' = Â z, exactly the forced free flight.
# ---------------------------------------------------------------------------------------------

def augmented(model, ctx):
    """Â in ctx's arithmetic (np float64 or mpmath), from the stored double values."""
    n = model.n
    m = 2 * n
    if ctx == "np":
        Minv = np.linalg.inv(model.M)
        A = np.zeros((m + 3, m + 3))
        A[:n, n:m] = np.eye(n)
        A[n:m, :n] = -Minv @ model.K
        A[n:m, n:m] = -Minv @ (model.C + model.speed * model.G)
        fc, fs = unbalance_force(model)
        A[n:m, m] = Minv @ (model.speed ** 2 * fc)
        A[n:m, m + 1] = Minv @ (-(model.speed ** 2) * fs)
        A[n:m, m + 2] = Minv @ model.inputs
        A[m, m + 1] = -model.speed
        A[m + 1, m] = model.speed
        return A
    mpm = lambda a: mp.matrix([[mp.mpf(float(x)) for x in row] for row in a])  # noqa: E731
    Mi = mpm(model.M) ** -1
    eta = mp.mpf(model.speed)
    Ktot = mpm(model.K)
    Ctot = mpm(model.C) + eta * mpm(model.G)
    A = mp.zeros(m + 3, m + 3)
    MK, MC = Mi * Ktot, Mi * Ctot
    fc, fs = unbalance_force(model, mp)
    vc = Mi * mp.matrix([eta ** 2 * x for x in fc])
    vs = Mi * mp.matrix([-(eta ** 2) * x for x in fs])
    vu = Mi * mp.matrix([mp.mpf(float(x)) for x in model.inputs])
    for i in range(n):
        A[i, n + i] = 1
        for j in range(n):
            A[n + i, j] = -MK[i, j]
            A[n + i, n + j] = -MC[i, j]
        A[n + i, m] = vc[i]
        A[n + i, m + 1] = vs[i]
        A[n + i, m + 2] = vu[i]
    A[m, m + 1] = -eta
    A[m + 1, m] = eta
    return A


def unbalance_force(model, ctx=None):
    """f̂ = fc + i·fs per DOF: η² Re(f̂ e^{iθ}) = η² (fc cos θ − fs sin θ); an unbalance m·e at
    angle φ on (x, y) forces m e (cos(θ + φ), sin(θ + φ))."""
    if ctx is None:
        fc, fs = np.zeros(model.n), np.zeros(model.n)
        cos, sin = np.cos, np.sin
    else:
        fc, fs = [mp.mpf(0)] * model.n, [mp.mpf(0)] * model.n
        cos, sin = mp.cos, mp.sin
    for (x, y, amount, phase) in model.unbalances:
        a = amount if ctx is None else mp.mpf(amount)
        ph = phase if ctx is None else mp.mpf(phase)
        # x: m e cos(θ + φ) = Re(m e e^{iφ} e^{iθ}); y: m e sin(θ + φ) = Re(−i m e e^{iφ} e^{iθ})
        fc[x] += a * cos(ph)
        fs[x] += a * sin(ph)
        fc[y] += a * sin(ph)
        fs[y] += -a * cos(ph)
    return fc, fs


def start_vector(model, t0, y0, ctx):
    if ctx == "np":
        theta = model.speed * t0 + model.phase
        return np.concatenate([y0, [np.cos(theta), np.sin(theta), 1.0]])
    theta = mp.mpf(model.speed) * mp.mpf(t0) + mp.mpf(model.phase)
    return mp.matrix([mp.mpf(float(v)) for v in y0] + [mp.cos(theta), mp.sin(theta), 1])


def taylor_step(A, z, tau, terms=80):
    """e^{Aτ} z by its Taylor series (τ small: ‖A‖τ ≲ 1)."""
    out = mp.matrix(z)
    term = mp.matrix(z)
    for j in range(1, terms):
        term = (A * term) * (tau / j)
        out += term
        if mp.norm(term) < mp.mpf(10) ** (-mp.mp.dps - 5) * (1 + mp.norm(out)):
            break
    return out


def station(model, z, ctx):
    """h = |P − ε̂|² − 1 and h' of the augmented state z."""
    n = model.n
    rx, ry = model.station["rotor"]
    st = model.station["stator"]
    ex, ey = model.station["offset"]
    if ctx != "np":
        ex, ey = mp.mpf(ex), mp.mpf(ey)

    def comp(i, off):
        v = z[off + i]
        return v

    px, py = comp(rx, 0), comp(ry, 0)
    vx, vy = comp(rx, n), comp(ry, n)
    if st is not None:
        px -= comp(st[0], 0)
        py -= comp(st[1], 0)
        vx -= comp(st[0], n)
        vy -= comp(st[1], n)
    u, v = px - ex, py - ey
    return u * u + v * v - 1, 2 * (u * vx + v * vy)


# ---------------------------------------------------------------------------------------------
# References
# ---------------------------------------------------------------------------------------------

def states(model, times):
    A = augmented(model, "np")
    z0 = start_vector(model, model.t0, model.y0, "np")
    Amp = augmented(model, "mp")
    z0mp = start_vector(model, model.t0, model.y0, "mp")
    m = 2 * model.n
    rows, worst = [], 0.0
    for t in times:
        z = expm(A * (t - model.t0)) @ z0
        zmp = mp.expm(Amp * (mp.mpf(t) - mp.mpf(model.t0))) * z0mp
        y, ymp = z[:m], np.array([float(zmp[i]) for i in range(m)])
        worst = max(worst, np.linalg.norm(y - ymp) / np.linalg.norm(ymp))
        rows.append((t, ymp, y))
    return rows, worst


def first_contact(model, t_end, samples_per_unit=40):
    """The first time h = 0 upward on (t0, t_end], in 30 digits (None: no contact)."""
    A = augmented(model, "mp")
    z = start_vector(model, model.t0, model.y0, "mp")
    dt = mp.mpf(1) / samples_per_unit
    E = mp.expm(A * dt)
    t = mp.mpf(model.t0)
    h, dh = station(model, z, "mp")
    steps = int(mp.ceil((mp.mpf(t_end) - t) / dt))
    for _ in range(steps):
        z1 = E * z
        h1, dh1 = station(model, z1, "mp")
        lo_max = hermite_max(h, dh, h1, dh1, dt)
        if h1 > 0 or lo_max > -mp.mpf("1e-3"):
            root = refine(model, A, z, t, dt, h, h1)
            if root is not None:
                return root
        z, t, h, dh = z1, t + dt, h1, dh1
    return None


def hermite_max(h0, d0, h1, d1, L, n=16):
    best = max(h0, h1)
    for k in range(1, n):
        s = mp.mpf(k) / n
        h00, h10 = 2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s
        h01, h11 = -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2
        best = max(best, h00 * h0 + h10 * L * d0 + h01 * h1 + h11 * L * d1)
    return best


def refine(model, A, z, t, dt, h0, h1):
    """The first root of h in (t, t + dt]: find h's maximum on the interval first (a graze has
    two roots close together, or none), then bracket the first root."""
    f = lambda tau: station(model, taylor_step(A, z, tau), "mp")  # noqa: E731
    parts = 16
    grid = [dt * k / parts for k in range(parts + 1)]
    values = [f(tau) for tau in grid]
    for k in range(parts):
        (ha, da), (hb, db) = values[k], values[k + 1]
        a, b = grid[k], grid[k + 1]
        if ha <= 0 < hb:
            root = mp.findroot(lambda s: f(s)[0], (a, b), solver="anderson")
            return t + root
        if da > 0 >= db:
            # A maximum of h inside: locate it (h' = 0), then the root before it if h > 0.
            top = mp.findroot(lambda s: f(s)[1], (a, b), solver="anderson")
            if f(top)[0] > 0:
                root = mp.findroot(lambda s: f(s)[0], (a, top), solver="anderson")
                return t + root
    return None


def graze(model, name, delta, t_lo, t_hi, samples=400):
    """Move ε̂ so that the flight's maximum of z on [t_lo, t_hi] is 1 + δ at the same time t*:
    with n* the direction of d(t*) = P(t*) − ε̂ at the maximum, ε̂ ← P(t*) − (1 + δ) n*. Then
    |d(t)|² ≤ (1 + δ)² on the window with equality at t* only (|d_old| ≤ r, d_old·n* ≤ r)."""
    A = augmented(model, "mp")
    z = start_vector(model, model.t0, model.y0, "mp")
    step = (mp.mpf(t_hi) - mp.mpf(t_lo)) / samples
    if mp.mpf(t_lo) > mp.mpf(model.t0):
        z = mp.expm(A * (mp.mpf(t_lo) - mp.mpf(model.t0))) * z
    E = mp.expm(A * step)
    ex, ey = (mp.mpf(v) for v in model.station["offset"])

    def P(zz):
        n = model.n
        rx, ry = model.station["rotor"]
        st = model.station["stator"]
        px, py, vx, vy = zz[rx], zz[ry], zz[n + rx], zz[n + ry]
        if st is not None:
            px, py = px - zz[st[0]], py - zz[st[1]]
            vx, vy = vx - zz[n + st[0]], vy - zz[n + st[1]]
        return px, py, vx, vy

    def r2(zz):
        px, py, _, _ = P(zz)
        return (px - ex) ** 2 + (py - ey) ** 2

    grid = [z]
    for _ in range(samples):
        grid.append(E * grid[-1])
    k = max(range(samples + 1), key=lambda i: r2(grid[i]))
    base = grid[max(k - 1, 0)]
    t_base = mp.mpf(t_lo) + step * max(k - 1, 0)

    def dh(tau):
        px, py, vx, vy = P(taylor_step(A, base, tau))
        return (px - ex) * vx + (py - ey) * vy

    tau = mp.findroot(dh, (step * (0.5 if k > 0 else 0.0), step * 1.5), solver="anderson")
    top = t_base + tau
    px, py, _, _ = P(taylor_step(A, base, tau))
    u, v = px - ex, py - ey
    r = mp.sqrt(u * u + v * v)
    new = (float(px - (1 + mp.mpf(delta)) * u / r), float(py - (1 + mp.mpf(delta)) * v / r))
    g = model.copy(name, offset=new)
    g.note = "graze: max z = 1 %+g at t* = %s on [%g, %g] (before ε̂ is rounded to doubles)" % (
        delta, mp.nstr(top, 20), t_lo, t_hi)
    return g, top


def write(model, rows, worst, contact, t_end, path):
    def fmt(x):
        return repr(float(x))

    lines = ["# generated by scripts/matrix_expm.py: do not edit (rerun the script)",
             "# %s" % model.note if model.note else "#",
             "name %s" % model.name,
             "n %d" % model.n,
             "speed %s" % fmt(model.speed),
             "phase %s" % fmt(model.phase)]
    for tag, a in (("mass", model.M), ("damping", model.C), ("gyroscopic", model.G),
                   ("stiffness", model.K)):
        lines.append(tag + " " + " ".join(fmt(x) for x in a.flatten()))
    for (x, y, amount, phase) in model.unbalances:
        lines.append("unbalance %d %d %s %s" % (x, y, fmt(amount), fmt(phase)))
    lines.append("input " + " ".join(fmt(x) for x in model.inputs))
    st = model.station
    stator = "%d %d" % st["stator"] if st["stator"] is not None else "- -"
    lines.append("station %d %d %s %s %s" % (st["rotor"][0], st["rotor"][1], stator,
                                             fmt(st["offset"][0]), fmt(st["offset"][1])))
    lines.append("start %s %s" % (fmt(model.t0), " ".join(fmt(x) for x in model.y0)))
    if rows:
        lines.append("expm_check %.3e" % worst)
    for t, y, ys in rows:
        lines.append("state %s %s" % (fmt(t), " ".join(fmt(x) for x in y)))
        lines.append("scipy %s %s" % (fmt(t), " ".join(fmt(x) for x in ys)))
    if contact is not None:
        lines.append("contact %s" % mp.nstr(contact, 25))
    elif t_end is not None:
        lines.append("nocontact %s" % fmt(t_end))
    text = "\n".join(lines) + "\n"
    return text


def inside(model, span=25.0, reach=0.8, samples=2500):
    """The model with its start, unbalances and input force scaled (the flight is linear in
    them) so that the station's reach |P − ε̂| stays ≤ `reach` on [t0, t0 + span] (sampled by
    scipy): a free-flight case without contact."""
    A = augmented(model, "np")
    z0 = start_vector(model, model.t0, model.y0, "np")
    E = expm(A * (span / samples))
    z, top = z0, 0.0
    for _ in range(samples + 1):
        top = max(top, station_radius(model, z))
        z = E @ z
    if top <= reach:
        return model
    f = reach / top
    scaled = model.copy(model.name, y0=model.y0 * f)
    scaled.unbalances = [(x, y, a * f, p) for (x, y, a, p) in model.unbalances]
    scaled.inputs = model.inputs * f
    scaled.note = "start, unbalances and input scaled by %.6g: max |P - offset| <= %g on the span" % (f, reach)
    return scaled


def station_radius(model, z):
    h, _ = station(model, z, "np")
    return float(np.sqrt(h + 1.0))


def cases():
    all_models = {m.name: m for m in models()}
    spans = [0.01, 0.3, 1.0, 3.7, 10.0, 25.0]
    out = []
    for name in ["jeffcott", "bearing", "gyroscopic", "ring_nonsymmetric", "ring_undamped",
                 "ring_repeated", "ring_resonant_unforced", "rigid_body", "repeated", "chain20"]:
        m = inside(all_models[name])
        out.append((m, [m.t0 + s for s in spans], None))
    for name, t_end in [("jeffcott_contact", 10.0), ("gyroscopic_contact", 10.0),
                        ("ring_undamped_contact", 10.0), ("chain20_contact", 10.0)]:
        out.append((all_models[name], [], t_end))
    # Grazing: the ring (both bodies moving, ĉ = 0) and the 20-DOF rotor.
    base = all_models["ring_undamped"]
    for delta, name in [(1e-11, "ring_graze"), (-1e-11, "ring_graze_miss")]:
        g, _ = graze(base, name, delta, base.t0, base.t0 + 3.0)
        out.append((g, [], base.t0 + 3.0))
    base = all_models["chain20"]
    for delta, name in [(1e-11, "chain20_graze"), (-1e-11, "chain20_graze_miss")]:
        g, _ = graze(base, name, delta, base.t0, base.t0 + 4.0)
        out.append((g, [], base.t0 + 4.0))
    return out


def main():
    check = "--check" in sys.argv
    os.makedirs(OUT, exist_ok=True)
    status = 0
    for model, times, t_end in cases():
        rows, worst = states(model, times) if times else ([], 0.0)
        contact = first_contact(model, t_end) if t_end is not None else None
        text = write(model, rows, worst, contact, t_end, None)
        path = os.path.join(OUT, model.name + ".txt")
        summary = "%-24s n=%2d expm_check=%.2e %s" % (
            model.name, model.n, worst,
            ("contact at %s" % mp.nstr(contact, 20)) if contact is not None else
            ("no contact to %g" % t_end if t_end is not None else ""))
        if check:
            old = open(path).read() if os.path.exists(path) else ""
            same = old == text
            status |= not same
            print(("same    " if same else "CHANGED ") + summary, flush=True)
        else:
            with open(path, "w") as f:
                f.write(text)
            print(summary, flush=True)
    sys.exit(status)


if __name__ == "__main__":
    main()
