//! Differentiation rules and total derivatives against central differences.

use super::*;

// ---------------------------------------------------------------------------------------------
// A. Differentiation rules against central differences.

#[test]
fn derivative_of_sum_and_product() {
    let mut rng = Rng::new(1);
    let mut g = Graph::new();
    let (a, b, c) = (g.input("a"), g.input("b"), g.input("c"));
    let three = g.constant(3.0);
    let sum = g.sum(&[a, b, c, three]);
    let ab = g.mul(a, b);
    let sum2 = g.sub(ab, c);
    let prod = g.product(&[a, b, c]);
    let sq = g.mul(a, a);
    let mixed = g.product(&[sq, b, three]);
    let quotient = g.div(a, b);
    for _ in 0..50 {
        let vals = [
            ("a", rng.range(-2.0, 2.0)),
            (
                "b",
                rng.range(0.5, 2.0) * if rng.unit() < 0.5 { -1.0 } else { 1.0 },
            ),
            ("c", rng.range(-2.0, 2.0)),
        ];
        for (e, what) in [
            (sum, "a+b+c+3"),
            (sum2, "ab−c"),
            (prod, "abc"),
            (mixed, "3a²b"),
            (quotient, "a/b"),
        ] {
            check_partials(&mut g, e, &vals, what);
        }
    }
    // The sum rule is exact: ∂(a+b+c+3)/∂a is the constant 1, not merely numerically 1.
    let sa = g.symbol("a");
    let d = partial(&mut g, sum, sa);
    assert!(g.is_const(d, 1.0));
}

#[test]
fn derivative_of_integer_powers_including_negative() {
    let mut rng = Rng::new(2);
    let mut g = Graph::new();
    let a = g.input("a");
    let b = g.input("b");
    let ab = g.add(a, b);
    for n in [2, 3, 5, -1, -2, -3, -4] {
        let p = g.powi(a, n);
        let q = g.powi(ab, n);
        for _ in 0..30 {
            // |a| ∈ [0.5, 2] of either sign; a + b kept away from 0 as well.
            let sign = if rng.unit() < 0.5 { -1.0 } else { 1.0 };
            let av = sign * rng.range(0.5, 2.0);
            let bv = sign * rng.range(0.1, 1.0);
            let vals = [("a", av), ("b", bv)];
            check_partials(&mut g, p, &vals[..1], &format!("a^{n}"));
            check_partials(&mut g, q, &vals, &format!("(a+b)^{n}"));
        }
    }
}

#[test]
fn derivative_of_sqrt_exp_sin_cos() {
    let mut rng = Rng::new(3);
    let mut g = Graph::new();
    let a = g.input("a");
    let sq = g.sqrt(a);
    let ex = g.exp(a);
    let si = g.sin(a);
    let co = g.cos(a);
    for _ in 0..50 {
        let pos = [("a", rng.range(0.3, 3.0))];
        check_partials(&mut g, sq, &pos, "sqrt(a)");
        let any = [("a", rng.range(-3.0, 3.0))];
        check_partials(&mut g, ex, &any, "exp(a)");
        check_partials(&mut g, si, &any, "sin(a)");
        check_partials(&mut g, co, &any, "cos(a)");
    }
}

#[test]
fn derivative_chain_rule() {
    let mut rng = Rng::new(4);
    let mut g = Graph::new();
    let (a, b) = (g.input("a"), g.input("b"));
    // sin(exp(a b)) + cos(sqrt(a² + b²))·b⁻² − exp(−a)·sqrt(1 + a²)
    let ab = g.mul(a, b);
    let e1 = g.exp(ab);
    let t1 = g.sin(e1);
    let aa = g.mul(a, a);
    let bb = g.mul(b, b);
    let r2 = g.add(aa, bb);
    let r = g.sqrt(r2);
    let cr = g.cos(r);
    let ib2 = g.powi(b, -2);
    let t2 = g.mul(cr, ib2);
    let na = g.neg(a);
    let ena = g.exp(na);
    let one = g.constant(1.0);
    let opa = g.add(one, aa);
    let s = g.sqrt(opa);
    let t3 = g.mul(ena, s);
    let nt3 = g.neg(t3);
    let e = g.sum(&[t1, t2, nt3]);
    // The contact function of the model: gx = (1 − 1/√(u² + v²)) u.
    let (x, y) = (g.input("x"), g.input("y"));
    let uu = g.mul(x, x);
    let vv = g.mul(y, y);
    let z2 = g.add(uu, vv);
    let z = g.sqrt(z2);
    let iz = g.powi(z, -1);
    let sc = g.sub(one, iz);
    let gx = g.mul(sc, x);
    for _ in 0..50 {
        let vals = [("a", rng.range(-1.0, 1.0)), ("b", rng.range(0.5, 1.5))];
        check_partials(&mut g, e, &vals, "chain");
        let ang = rng.range(0.0, std::f64::consts::TAU);
        let rad = rng.range(0.5, 3.0);
        let vals = [("x", rad * ang.cos()), ("y", rad * ang.sin())];
        check_partials(&mut g, gx, &vals, "gx");
    }
}

