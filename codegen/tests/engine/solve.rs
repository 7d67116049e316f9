//! Linear solves and determinants against Gaussian elimination.

use super::*;

// ---------------------------------------------------------------------------------------------
// Linear solver.

/// Solve a numeric system by Gaussian elimination with partial pivoting (reference).
fn gauss(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..n {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    x
}

/// A symbolic system M u = b with M[i][j] = symbol `m{i}{j}` (or structural zero where
/// `zero(i, j)`), b[i] = `b{i}` + sin(p)·u-free term. Returns (equations, unknowns).
fn symbolic_system(
    g: &mut Graph,
    n: usize,
    zero: &dyn Fn(usize, usize) -> bool,
) -> (Vec<ExprId>, Vec<Symbol>) {
    let unknowns: Vec<Symbol> = (0..n).map(|j| g.symbol(&format!("u{j}"))).collect();
    let p = g.input("p");
    let sp = g.sin(p);
    let mut eqs = Vec::new();
    for i in 0..n {
        let mut terms = Vec::new();
        for (j, &u) in unknowns.iter().enumerate() {
            if zero(i, j) {
                continue;
            }
            let m = g.input(&format!("m{i}{j}"));
            let uj = g.input_of(u);
            terms.push(g.mul(m, uj));
        }
        let b = g.input(&format!("b{i}"));
        let rhs = g.mul(b, sp);
        terms.push(g.neg(rhs));
        eqs.push(g.sum(&terms));
    }
    (eqs, unknowns)
}

/// Random diagonally dominant values (|m_ii| ∈ [2, 3], |m_ij| ≤ 0.5/… so that Σ_{j≠i}|m_ij| ≤ 1.5,
/// condition number ≤ (3 + 1.5)/(2 − 1.5) = 9) for the symbols of [`symbolic_system`].
fn system_values(
    rng: &mut Rng,
    n: usize,
    zero: &dyn Fn(usize, usize) -> bool,
) -> (Vec<Vec<f64>>, Vec<f64>, f64) {
    let off = 1.5 / (n.max(2) - 1) as f64;
    let m: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    if zero(i, j) {
                        0.0
                    } else if i == j {
                        rng.range(2.0, 3.0) * if rng.unit() < 0.5 { -1.0 } else { 1.0 }
                    } else {
                        rng.range(-off, off)
                    }
                })
                .collect()
        })
        .collect();
    let b = (0..n).map(|_| rng.range(-2.0, 2.0)).collect();
    (m, b, rng.range(0.3, 2.8))
}

fn check_solution(
    g: &mut Graph,
    eqs: &[ExprId],
    unknowns: &[Symbol],
    sol: &[ExprId],
    m: &[Vec<f64>],
    b: &[f64],
    p: f64,
) {
    let n = b.len();
    let mut en = Env::default();
    for i in 0..n {
        for j in 0..n {
            en.set(g, &format!("m{i}{j}"), m[i][j]);
        }
        en.set(g, &format!("b{i}"), b[i]);
    }
    en.set(g, "p", p);
    let u: Vec<f64> = sol.iter().map(|&s| g.eval(s, &en)).collect();
    // Residual of each symbolic equation at the solution.
    let mut full = en.clone();
    for (j, &s) in unknowns.iter().enumerate() {
        full.0.insert(s, u[j]);
    }
    let rhs: Vec<f64> = b.iter().map(|&bi| bi * p.sin()).collect();
    for (i, &e) in eqs.iter().enumerate() {
        let r = g.eval(e, &full);
        let scale: f64 = (0..n).map(|j| (m[i][j] * u[j]).abs()).sum::<f64>() + rhs[i].abs();
        assert!(
            r.abs() <= 1e-11 * scale,
            "equation {i}: residual {r} (scale {scale})"
        );
    }
    // And the same numbers as a pivoted elimination (cond ≤ 9: forward error ≲ 1e-14).
    let reference = gauss(m.to_vec(), rhs);
    let norm = reference.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for j in 0..n {
        assert!(
            (u[j] - reference[j]).abs() <= 1e-11 * norm,
            "u{j}: {} vs {}",
            u[j],
            reference[j]
        );
    }
}

#[test]
fn solve_linear_dense_systems() {
    let mut rng = Rng::new(10);
    for n in [1, 2, 3, 4] {
        let dense = |_: usize, _: usize| false;
        let mut g = Graph::new();
        let (eqs, unknowns) = symbolic_system(&mut g, n, &dense);
        let sol = solve_linear(&mut g, &eqs, &unknowns).expect("solvable");
        assert_eq!(sol.len(), n);
        for &s in &sol {
            for &u in &unknowns {
                assert!(!g.depends_on(s, u), "solution depends on an unknown");
            }
        }
        for _ in 0..40 {
            let (m, b, p) = system_values(&mut rng, n, &dense);
            check_solution(&mut g, &eqs, &unknowns, &sol, &m, &b, p);
        }
    }
}

