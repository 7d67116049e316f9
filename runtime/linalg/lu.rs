//! LU factorization with partial pivoting, P A = L U, real or complex (Golub & Van Loan,
//! *Matrix Computations*, 4th ed., Algorithm 3.4.1, the row-oriented gaxpy form): the solves of
//! the linear algebra — M⁻¹ for the first-order matrix, the harmonic response's
//! (K − η²M + iη(C + ηG)) Z = F, the static deflection K q = u.
//!
//! Backward stable in practice (growth factor ≤ 2^(n−1), small for the matrices met here): the
//! computed solution solves (A + E) x = b with ‖E‖ ≲ n·ε·growth·‖A‖. A matrix whose pivot falls to
//! n·ε·max|a_ij| or below is reported singular to working precision
//! ([`LinalgError::Singular`]), never divided by.

use super::dense::{Matrix, Scalar, axpy};
use super::error::LinalgError;

/// The factors of P A = L U (L unit lower, U upper, stored in one matrix) and the pivot rows.
#[derive(Clone, Debug)]
pub struct Lu<T: Scalar, const CAP: usize> {
    lu: Matrix<T, CAP>,
    /// Row swapped with row k at step k.
    pivots: [usize; CAP],
    /// −1 when the pivots made an odd permutation.
    sign: f64,
}

impl<T: Scalar, const CAP: usize> Lu<T, CAP> {
    /// Factor a square matrix; `what` names it in errors ("mass matrix", …).
    ///
    /// ```
    /// use rotor_rub::linalg::{Lu, RealMatrix};
    /// let a = RealMatrix::<2>::from_rows(&[&[0.0, 2.0], &[1.0, 1.0]]).unwrap();
    /// let lu = Lu::factor(&a, "a").unwrap();
    /// let mut x = [4.0, 3.0];
    /// lu.solve(&mut x);
    /// assert_eq!(x, [1.0, 2.0]);
    /// assert_eq!(lu.determinant(), -2.0);
    /// ```
    pub fn factor(a: &Matrix<T, CAP>, what: &'static str) -> Result<Self, LinalgError> {
        let n = a.check_square(what)?;
        let tiny = n as f64 * f64::EPSILON * a.max_magnitude();
        let mut lu = a.clone();
        let mut pivots = [0usize; CAP];
        let mut sign = 1.0;
        for k in 0..n {
            // The pivot: the largest magnitude in column k at or below the diagonal.
            let (p, size) = (k..n)
                .map(|i| (i, lu.get(i, k).magnitude()))
                .fold((k, -1.0), |best, c| if c.1 > best.1 { c } else { best });
            if size.is_nan() || size <= tiny {
                return Err(LinalgError::Singular { what, column: k });
            }
            if let Some(slot) = pivots.get_mut(k) {
                *slot = p;
            }
            if p != k {
                if let Some((rk, rp)) = lu.two_rows_mut(k, p) {
                    rk.swap_with_slice(rp);
                }
                sign = -sign;
            }
            for i in k + 1..n {
                if let Some((rk, ri)) = lu.two_rows_mut(k, i) {
                    let (Some(&rkk), Some(rik)) = (rk.get(k), ri.get_mut(k)) else {
                        continue;
                    };
                    let l = *rik / rkk;
                    *rik = l;
                    if let (Some(src), Some(dst)) = (rk.get(k + 1..), ri.get_mut(k + 1..)) {
                        axpy(-l, src, dst);
                    }
                }
            }
        }
        Ok(Lu { lu, pivots, sign })
    }

    /// The size n.
    pub fn dim(&self) -> usize {
        self.lu.rows()
    }

    /// Solve A x = b in place (`x` holds b on entry; entries beyond n are left alone).
    pub fn solve(&self, x: &mut [T]) {
        let n = self.dim();
        let Some(x) = x.get_mut(..n) else {
            return;
        };
        for (k, &p) in self.pivots.iter().enumerate().take(n) {
            x.swap(k, p.min(n - 1));
        }
        // L y = P b (unit lower), then U x = y.
        for i in 0..n {
            let row = self.lu.row(i);
            let s = row
                .iter()
                .zip(x.iter())
                .take(i)
                .fold(T::ZERO, |acc, (&l, &y)| acc + l * y);
            if let Some(xi) = x.get_mut(i) {
                *xi -= s;
            }
        }
        for i in (0..n).rev() {
            let row = self.lu.row(i);
            let s = row
                .iter()
                .zip(x.iter())
                .skip(i + 1)
                .fold(T::ZERO, |acc, (&u, &y)| acc + u * y);
            let d = row.get(i).copied().unwrap_or(T::ONE);
            if let Some(xi) = x.get_mut(i) {
                *xi = (*xi - s) / d;
            }
        }
    }

    /// Solve A X = B column by column, in place (X holds B on entry, n rows).
    pub fn solve_matrix(&self, b: &mut Matrix<T, CAP>) {
        let n = self.dim();
        let mut col = [T::ZERO; CAP];
        for j in 0..b.cols() {
            for (i, c) in col.iter_mut().enumerate().take(n) {
                *c = b.get(i, j);
            }
            self.solve(&mut col);
            for (i, &c) in col.iter().enumerate().take(n) {
                b.set(i, j, c);
            }
        }
    }

    /// det A = ± Π u_kk (nonzero: a singular matrix does not factor).
    pub fn determinant(&self) -> T {
        let n = self.dim();
        let prod = (0..n).fold(T::ONE, |acc, k| acc * self.lu.get(k, k));
        if self.sign < 0.0 { -prod } else { prod }
    }

    /// The smallest |u_kk| over the largest: a cheap indicator of near-singularity (not a
    /// condition number).
    pub fn pivot_ratio(&self) -> f64 {
        let n = self.dim();
        let (lo, hi) = (0..n)
            .map(|k| self.lu.get(k, k).magnitude())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), u| {
                (lo.min(u), hi.max(u))
            });
        if hi > 0.0 { lo / hi } else { 0.0 }
    }
}
