//! A square system A x = b that may be singular but consistent: Gaussian elimination with
//! complete pivoting (Golub & Van Loan, 4th ed., §3.4.8), which reveals the rank of A as the
//! step where every remaining entry is negligible, and then checks that b's transformed entries
//! in the negligible rows are negligible too. Used where a singular matrix is legitimate when the
//! forcing does not excite its null space: an undamped mode exactly at the forcing frequency with
//! no forcing on it (the stator ring's modes in free flight), a free rigid-body mode with a
//! constant force that does not push along it.
//!
//! **Thresholds.** An entry is negligible when ≤ n·ε·max|a_ij| (the partial-pivoting LU's test,
//! [`super::Lu`]); b's transformed entry when ≤ 1e3·n·ε·max|b̃| (b̃: b after the elimination).
//! Such a residual is rounding of the elimination, or a forcing of the null space so small that
//! its response (growing like ε·t) is below any reported digit for t < 1e12. The unknowns of the
//! negligible columns are set to 0: one particular solution (any one makes
//! y_p(s) + e^{As}(y0 − y_p(0)) exact).

use super::dense::{Matrix, Scalar};

/// Relative size of b's negligible-row residual accepted as consistent (times n·ε).
const CONSISTENCY: f64 = 1e3;

/// Solve A x = b in place (`x` holds b on entry, n entries) for a square A, singular or not.
/// `Err(k)`: b is inconsistent with A's negligible part, whose first elimination step is k
/// (A has numerical rank k).
pub(crate) fn solve_consistent<T: Scalar, const CAP: usize>(
    a: &Matrix<T, CAP>,
    x: &mut [T],
) -> Result<(), usize> {
    let n = a.rows().min(a.cols());
    let Some(x) = x.get_mut(..n) else {
        return Err(0);
    };
    let mut u = a.clone();
    let mut columns = [0usize; CAP];
    columns.iter_mut().enumerate().for_each(|(i, c)| *c = i);
    let tiny = n as f64 * f64::EPSILON * a.max_magnitude();
    let mut rank = n;
    for k in 0..n {
        // The pivot: the largest magnitude in the trailing block.
        let (mut p, mut q, mut size) = (k, k, -1.0);
        for i in k..n {
            for j in k..n {
                let m = u.get(i, j).magnitude();
                if m > size {
                    (p, q, size) = (i, j, m);
                }
            }
        }
        if size.is_nan() || size <= tiny {
            rank = k;
            break;
        }
        if p != k {
            if let Some((rk, rp)) = u.two_rows_mut(k, p) {
                rk.swap_with_slice(rp);
            }
            x.swap(k, p);
        }
        if q != k {
            for i in 0..n {
                let (a, b) = (u.get(i, k), u.get(i, q));
                u.set(i, k, b);
                u.set(i, q, a);
            }
            columns.swap(k, q);
        }
        let pivot = u.get(k, k);
        let xk = x.get(k).copied().unwrap_or(T::ZERO);
        for i in k + 1..n {
            let l = u.get(i, k) / pivot;
            if l == T::ZERO {
                continue;
            }
            u.set(i, k, T::ZERO);
            for j in k + 1..n {
                let v = u.get(i, j) - l * u.get(k, j);
                u.set(i, j, v);
            }
            if let Some(xi) = x.get_mut(i) {
                *xi -= l * xk;
            }
        }
    }
    let scale = x.iter().map(|v| v.magnitude()).fold(0.0, f64::max);
    let tolerance = CONSISTENCY * n as f64 * f64::EPSILON * scale;
    if x.iter()
        .skip(rank)
        .any(|v| v.magnitude().is_nan() || v.magnitude() > tolerance)
    {
        return Err(rank);
    }
    let mut z = [T::ZERO; CAP];
    for i in (0..rank).rev() {
        let mut s = x.get(i).copied().unwrap_or(T::ZERO);
        for j in i + 1..rank {
            s -= u.get(i, j) * z.get(j).copied().unwrap_or(T::ZERO);
        }
        if let Some(zi) = z.get_mut(i) {
            *zi = s / u.get(i, i);
        }
    }
    x.iter_mut().for_each(|v| *v = T::ZERO);
    for (i, &c) in columns.iter().enumerate().take(rank) {
        if let Some(slot) = x.get_mut(c) {
            *slot = z.get(i).copied().unwrap_or(T::ZERO);
        }
    }
    Ok(())
}
