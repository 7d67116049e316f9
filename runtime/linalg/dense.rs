//! Fixed-capacity dense matrices: storage for CAP × CAP entries, used for a runtime size
//! rows × cols ≤ CAP (const-generic capacity, runtime dimension), real or complex through
//! [`Scalar`]. Plain `Clone` data, no heap: the embedded stepper uses a small CAP, the CLI and
//! Python a boxed large one.
//!
//! Element access never panics: [`Matrix::get`] reads 0 outside the used size and
//! [`Matrix::set`] drops such writes. Every algorithm in this module loops within the used size,
//! so neither case happens; the fallbacks only keep the crate's no-panic rule without `unsafe`.

use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use super::complex::Complex;
use super::error::LinalgError;
use crate::math;

/// The field a matrix's entries live in: f64 or [`Complex`].
pub trait Scalar:
    Copy
    + Default
    + PartialEq
    + core::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// A cheap magnitude for pivoting and negligibility tests (|x|; |re| + |im| for complex).
    fn magnitude(self) -> f64;
    /// Finite (both parts for complex).
    fn finite(self) -> bool;
    /// The conjugate (identity for reals).
    fn conjugate(self) -> Self;
}

impl Scalar for f64 {
    const ZERO: f64 = 0.0;
    const ONE: f64 = 1.0;
    #[inline]
    fn magnitude(self) -> f64 {
        math::abs(self)
    }
    #[inline]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline]
    fn conjugate(self) -> f64 {
        self
    }
}

impl Scalar for Complex {
    const ZERO: Complex = Complex::ZERO;
    const ONE: Complex = Complex::ONE;
    #[inline]
    fn magnitude(self) -> f64 {
        self.abs1()
    }
    #[inline]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline]
    fn conjugate(self) -> Complex {
        self.conj()
    }
}

/// A rows × cols matrix in CAP × CAP storage (row-major: a row is a contiguous slice).
#[derive(Clone, Debug, PartialEq)]
pub struct Matrix<T: Scalar, const CAP: usize> {
    rows: usize,
    cols: usize,
    data: [[T; CAP]; CAP],
}

/// A real matrix.
pub type RealMatrix<const CAP: usize> = Matrix<f64, CAP>;
/// A complex matrix.
pub type ComplexMatrix<const CAP: usize> = Matrix<Complex, CAP>;

impl<T: Scalar, const CAP: usize> Matrix<T, CAP> {
    /// The rows × cols zero matrix; an error when either exceeds CAP.
    pub fn zeros(rows: usize, cols: usize) -> Result<Self, LinalgError> {
        for (what, n) in [("rows", rows), ("columns", cols)] {
            if n > CAP {
                return Err(LinalgError::TooLarge {
                    what,
                    size: n,
                    capacity: CAP,
                });
            }
        }
        Ok(Matrix {
            rows,
            cols,
            data: [[T::ZERO; CAP]; CAP],
        })
    }

    /// The n × n identity; an error when n exceeds CAP.
    pub fn identity(n: usize) -> Result<Self, LinalgError> {
        let mut a = Self::zeros(n, n)?;
        for i in 0..n {
            a.set(i, i, T::ONE);
        }
        Ok(a)
    }

    /// The matrix with entries `f(i, j)`.
    ///
    /// ```
    /// use rotor_rub::linalg::RealMatrix;
    /// let a = RealMatrix::<4>::from_fn(2, 3, |i, j| (10 * i + j) as f64).unwrap();
    /// assert_eq!(a.get(1, 2), 12.0);
    /// ```
    pub fn from_fn(
        rows: usize,
        cols: usize,
        mut f: impl FnMut(usize, usize) -> T,
    ) -> Result<Self, LinalgError> {
        let mut a = Self::zeros(rows, cols)?;
        for (i, row) in a.data.iter_mut().take(rows).enumerate() {
            for (j, x) in row.iter_mut().take(cols).enumerate() {
                *x = f(i, j);
            }
        }
        Ok(a)
    }

    /// The matrix from row slices (all of one length).
    pub fn from_rows(rows: &[&[T]]) -> Result<Self, LinalgError> {
        let cols = rows.first().map_or(0, |r| r.len());
        if let Some(bad) = rows.iter().find(|r| r.len() != cols) {
            return Err(LinalgError::Shape {
                what: "row length",
                got: bad.len(),
                expected: cols,
            });
        }
        Self::from_fn(rows.len(), cols, |i, j| {
            rows.get(i)
                .and_then(|r| r.get(j))
                .copied()
                .unwrap_or(T::ZERO)
        })
    }

    /// Rows in use.
    #[inline]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Columns in use.
    #[inline]
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Entry (i, j); 0 outside the used size.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> T {
        if j >= self.cols {
            return T::ZERO;
        }
        self.data
            .get(i)
            .filter(|_| i < self.rows)
            .and_then(|r| r.get(j))
            .copied()
            .unwrap_or(T::ZERO)
    }