/// Block-triangular: rows 0–1 involve only u2, u3; rows 2–4 involve everything. The solver must
/// solve the 2×2 block first: u2, u3 must not depend on the other rows' coefficients.
#[test]
fn solve_linear_block_triangular_system() {
    let mut rng = Rng::new(11);
    let n = 5;
    let zero = |i: usize, j: usize| i < 2 && j != 2 && j != 3;
    let mut g = Graph::new();
    let (eqs, unknowns) = symbolic_system(&mut g, n, &zero);
    let sol = solve_linear(&mut g, &eqs, &unknowns).expect("solvable");
    for j in [2, 3] {
        for i in 2..n {
            for k in 0..n {
                let s = g.symbol(&format!("m{i}{k}"));
                assert!(
                    !g.depends_on(sol[j], s),
                    "u{j} depends on m{i}{k}: block not separated"
                );
            }
        }
    }
    for _ in 0..60 {
        // Diagonal dominance for the block's own diagonal: rows 0–1 use columns 2, 3.
        let (mut m, b, p) = system_values(&mut rng, n, &zero);
        // Rows 0–1 are [·, ·, a, b, ·]: make the block strongly diagonal.
        m[0][2] = rng.range(2.0, 3.0);
        m[1][3] = rng.range(2.0, 3.0);
        m[0][3] = rng.range(-0.5, 0.5);
        m[1][2] = rng.range(-0.5, 0.5);
        // The remaining rows' leading block (u0, u1, u4) must be dominant too.
        m[2][0] = rng.range(2.0, 3.0);
        m[3][1] = rng.range(2.0, 3.0);
        m[4][4] = rng.range(2.0, 3.0);
        m[2][2] = rng.range(-0.3, 0.3);
        m[3][3] = rng.range(-0.3, 0.3);
        check_solution(&mut g, &eqs, &unknowns, &sol, &m, &b, p);
    }
}

#[test]
fn solve_linear_rejects_nonlinear_and_underdetermined() {
    let mut g = Graph::new();
    let (u0, u1) = (g.input("u0"), g.input("u1"));
    let (s0, s1) = (g.symbol("u0"), g.symbol("u1"));
    let prod = g.mul(u0, u1);
    let one = g.constant(1.0);
    let e0 = g.sub(prod, one);
    let e1 = g.add(u0, u1);
    assert_eq!(
        solve_linear(&mut g, &[e0, e1], &[s0, s1]),
        Err(SolveError::NotLinear(0))
    );
    // Both equations involve only u0: no block determines u1.
    let a = g.input("a");
    let e0 = g.sub(u0, one);
    let au0 = g.mul(a, u0);
    let e1 = g.sub(au0, a);
    assert_eq!(
        solve_linear(&mut g, &[e0, e1], &[s0, s1]),
        Err(SolveError::Underdetermined)
    );
}

#[test]
fn determinant_matches_elimination() {
    let mut rng = Rng::new(12);
    for n in 1..=4 {
        let mut g = Graph::new();
        let a: Vec<Vec<ExprId>> = (0..n)
            .map(|i| (0..n).map(|j| g.input(&format!("a{i}{j}"))).collect())
            .collect();
        let det = determinant(&mut g, &a);
        for _ in 0..30 {
            let mut en = Env::default();
            let vals: Vec<Vec<f64>> = (0..n)
                .map(|_| (0..n).map(|_| rng.range(-1.0, 1.0)).collect())
                .collect();
            for i in 0..n {
                for j in 0..n {
                    en.set(&mut g, &format!("a{i}{j}"), vals[i][j]);
                }
            }
            // Reference: product of pivots of a pivoted elimination, with the swap sign.
            let mut m = vals.clone();
            let mut reference = 1.0;
            for c in 0..n {
                let p = (c..n)
                    .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
                    .unwrap();
                if p != c {
                    m.swap(c, p);
                    reference = -reference;
                }
                reference *= m[c][c];
                for r in c + 1..n {
                    let f = m[r][c] / m[c][c];
                    for k in c..n {
                        m[r][k] -= f * m[c][k];
                    }
                }
            }
            let got = g.eval(det, &en);
            // Entries ≤ 1: each of the n! products ≤ 1, so rounding ≤ n!·n·u ≪ 1e-12.
            assert!((got - reference).abs() <= 1e-12, "det {got} vs {reference}");
        }
    }
}
