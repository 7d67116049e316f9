//! A rotor's second-order matrices and its first-order matrix: M q'' + (C + ηG) q' + K q = f
//! becomes y' = A y + (0, M⁻¹f) with y = (q, q') and
//! A = [[0, I], [−M⁻¹K, −M⁻¹(C + ηG)]], M⁻¹ applied by an LU solve (never an explicit inverse).
//!
//! M must be symmetric (to 1e-12 relative: finite-element matrices are symmetric to rounding)
//! and positive definite (checked by a Cholesky factorization, whose failing pivot the error
//! names); C, G and K may be any real matrices (bearings make C and K non-symmetric; G is
//! gyroscopic, skew, scaled by the speed ratio η).

use super::dense::RealMatrix;
use super::error::LinalgError;
use super::lu::Lu;
use crate::math;

/// Relative asymmetry of M accepted as rounding.
const SYMMETRY_TOLERANCE: f64 = 1e-12;

/// The second-order matrices of a linear rotor, each n × n (borrowed: the caller owns them).
#[derive(Clone, Copy, Debug)]
pub struct SecondOrder<'a, const CAP: usize> {
    /// M, symmetric positive definite.
    pub mass: &'a RealMatrix<CAP>,
    /// C, any real.
    pub damping: &'a RealMatrix<CAP>,
    /// G, gyroscopic (skew for a rotor), multiplied by the speed ratio η.
    pub gyroscopic: &'a RealMatrix<CAP>,
    /// K, any real.
    pub stiffness: &'a RealMatrix<CAP>,
}

impl<const CAP: usize> SecondOrder<'_, CAP> {
    /// The number of degrees of freedom n, after checking that all four are finite n × n
    /// matrices and M symmetric positive definite.
    pub fn check(&self) -> Result<usize, LinalgError> {
        let n = self.mass.rows();
        for (what, a) in [
            ("mass matrix", self.mass),
            ("damping matrix", self.damping),
            ("gyroscopic matrix", self.gyroscopic),
            ("stiffness matrix", self.stiffness),
        ] {
            for got in [a.rows(), a.cols()] {
                if got != n {
                    return Err(LinalgError::Shape {
                        what,
                        got,
                        expected: n,
                    });
                }
            }
            if let Some((row, col)) = a.first_non_finite() {
                return Err(LinalgError::NonFinite { what, row, col });
            }
        }
        check_mass(self.mass)?;
        Ok(n)
    }

    /// The first-order matrix A (2n × 2n) at speed ratio η.
    ///
    /// ```
    /// use rotor_rub::linalg::{RealMatrix, SecondOrder};
    /// let i = RealMatrix::<4>::identity(1).unwrap();
    /// let c = RealMatrix::<4>::from_rows(&[&[0.5]]).unwrap();
    /// let g = RealMatrix::<4>::zeros(1, 1).unwrap();
    /// let rotor = SecondOrder { mass: &i, damping: &c, gyroscopic: &g, stiffness: &i };
    /// let a = rotor.first_order(1.0).unwrap();
    /// assert_eq!((a.get(0, 1), a.get(1, 0), a.get(1, 1)), (1.0, -1.0, -0.5));
    /// ```
    pub fn first_order(&self, speed_ratio: f64) -> Result<RealMatrix<CAP>, LinalgError> {
        let n = self.check()?;
        if !speed_ratio.is_finite() {
            return Err(LinalgError::NonFinite {
                what: "speed ratio",
                row: 0,
                col: 0,
            });
        }
        let lu = Lu::factor(self.mass, "mass matrix")?;
        let mut a = RealMatrix::zeros(2 * n, 2 * n)?;
        // M⁻¹K and M⁻¹(C + ηG), each solved column by column.
        let mut rhs = [0.0; CAP];
        for j in 0..n {
            for (pass, col0) in [(0, 0), (1, n)] {
                for (i, r) in rhs.iter_mut().enumerate().take(n) {
                    *r = if pass == 0 {
                        self.stiffness.get(i, j)
                    } else {
                        self.damping.get(i, j) + speed_ratio * self.gyroscopic.get(i, j)
                    };
                }
                lu.solve(&mut rhs);
                for (i, &r) in rhs.iter().enumerate().take(n) {
                    a.set(n + i, col0 + j, -r);
                }
            }
            a.set(j, n + j, 1.0);
        }
        Ok(a)
    }
}

/// M symmetric to [`SYMMETRY_TOLERANCE`] and positive definite (Cholesky on its lower
/// triangle; a pivot ≤ n·ε·max|M| counts as not positive).
fn check_mass<const CAP: usize>(m: &RealMatrix<CAP>) -> Result<(), LinalgError> {
    let n = m.rows();
    let scale = m.max_magnitude();
    for i in 0..n {
        for j in 0..i {
            let difference = m.get(i, j) - m.get(j, i);
            if math::abs(difference) > SYMMETRY_TOLERANCE * scale {
                return Err(LinalgError::MassNotSymmetric {
                    row: i,
                    col: j,
                    difference,
                });
            }
        }
    }
    let tiny = n as f64 * f64::EPSILON * scale;
    let mut l = RealMatrix::<CAP>::zeros(n, n)?;
    for j in 0..n {
        let d = m.get(j, j) - (0..j).map(|k| l.get(j, k) * l.get(j, k)).sum::<f64>();
        if d.is_nan() || d <= tiny {
            return Err(LinalgError::MassNotPositiveDefinite { pivot: j, value: d });
        }
        let d = math::sqrt(d);
        l.set(j, j, d);
        for i in j + 1..n {
            let s = m.get(i, j) - (0..j).map(|k| l.get(i, k) * l.get(j, k)).sum::<f64>();
            l.set(i, j, s / d);
        }
    }
    Ok(())
}
