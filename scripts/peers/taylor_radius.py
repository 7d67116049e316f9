"""Radius of convergence of the contact solution's Taylor series: Cartesian against polar.

Issue 31 asked whether writing contact in polar coordinates about the stator centre
(z, φ: the elastic law K_s (z − 1) n is polynomial in z) removes the convergence limit of the
taylor method's series, set by the complex-time zeros of z² = u² + v² (docs/MODEL.md §16).
This script answers with numbers: at contact points of the contact-heavy case (paper preset,
η = 2.5; states from the 30-digit reference `data/contact_heavy_100.csv`) it expands the
solution to order N in both formulations, in mpmath at 60 digits, and prints the root-test
estimate ρ_n = (max(1, ‖x₀‖∞) / ‖xₙ‖∞)^{1/n} over the states at the highest orders (the
estimate the method's step rule uses at n = p − 1, p).

Cartesian (the method's): x, y, x', y', cos θ, sin θ;
    q'' = F (cos θ, sin θ) − 2ν q' − q − K_s (1 − 1/z) (u, v).
Polar: z, c = cos φ, s = sin φ, z', ω = φ', cos θ, sin θ, with q = ε̂ + z n, n = (c, s),
t = (−s, c), a the same acceleration written with K_s (z − 1) n:
    z'' = z ω² + a·n,   ω' = (a·t − 2 z' ω) / z,   c' = −s ω,   s' = c ω.

Both formulations describe the same solution, and z(τ)² = u(τ)² + v(τ)² continues analytically
off the real axis, so the polar field's only singularity, z = 0 (in ω'), is met at exactly the
complex times where the Cartesian square root branches: the radius cannot grow. A Sundman
time dτ = z ds or z² ds (with z a state the field is polynomial) is printed too: the radius in τ
shrinks.

Usage: python3 taylor_radius.py [ORDER] [CONTACTS]   (defaults 40 and 3; ~1 min each at 40)
"""

import csv
import os
import sys

from mpmath import mp, mpf, sqrt, cos, sin

mp.dps = 60
NU, ETA = mpf("0.125"), mpf("2.5")
F = mpf("0.005") * mpf(70) * ETA**2
K = [[mpf(20), mpf(20)], [mpf(20), mpf(40)]]
EX, EY = mpf("0.3"), mpf("-0.2")


def mul(a, b):
    return [sum(a[j] * b[k - j] for j in range(k + 1)) for k in range(len(a))]


def recip(a):
    r = [1 / a[0]]
    for k in range(1, len(a)):
        r.append(-r[0] * sum(a[j] * r[k - j] for j in range(1, k + 1)))
    return r


def sqrt_series(a):
    r = [sqrt(a[0])]
    for k in range(1, len(a)):
        r.append((a[k] - sum(r[j] * r[k - j] for j in range(1, k))) / (2 * r[0]))
    return r


def add(*xs):
    return [sum(v) for v in zip(*xs)]


def scale(c, a):
    return [c * v for v in a]


def const(c, n):
    return [mpf(c)] + [mpf(0)] * (n - 1)


def expand(x0, field, n):
    """Taylor coefficients 0 … n−1 of the solution from x0 (Picard: one more exact per pass)."""
    xs = [const(v, n) for v in x0]
    for _ in range(n):
        d = field(xs, n)
        xs = [[x0[i]] + [d[i][k - 1] / k for k in range(1, n)] for i in range(len(x0))]
    return xs


def forcing_minus(qx, qy, vx, vy, ct, st, fx, fy, n):
    """F (cos θ, sin θ) − 2ν q' − q − K_s f, f the contact function's series."""
    ax = add(scale(F, ct), scale(-2 * NU, vx), scale(-1, qx),
             scale(-K[0][0], fx), scale(-K[0][1], fy))
    ay = add(scale(F, st), scale(-2 * NU, vy), scale(-1, qy),
             scale(-K[1][0], fx), scale(-K[1][1], fy))
    return ax, ay


def cartesian(xs, n):
    x, y, vx, vy, ct, st = xs
    u, v = add(x, const(-EX, n)), add(y, const(-EY, n))
    g = add(const(1, n), scale(-1, recip(sqrt_series(add(mul(u, u), mul(v, v))))))
    ax, ay = forcing_minus(x, y, vx, vy, ct, st, mul(g, u), mul(g, v), n)
    return [vx, vy, ax, ay, scale(-ETA, st), scale(ETA, ct)]


