//! Symbolic solution of linear systems.
//!
//! The model's systems are small (2 to 8 unknowns) and often block-triangular (initial conditions:
//! positions before velocities; polynomial ansatz: highest degree first). The solver finds that
//! structure, then solves each block by Cramer's rule with determinants expanded along rows.
//! Cramer divides only by the block's determinant, so a formula is singular exactly where the
//! system is, never because an intermediate pivot happened to vanish (which symbolic Gaussian
//! elimination would do, e.g. at Fa1 = η²).

use std::collections::HashMap;

use super::diff::partial;
use crate::expr::{ExprId, Graph, Symbol};

/// Why a system could not be solved symbolically.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SolveError {
    /// An equation is not linear in the unknowns.
    NotLinear(usize),
    /// No block of equations determines a set of remaining unknowns.
    Underdetermined,
}

/// Solve `equations[i] = 0` for `unknowns` (linear). Returns one expression per unknown.
pub fn solve_linear(
    g: &mut Graph,
    equations: &[ExprId],
    unknowns: &[Symbol],
) -> Result<Vec<ExprId>, SolveError> {
    let n = unknowns.len();
    assert_eq!(equations.len(), n, "square systems only");
    // Coefficient matrix and right-hand side: E = M u − b.
    let zero = g.constant(0.0);
    let at_zero: HashMap<Symbol, ExprId> = unknowns.iter().map(|&u| (u, zero)).collect();
    let mut m = vec![vec![zero; n]; n];
    let mut rhs = vec![zero; n];
    for (i, &e) in equations.iter().enumerate() {
        for (j, &u) in unknowns.iter().enumerate() {
            let c = partial(g, e, u);
            if unknowns.iter().any(|&v| g.depends_on(c, v)) {
                return Err(SolveError::NotLinear(i));
            }
            m[i][j] = c;
        }
        let e0 = g.substitute(e, &at_zero);
        rhs[i] = g.neg(e0);
    }
    let mut solution: Vec<Option<ExprId>> = vec![None; n];
    let mut remaining: Vec<usize> = (0..n).collect();
    while !remaining.is_empty() {
        let (rows, cols) =
            smallest_block(g, &m, &remaining, &solution).ok_or(SolveError::Underdetermined)?;
        // Move known unknowns to the right-hand side.
        let mut block_rhs = Vec::with_capacity(rows.len());
        for &i in &rows {
            let mut terms = vec![rhs[i]];
            for (j, known) in solution.iter().enumerate() {
                if let Some(v) = *known {
                    let t = g.mul(m[i][j], v);
                    terms.push(g.neg(t));
                }
            }
            block_rhs.push(g.sum(&terms));
        }
        let block: Vec<Vec<ExprId>> = rows
            .iter()
            .map(|&i| cols.iter().map(|&j| m[i][j]).collect())
            .collect();
        let values = cramer(g, &block, &block_rhs);
        for (k, &j) in cols.iter().enumerate() {
            solution[j] = Some(values[k]);
        }
        remaining.retain(|i| !rows.contains(i));
    }
    Ok(solution
        .into_iter()
        .map(|v| v.expect("every unknown solved"))
        .collect())
}

/// The smallest set of remaining equations whose still-unknown unknowns are exactly as many as
/// the equations (brute force over subsets; systems here have at most 8 equations).
fn smallest_block(
    g: &Graph,
    m: &[Vec<ExprId>],
    remaining: &[usize],
    solution: &[Option<ExprId>],
) -> Option<(Vec<usize>, Vec<usize>)> {
    let r = remaining.len();
    let mut best: Option<(Vec<usize>, Vec<usize>)> = None;
    for mask in 1u32..(1 << r) {
        let rows: Vec<usize> = (0..r)
            .filter(|k| mask & (1 << k) != 0)
            .map(|k| remaining[k])
            .collect();
        if best.as_ref().is_some_and(|(b, _)| b.len() <= rows.len()) {
            continue;
        }
        let mut cols: Vec<usize> = (0..m.len())
            .filter(|&j| solution[j].is_none() && rows.iter().any(|&i| !g.is_const(m[i][j], 0.0)))
            .collect();
        cols.sort_unstable();
        if cols.len() == rows.len() {
            best = Some((rows, cols));
        }
    }
    best
}

/// Cramer's rule: `a x = b`.
fn cramer(g: &mut Graph, a: &[Vec<ExprId>], b: &[ExprId]) -> Vec<ExprId> {
    let det = determinant(g, a);
    let inv_det = g.powi(det, -1);
    (0..b.len())
        .map(|j| {
            let replaced: Vec<Vec<ExprId>> = a
                .iter()
                .enumerate()
                .map(|(i, row)| {
                    let mut r = row.clone();
                    r[j] = b[i];
                    r
                })
                .collect();
            let num = determinant(g, &replaced);
            g.mul(num, inv_det)
        })
        .collect()
}

/// Determinant by Laplace expansion along the first row, skipping zero entries.
pub fn determinant<R: AsRef<[ExprId]>>(g: &mut Graph, a: &[R]) -> ExprId {
    let a: Vec<&[ExprId]> = a.iter().map(|r| r.as_ref()).collect();
    let n = a.len();
    match n {
        0 => g.constant(1.0),
        1 => a[0][0],
        2 => {
            let p = g.mul(a[0][0], a[1][1]);
            let q = g.mul(a[0][1], a[1][0]);
            g.sub(p, q)
        }
        _ => {
            let mut terms = Vec::new();
            for j in 0..n {
                if g.is_const(a[0][j], 0.0) {
                    continue;
                }
                let minor: Vec<Vec<ExprId>> = a[1..]
                    .iter()
                    .copied()
                    .map(|row| {
                        row.iter()
                            .enumerate()
                            .filter(|&(k, _)| k != j)
                            .map(|(_, &e)| e)
                            .collect()
                    })
                    .collect();
                let d = determinant(g, &minor);
                let t = g.mul(a[0][j], d);
                terms.push(if j % 2 == 0 { t } else { g.neg(t) });
            }
            g.sum(&terms)
        }
    }
}