/// The total derivative with rates follows a trajectory: the forcing phasor (ct, st) rotating at
/// η and a harmonic oscillator (x, v) with x' = v, v' = −x. The symbolic d/dt and d²/dt² must
/// match finite differences of the expression evaluated along the exact trajectory.
#[test]
fn total_derivative_with_rates() {
    let mut rng = Rng::new(5);
    let mut g = Graph::new();
    let (eta, ct, st, x, v, k) = (
        g.input("eta"),
        g.input("ct"),
        g.input("st"),
        g.input("x"),
        g.input("v"),
        g.input("k"),
    );
    let mut rates: HashMap<Symbol, ExprId> = HashMap::new();
    let es = g.mul(eta, st);
    rates.insert(g.symbol("ct"), g.neg(es));
    rates.insert(g.symbol("st"), g.mul(eta, ct));
    rates.insert(g.symbol("x"), v);
    rates.insert(g.symbol("v"), g.neg(x));
    // f = k·ct·x² + st·exp(v)/(2 + x²) + sin(ct·v)   (k is a constant parameter: no rate)
    let xx = g.mul(x, x);
    let t1 = g.product(&[k, ct, xx]);
    let ev = g.exp(v);
    let two = g.constant(2.0);
    let den = g.add(two, xx);
    let num = g.mul(st, ev);
    let t2 = g.div(num, den);
    let cv = g.mul(ct, v);
    let t3 = g.sin(cv);
    let f = g.sum(&[t1, t2, t3]);
    let d1 = derivative(&mut g, f, &rates);
    let d2 = nth_derivative(&mut g, f, &rates, 2);
    for _ in 0..50 {
        let (etav, phi, amp, bmp, kv) = (
            rng.range(0.2, 3.0),
            rng.range(0.0, 6.3),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-2.0, 2.0),
        );
        let t0 = rng.range(0.0, 5.0);
        let at = |g: &mut Graph, t: f64| {
            let th = etav * t + phi;
            env(
                g,
                &[
                    ("eta", etav),
                    ("k", kv),
                    ("ct", th.cos()),
                    ("st", th.sin()),
                    ("x", amp * t.cos() + bmp * t.sin()),
                    ("v", -amp * t.sin() + bmp * t.cos()),
                ],
            )
        };
        let h = 1e-4;
        let (fm, f0, fp) = {
            let (em, e0, ep) = (at(&mut g, t0 - h), at(&mut g, t0), at(&mut g, t0 + h));
            (g.eval(f, &em), g.eval(f, &e0), g.eval(f, &ep))
        };
        let e0 = at(&mut g, t0);
        let exact1 = g.eval(d1, &e0);
        let exact2 = g.eval(d2, &e0);
        let fd1 = (fp - fm) / (2.0 * h);
        // Second difference: truncation h²|f⁗|/12 ≈ 1e-9·|f⁗|, rounding 4u|f|/h² ≈ 5e-8·|f|.
        let fd2 = (fp - 2.0 * f0 + fm) / (h * h);
        assert!(
            (exact1 - fd1).abs() <= 1e-6 * (1.0 + exact1.abs()),
            "d/dt: {exact1} vs {fd1}"
        );
        assert!(
            (exact2 - fd2).abs() <= 1e-5 * (1.0 + exact2.abs()),
            "d²/dt²: {exact2} vs {fd2}"
        );
    }
    // A symbol without a rate is constant: d(k)/dt = 0 exactly.
    let dk = derivative(&mut g, k, &rates);
    assert!(g.is_const(dk, 0.0));
}
