//! Polynomial particular solutions (for exprb43's φ-terms, `docs/MODEL.md` §8): a cubic forcing
//! a0 + a1 s + a2 s² + a3 s³ has the cubic particular solution b0 + b1 s + b2 s² + b3 s³.

use super::{Model, Rates};
use crate::derive::{derivative, nth_derivative};

const B: [[&str; 2]; 4] = [
    ["b0x", "b0y"],
    ["b1x", "b1y"],
    ["b2x", "b2y"],
    ["b3x", "b3y"],
];
const A: [[&str; 2]; 4] = [
    ["a0x", "a0y"],
    ["a1x", "a1y"],
    ["a2x", "a2y"],
    ["a3x", "a3y"],
];

pub(super) fn derive(m: &mut Model) {
    polynomial_particular(m);
    polynomial_eval(m);
}

/// Σ c_k s^k for coefficient names `names` (x or y component `i`).
fn cubic(m: &mut Model, names: &[[&str; 2]; 4], i: usize) -> crate::expr::ExprId {
    let s = m.var("s");
    let terms: Vec<_> = (0..4)
        .map(|k| {
            let c = m.var(names[k][i]);
            let p = m.graph.powi(s, k as i32);
            m.graph.mul(c, p)
        })
        .collect();
    m.graph.sum(&terms)
}

fn polynomial_particular(m: &mut Model) {
    let s_sym = m.sym("s");
    let one = m.graph.constant(1.0);
    let rates = Rates::from([(s_sym, one)]);
    let q = [cubic(m, &B, 0), cubic(m, &B, 1)];
    let forcing = [cubic(m, &A, 0), cubic(m, &A, 1)];
    let (kl, _) = m.linearized_inputs();
    let zero = m.graph.constant(0.0);
    let stiffness = m.linear_stiffness_term(kl, [zero, zero], q);
    let r = m.equations_of_motion(q, &rates, stiffness, forcing);
    // Coefficient of s^k: the k-th derivative at s = 0 over k!.
    let mut eqs = Vec::new();
    for k in 0..4 {
        for ri in r {
            let d = nth_derivative(&mut m.graph, ri, &rates, k);
            let d0 = m.subst(d, &[("s", zero)]);
            let fact = [1.0, 1.0, 2.0, 6.0][k];
            eqs.push(m.graph.scale(1.0 / fact, d0));
        }
    }
    let unknowns: Vec<&str> = B.iter().flatten().copied().collect();
    let sol = m.solve(&eqs, &unknowns);
    let docs = [
        "b0 (constant), x",
        "b0, y",
        "b1 (linear), x",
        "b1, y",
        "b2 (quadratic), x",
        "b2, y",
        "b3 (cubic), x",
        "b3, y",
    ];
    let outputs = unknowns
        .iter()
        .zip(docs)
        .zip(sol)
        .map(|((&n, d), e)| (n, d, e))
        .collect();
    m.add_formula(
        "polynomial_particular",
        "Cubic particular solution of q'' + 2νq' + Kl q = a0 + a1 s + a2 s² + a3 s³.",
        "docs/MODEL.md §8 (φ-terms as polynomial particular solutions)",
        "cubic ansatz substituted into the linearized equations; coefficients of s³, s², s, 1 solved top-down as 2×2 blocks with Kl (Cramer).",
        "PolynomialParticular",
        outputs,
    );
}

fn polynomial_eval(m: &mut Model) {
    let s_sym = m.sym("s");
    let one = m.graph.constant(1.0);
    let rates = Rates::from([(s_sym, one)]);
    let q = [cubic(m, &B, 0), cubic(m, &B, 1)];
    let v = [
        derivative(&mut m.graph, q[0], &rates),
        derivative(&mut m.graph, q[1], &rates),
    ];
    m.add_formula(
        "polynomial_eval",
        "Position and velocity of the cubic particular solution at local time s.",
        "docs/MODEL.md §8",
        "the cubic and its derivative.",
        "PolynomialState",
        vec![
            ("x", "x", q[0]),
            ("y", "y", q[1]),
            ("vx", "x'", v[0]),
            ("vy", "y'", v[1]),
        ],
    );
}