def polar(xs, n):
    z, c, s, zd, w, ct, st = xs
    qx, qy = add(const(EX, n), mul(z, c)), add(const(EY, n), mul(z, s))
    zw = mul(z, w)
    vx, vy = add(mul(zd, c), scale(-1, mul(zw, s))), add(mul(zd, s), mul(zw, c))
    pen = add(z, const(-1, n))
    ax, ay = forcing_minus(qx, qy, vx, vy, ct, st, mul(pen, c), mul(pen, s), n)
    an, at = add(mul(ax, c), mul(ay, s)), add(mul(ay, c), scale(-1, mul(ax, s)))
    wd = mul(add(at, scale(-2, mul(zd, w))), recip(z))
    return [zd, scale(-1, mul(s, w)), mul(c, w), add(mul(zw, w), an), wd,
            scale(-ETA, st), scale(ETA, ct)]


def sundman(power):
    """The Cartesian field in the time s of dτ = z^power ds, with z a state (polynomial)."""
    def field(xs, n):
        x, y, vx, vy, ct, st, z = xs
        u, v = add(x, const(-EX, n)), add(y, const(-EY, n))
        dt = z if power == 1 else mul(z, z)
        zk1 = const(1, n) if power == 1 else z
        ku = [add(scale(K[i][0], u), scale(K[i][1], v)) for i in (0, 1)]
        # z^p a = z^p (F cos θ − 2ν x' − x − K_s (u, v)) + z^(p−1) K_s (u, v)
        ax, ay = forcing_minus(x, y, vx, vy, ct, st, u, v, n)
        ax, ay = add(mul(dt, ax), mul(zk1, ku[0])), add(mul(dt, ay), mul(zk1, ku[1]))
        dz = mul(zk1, add(mul(u, vx), mul(v, vy)))
        return [mul(dt, vx), mul(dt, vy), ax, ay, scale(-ETA, mul(dt, st)),
                scale(ETA, mul(dt, ct)), dz]
    return field


def radius(xs, n):
    ref = max(1, max(abs(x[0]) for x in xs))
    return (ref / max(abs(x[n]) for x in xs)) ** (mpf(1) / n)


def evaluate(xs, h):
    return [sum(x[k] * h**k for k in range(len(x))) for x in xs]


def main():
    order = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    contacts = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    here = os.path.dirname(os.path.abspath(__file__))
    rows = [r for r in csv.DictReader(
        line for line in open(os.path.join(here, "data", "contact_heavy_100.csv"))
        if not line.startswith("#")) if r["kind"] == "enter"]
    shown = list(range(order - 8, order, 2))
    print(f"root-test radius at orders {shown} (Cartesian | polar | Sundman dτ = z ds, z² ds,"
          " in τ: times z₀, z₀²)")
    for r in rows[:contacts]:
        tau = mpf(r["time"])
        state = [mpf(r[k]) for k in ("x", "y", "vx", "vy")] + [cos(ETA * tau), sin(ETA * tau)]
        for step in range(4):  # the entry, then 0.1, 0.2, 0.3 into the contact
            cart = expand(state, cartesian, order)
            x, y, vx, vy, ct, st = state
            u, v = x - EX, y - EY
            z = sqrt(u * u + v * v)
            c, s = u / z, v / z
            pol = expand([z, c, s, vx * c + vy * s, (vy * c - vx * s) / z, ct, st], polar, order)
            rc = " ".join(f"{float(radius(cart, n)):.3f}" for n in shown)
            rp = " ".join(f"{float(radius(pol, n)):.3f}" for n in shown)
            line = f"tau = {float(tau):.4f} + {0.1 * step:.1f}, z = {float(z):.4f}: {rc} | {rp}"
            for power in (1, 2):
                sun = expand(state + [z], sundman(power), order)
                line += " | " + " ".join(
                    f"{float(radius(sun, n) * z**power):.3f}" for n in shown)
            print(line)
            state = evaluate(cart, mpf("0.1"))


if __name__ == "__main__":
    main()
