//! Derivatives of random expressions against forward-mode dual numbers.

use super::*;

// ---------------------------------------------------------------------------------------------
// Random derivatives: the graph's derivative of a random expression against forward-mode dual
// numbers on the reference AST (an independent implementation of the same rules).

impl Ast {
    /// (value, d/dx_k, magnitude scale of the derivative's terms).
    fn dual(&self, x: &[f64], k: usize) -> (f64, f64, f64) {
        match self {
            Ast::Var(i) => (
                x[*i],
                if *i == k { 1.0 } else { 0.0 },
                if *i == k { 1.0 } else { 0.0 },
            ),
            Ast::Const(c) => (*c, 0.0, 0.0),
            Ast::Add(a, b) | Ast::Sub(a, b) => {
                let ((a, da, ma), (b, db, mb)) = (a.dual(x, k), b.dual(x, k));
                if matches!(self, Ast::Add(..)) {
                    (a + b, da + db, ma + mb)
                } else {
                    (a - b, da - db, ma + mb)
                }
            }
            Ast::Mul(a, b) => {
                let ((a, da, ma), (b, db, mb)) = (a.dual(x, k), b.dual(x, k));
                (a * b, da * b + a * db, ma * b.abs() + a.abs() * mb)
            }
            Ast::Div(a, b) => {
                let ((a, da, ma), (b, db, mb)) = (a.dual(x, k), b.dual(x, k));
                let v = a / b;
                (v, (da - v * db) / b, (ma + v.abs() * mb) / b.abs())
            }
            Ast::Powi(a, n) => {
                let (a, da, ma) = a.dual(x, k);
                let nf = f64::from(*n);
                let p = a.powi(n - 1);
                (a.powi(*n), nf * p * da, nf.abs() * p.abs() * ma)
            }
            Ast::Sqrt(a) => {
                let (a, da, ma) = a.dual(x, k);
                let v = a.sqrt();
                (v, da / (2.0 * v), ma / (2.0 * v))
            }
            Ast::Exp(a) => {
                let (a, da, ma) = a.dual(x, k);
                let v = a.exp();
                (v, v * da, v * ma)
            }
            Ast::Sin(a) => {
                let (a, da, ma) = a.dual(x, k);
                (a.sin(), a.cos() * da, ma)
            }
            Ast::Cos(a) => {
                let (a, da, ma) = a.dual(x, k);
                (a.cos(), -a.sin() * da, ma)
            }
        }
    }
}

#[test]
fn derivatives_of_random_expressions_match_dual_numbers() {
    let mut rng = Rng::new(9);
    let mut compared = 0;
    for _ in 0..1500 {
        let mut g = Graph::new();
        let ast = Ast::random(&mut rng, 4, &GENERAL_CONSTS);
        let id = ast.build(&mut g);
        let k = rng.below(VARS.len());
        let sk = g.symbol(VARS[k]);
        let d = partial(&mut g, id, sk);
        let x: Vec<f64> = (0..VARS.len()).map(|_| rng.range(-2.0, 2.0)).collect();
        let (v, dv, mag) = ast.dual(&x, k);
        let (_, e_val) = ast.eval(&x);
        if !(v.is_finite() && dv.is_finite() && mag.is_finite())
            || mag > 1e100
            || !e_val.is_finite()
        {
            continue;
        }
        // Only well-conditioned points: the value's own rounding bound is small, so that no
        // operand sits near a singularity (√0, 0⁻¹) where both derivatives are rounding noise.
        if e_val > 1e-12 * v.abs().max(1.0) {
            continue;
        }
        let (en, _) = bindings(&mut g, &x);
        let got = g.eval(d, &en);
        compared += 1;
        // The derivative's terms have magnitude ≤ mag; both evaluations round each of at most
        // ~100 operations by u relative to that scale.
        assert!(
            (got - dv).abs() <= 1e-11 * (mag + dv.abs()) + 1e-300,
            "∂/∂{} of {ast:?} at {x:?}: graph {got}, dual {dv} (scale {mag})",
            VARS[k]
        );
    }
    assert!(compared > 700, "only {compared} comparisons");
}
