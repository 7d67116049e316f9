//! 4 × 4 matrices of the state (x, y, x', y') as plain arrays, row-major (`m[i][j]`: component i
//! of the image of a unit component j): the state-transition, saltation and monodromy matrices.
//! Products and solves loop by iterator, so nothing indexes out of bounds.

use crate::linalg::{Complex, LinalgError, Lu, RealMatrix, eigenvalues};

/// A 4 × 4 matrix on the state (x, y, x', y'), row-major.
pub type Mat4 = [[f64; 4]; 4];

/// The identity.
pub const IDENTITY: Mat4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// a·b.
#[inline]
pub fn mul(a: &Mat4, b: &Mat4) -> Mat4 {
    a.map(|row| combine(row, b))
}

/// Σ_r c_r · (row r of `m`): a row vector times `m`.
#[inline]
pub fn combine(c: [f64; 4], m: &Mat4) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (cr, row) in c.iter().zip(m) {
        for (o, v) in out.iter_mut().zip(row) {
            *o += cr * v;
        }
    }
    out
}

/// m·v.
#[inline]
pub fn apply(m: &Mat4, v: [f64; 4]) -> [f64; 4] {
    m.map(|row| dot(row, v))
}

/// a·b of two 4-vectors.
#[inline]
pub fn dot(a: [f64; 4], b: [f64; 4]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `m` as the linear algebra's matrix.
fn to_linalg(m: &Mat4) -> Result<RealMatrix<4>, LinalgError> {
    let mut out = RealMatrix::<4>::zeros(4, 4)?;
    for (i, row) in m.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            out.set(i, j, *v);
        }
    }
    Ok(out)
}

/// The eigenvalues of `m`, sorted by modulus, largest first (the linear algebra's
/// [`eigenvalues`]: balancing, Hessenberg reduction, shifted QR).
///
/// # Errors
/// A non-finite entry, or a QR iteration that does not converge.
pub fn eigenvalues_of(m: &Mat4) -> Result<[Complex; 4], LinalgError> {
    let a = to_linalg(m)?;
    let mut out = [Complex::ZERO; 4];
    eigenvalues(&a, &mut out)?;
    Ok(out)
}

/// x solving a·x = b (LU with partial pivoting).
///
/// # Errors
/// [`LinalgError::Singular`] when `a` is singular to working precision (named `what`).
pub fn solve(a: &Mat4, b: [f64; 4], what: &'static str) -> Result<[f64; 4], LinalgError> {
    let lu = Lu::factor(&to_linalg(a)?, what)?;
    let mut x = b;
    lu.solve(&mut x);
    Ok(x)
}
