//! The first two steps of the eigen-decomposition of a real matrix: balancing (a diagonal
//! similarity by powers of 2, exact in floating point, that makes row and column norms
//! comparable: LAPACK `dgebal`'s scaling, Parlett & Reinsch 1969) and the orthogonal reduction
//! to upper Hessenberg form by Householder reflections (Golub & Van Loan, 4th ed., Algorithm
//! 7.4.2), accumulating the transformation.
//!
//! A first-order rotor matrix in SI units mixes K/M ~ ω² (up to 1e8) with the identity block;
//! balancing brings both to ~ω, so the QR iteration's absolute errors (ε·‖A‖) become relative
//! to each mode's scale. Hessenberg reduction is backward stable: Q H Qᵀ = A + E with
//! ‖E‖ ≲ c·m²·ε·‖A‖ (in practice c·m·ε).

use super::dense::RealMatrix;
use crate::math;

/// Scaling factors no smaller or larger than this (LAPACK's `sfmin`/`sfmax` guard, simplified).
const SCALE_LIMIT: f64 = 1e150;
/// At most this many balancing sweeps (LAPACK stops when no sweep improves by 5 %; this only
/// caps pathological input).
const MAX_SWEEPS: usize = 64;

/// Balance `a` in place, Â = D⁻¹ A D with D = diag(scale), scale_i powers of 2; returns nothing,
/// writes the scales (entries beyond the size are 1).
pub(crate) fn balance<const CAP: usize>(a: &mut RealMatrix<CAP>, scale: &mut [f64; CAP]) {
    let n = a.rows();
    scale.iter_mut().for_each(|s| *s = 1.0);
    for _ in 0..MAX_SWEEPS {
        let mut changed = false;
        for i in 0..n {
            // Off-diagonal 2-norms of column i and row i.
            let c = math::sqrt(
                (0..n)
                    .filter(|&k| k != i)
                    .map(|k| a.get(k, i) * a.get(k, i))
                    .sum::<f64>(),
            );
            let r = math::sqrt(
                (0..n)
                    .filter(|&k| k != i)
                    .map(|k| a.get(i, k) * a.get(i, k))
                    .sum::<f64>(),
            );
            if c == 0.0 || r == 0.0 || !c.is_finite() || !r.is_finite() {
                continue;
            }
            let (mut f, mut cc, mut rr) = (1.0, c, r);
            while cc < rr / 2.0 && f < SCALE_LIMIT {
                f *= 2.0;
                cc *= 2.0;
                rr /= 2.0;
            }
            while cc / 2.0 >= rr && f > 1.0 / SCALE_LIMIT {
                f /= 2.0;
                cc /= 2.0;
                rr *= 2.0;
            }
            if cc + rr >= 0.95 * (c + r) {
                continue;
            }
            changed = true;
            if let Some(s) = scale.get_mut(i) {
                *s *= f;
            }
            // Row i by 1/f, column i by f.
            a.row_mut(i).iter_mut().for_each(|x| *x /= f);
            for k in 0..n {
                let v = a.get(k, i) * f;
                a.set(k, i, v);
            }
        }
        if !changed {
            break;
        }
    }
}

/// Reduce `a` in place to upper Hessenberg form H = Qᵀ A Q and write Q into `q` (entries
/// below the subdiagonal are set to exactly 0).
pub(crate) fn hessenberg<const CAP: usize>(a: &mut RealMatrix<CAP>, q: &mut RealMatrix<CAP>) {
    let n = a.rows();
    // `q` has a's size (the callers' storage is at least that large).
    if q.resize(n, n).is_err() {
        return;
    }
    q.set_identity();
    let mut v = [0.0; CAP];
    for k in 0..n.saturating_sub(2) {
        // x = a[k+1.., k]; v = x − α e1 with α = −sign(x0)‖x‖.
        let norm = math::sqrt((k + 1..n).map(|i| a.get(i, k) * a.get(i, k)).sum::<f64>());
        let tail = (k + 2..n).map(|i| a.get(i, k) * a.get(i, k)).sum::<f64>();
        if norm == 0.0 || tail == 0.0 {
            continue;
        }
        let x0 = a.get(k + 1, k);
        let alpha = if x0 > 0.0 { -norm } else { norm };
        for (i, vi) in v.iter_mut().enumerate().take(n) {
            *vi = if i <= k { 0.0 } else { a.get(i, k) };
        }
        if let Some(v0) = v.get_mut(k + 1) {
            *v0 = x0 - alpha;
        }
        let vv: f64 = v.iter().take(n).skip(k + 1).map(|x| x * x).sum();
        if vv.is_nan() || vv <= 0.0 {
            continue;
        }
        let beta = 2.0 / vv;
        // A ← (I − βvvᵀ) A: rows k+1.. (columns k.. carry nonzeros).
        for j in k..n {
            let s: f64 = (k + 1..n)
                .map(|i| v.get(i).copied().unwrap_or(0.0) * a.get(i, j))
                .sum();
            let s = beta * s;
            for i in k + 1..n {
                let x = a.get(i, j) - s * v.get(i).copied().unwrap_or(0.0);
                a.set(i, j, x);
            }
        }
        // A ← A (I − βvvᵀ) and Q ← Q (I − βvvᵀ): every row, columns k+1..
        for m in [&mut *a, &mut *q] {
            for i in 0..n {
                let row = m.row_mut(i);
                let s: f64 = row
                    .iter()
                    .zip(v.iter())
                    .skip(k + 1)
                    .map(|(x, y)| x * y)
                    .sum();
                let s = beta * s;
                row.iter_mut()
                    .zip(v.iter())
                    .skip(k + 1)
                    .for_each(|(x, y)| *x -= s * y);
            }
        }
        a.set(k + 1, k, alpha);
        for i in k + 2..n {
            a.set(i, k, 0.0);
        }
    }
}
