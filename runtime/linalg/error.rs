//! The one error type of the linear algebra: every failure names the value and what was wrong
//! with it, so the CLI, Python and the C ABI can pass it on as it is.

use core::fmt;

/// What went wrong in a factorization, a decomposition or a solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LinalgError {
    /// A size beyond the storage's capacity (CAP).
    TooLarge {
        /// What was too large.
        what: &'static str,
        /// Its size.
        size: usize,
        /// The capacity.
        capacity: usize,
    },
    /// Operands whose sizes do not match.
    Shape {
        /// Which size.
        what: &'static str,
        /// The size given.
        got: usize,
        /// The size required.
        expected: usize,
    },
    /// A NaN or infinite entry in an input.
    NonFinite {
        /// Which input.
        what: &'static str,
        /// Row of the entry (its index for a vector).
        row: usize,
        /// Column of the entry (0 for a vector).
        col: usize,
    },
    /// A matrix singular to working precision: LU's pivot in `column` is ≤ n·ε·max|a_ij|.
    Singular {
        /// Which matrix.
        what: &'static str,
        /// The elimination step (column) whose pivot vanished.
        column: usize,
    },
    /// The mass matrix is not symmetric: |M_ij − M_ji| > 1e-12·max|M| at (row, col).
    MassNotSymmetric {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
        /// M_ij − M_ji.
        difference: f64,
    },
    /// The mass matrix is not positive definite: Cholesky's pivot `pivot` is ≤ 0 (or below
    /// n·ε·max|M|, singular to working precision).
    MassNotPositiveDefinite {
        /// The step (diagonal index) whose pivot is not positive.
        pivot: usize,
        /// That pivot's value.
        value: f64,
    },
    /// The shifted QR iteration did not converge (30·max(10, m) sweeps without deflating an
    /// eigenvalue).
    NoConvergence {
        /// How many eigenvalues had deflated.
        converged: usize,
        /// The matrix's size.
        size: usize,
    },
    /// K − η²M + iη(C + ηG) is singular: the forcing frequency η is a natural frequency of an
    /// undamped mode (resonance), and the harmonic steady response does not exist.
    Resonance {
        /// The speed ratio η of the forcing.
        speed_ratio: f64,
    },
    /// A constant force with a singular stiffness K (a free rigid-body mode): the static
    /// deflection does not exist.
    StaticSingular {
        /// The elimination step whose pivot vanished.
        column: usize,
    },
}

impl fmt::Display for LinalgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            LinalgError::TooLarge {
                what,
                size,
                capacity,
            } => write!(f, "{what}: size {size} exceeds the capacity {capacity}"),
            LinalgError::Shape {
                what,
                got,
                expected,
            } => write!(f, "{what}: got size {got}, expected {expected}"),
            LinalgError::NonFinite { what, row, col } => {
                write!(f, "{what}: entry ({row}, {col}) is not finite")
            }
            LinalgError::Singular { what, column } => write!(
                f,
                "{what} is singular to working precision (pivot {column} vanishes)"
            ),
            LinalgError::MassNotSymmetric {
                row,
                col,
                difference,
            } => write!(
                f,
                "mass matrix is not symmetric: M[{row}][{col}] − M[{col}][{row}] = {difference:e}"
            ),
            LinalgError::MassNotPositiveDefinite { pivot, value } => write!(
                f,
                "mass matrix is not positive definite (Cholesky pivot {pivot} is {value:e})"
            ),
            LinalgError::NoConvergence { converged, size } => write!(
                f,
                "eigenvalues: the QR iteration did not converge ({converged} of {size} found)"
            ),
            LinalgError::Resonance { speed_ratio } => write!(
                f,
                "no harmonic steady response at speed ratio η = {speed_ratio}: \
                 K − η²M + iη(C + ηG) is singular (resonance of an undamped mode)"
            ),
            LinalgError::StaticSingular { column } => write!(
                f,
                "no static deflection under a constant force: the stiffness matrix is singular \
                 (a free rigid-body mode; pivot {column} vanishes)"
            ),
        }
    }
}

impl core::error::Error for LinalgError {}