    /// Set entry (i, j); dropped outside the used size.
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, v: T) {
        if i < self.rows
            && j < self.cols
            && let Some(x) = self.data.get_mut(i).and_then(|r| r.get_mut(j))
        {
            *x = v;
        }
    }

    /// Row i's used entries (empty outside the used size).
    #[inline]
    pub fn row(&self, i: usize) -> &[T] {
        self.data
            .get(i)
            .filter(|_| i < self.rows)
            .and_then(|r| r.get(..self.cols))
            .unwrap_or(&[])
    }

    /// Row i's used entries, mutable (empty outside the used size).
    #[inline]
    pub fn row_mut(&mut self, i: usize) -> &mut [T] {
        let cols = self.cols;
        if i >= self.rows {
            return &mut [];
        }
        self.data
            .get_mut(i)
            .and_then(|r| r.get_mut(..cols))
            .unwrap_or(&mut [])
    }

    /// Two distinct rows, mutable (`None` when equal or outside the used size).
    #[inline]
    pub(crate) fn two_rows_mut(&mut self, i: usize, k: usize) -> Option<(&mut [T], &mut [T])> {
        if i == k || i >= self.rows || k >= self.rows {
            return None;
        }
        let cols = self.cols;
        let (lo, hi) = if i < k { (i, k) } else { (k, i) };
        let (head, tail) = self.data.split_at_mut(hi);
        let a = head.get_mut(lo)?.get_mut(..cols)?;
        let b = tail.first_mut()?.get_mut(..cols)?;
        Some(if i < k { (a, b) } else { (b, a) })
    }

    /// Resize the used part (entries beyond the old size are whatever the storage holds: callers
    /// overwrite them); an error beyond CAP.
    pub(crate) fn resize(&mut self, rows: usize, cols: usize) -> Result<(), LinalgError> {
        if rows > CAP || cols > CAP {
            return Err(LinalgError::TooLarge {
                what: "matrix",
                size: rows.max(cols),
                capacity: CAP,
            });
        }
        self.rows = rows;
        self.cols = cols;
        Ok(())
    }

    /// Set every used entry to 0 and then the diagonal to 1 (the identity of the used size when
    /// square).
    pub(crate) fn set_identity(&mut self) {
        for (i, row) in self.data.iter_mut().take(self.rows).enumerate() {
            for (j, x) in row.iter_mut().take(self.cols).enumerate() {
                *x = if i == j { T::ONE } else { T::ZERO };
            }
        }
    }

    /// Copy `other` into this storage (same capacity).
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.rows = other.rows;
        self.cols = other.cols;
        for (dst, src) in self.data.iter_mut().zip(&other.data).take(other.rows) {
            for (d, s) in dst.iter_mut().zip(src).take(other.cols) {
                *d = *s;
            }
        }
    }

    /// Check that the matrix is square and finite (`what` names it in the error); its size.
    pub fn check_square(&self, what: &'static str) -> Result<usize, LinalgError> {
        let n = self.rows;
        if self.cols != n {
            return Err(LinalgError::Shape {
                what,
                got: self.cols,
                expected: n,
            });
        }
        if let Some((row, col)) = self.first_non_finite() {
            return Err(LinalgError::NonFinite { what, row, col });
        }
        Ok(n)
    }

    /// Whether every used entry is finite; the first that is not, otherwise.
    pub fn first_non_finite(&self) -> Option<(usize, usize)> {
        for i in 0..self.rows {
            if let Some(j) = self.row(i).iter().position(|x| !x.finite()) {
                return Some((i, j));
            }
        }
        None
    }

    /// The largest entry magnitude ([`Scalar::magnitude`]).
    pub fn max_magnitude(&self) -> f64 {
        (0..self.rows)
            .flat_map(|i| self.row(i).iter())
            .fold(0.0, |m: f64, x| m.max(x.magnitude()))
    }

    /// y = A x over the used size (x: cols entries, y: rows entries; shorter slices are
    /// truncated).
    pub fn mul_vec(&self, x: &[T], y: &mut [T]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.rows) {
            *yi = dot(self.row(i), x);
        }
    }
}

/// Σ a_k b_k over the shorter of the two.
#[inline]
pub(crate) fn dot<T: Scalar>(a: &[T], b: &[T]) -> T {
    a.iter().zip(b).fold(T::ZERO, |acc, (&x, &y)| acc + x * y)
}

/// y ← y + a·x over the shorter of the two.
#[inline]
pub(crate) fn axpy<T: Scalar>(a: T, x: &[T], y: &mut [T]) {
    for (yi, &xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

impl<const CAP: usize> RealMatrix<CAP> {
    /// The same matrix with complex entries.
    pub fn to_complex(&self) -> ComplexMatrix<CAP> {
        let mut c = Matrix {
            rows: self.rows,
            cols: self.cols,
            data: [[Complex::ZERO; CAP]; CAP],
        };
        for (dst, src) in c.data.iter_mut().zip(&self.data).take(self.rows) {
            for (d, &s) in dst.iter_mut().zip(src).take(self.cols) {
                *d = Complex::real(s);
            }
        }
        c
    }
}

impl<T: Scalar, const CAP: usize> Matrix<T, CAP> {
    /// ‖A‖₁ with [`Scalar::magnitude`] entries (the largest column sum).
    pub fn norm1(&self) -> f64 {
        (0..self.cols)
            .map(|j| {
                (0..self.rows)
                    .map(|i| self.get(i, j).magnitude())
                    .sum::<f64>()
            })
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn access_outside_the_used_size_is_inert() {
        let mut a = RealMatrix::<3>::from_fn(2, 2, |i, j| (i + 2 * j) as f64).unwrap();
        a.set(2, 0, 7.0);
        assert_eq!(a.get(2, 0), 0.0);
        assert_eq!(a.get(0, 5), 0.0);
        assert_eq!(a.row(2), &[] as &[f64]);
        assert!(RealMatrix::<3>::zeros(4, 1).is_err());
        let (r0, r1) = a.two_rows_mut(1, 0).unwrap();
        assert_eq!((r0[0], r1[0]), (1.0, 0.0));
    }
}
