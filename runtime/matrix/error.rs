//! What can be wrong with a rotor from matrices: every error names the value and what is valid.

use core::fmt;

use crate::linalg::LinalgError;
use crate::params::{Number, Range};

/// A rotor from matrices that cannot be built or run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MatrixError {
    /// The matrices themselves ([`LinalgError`]: shapes, non-finite entries, M not symmetric
    /// positive definite, a failed decomposition, a resonance of an undamped mode).
    Linalg(LinalgError),
    /// More degrees of freedom than the storage holds.
    TooLarge {
        /// n.
        dofs: usize,
        /// The most degrees of freedom this build holds (CAP/2).
        capacity: usize,
    },
    /// A vector of the wrong length.
    Shape {
        /// Which vector.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The length required.
        expected: usize,
    },
    /// A degree-of-freedom index beyond the model's.
    Dof {
        /// Which index (the rub station's rotor x, an unbalance's y, …).
        what: &'static str,
        /// The index given.
        index: usize,
        /// The model's number of degrees of freedom n (valid indices 0 … n − 1).
        dofs: usize,
    },
    /// The rub station's rotor and stator points share a degree of freedom, or its x and y are
    /// the same.
    StationOverlap {
        /// The degree of freedom used twice.
        index: usize,
    },
    /// A NaN or infinite value.
    NonFinite {
        /// Which value.
        what: &'static str,
        /// Its index (0 for a scalar).
        index: usize,
        /// The value.
        value: f64,
    },
    /// A method option a rotor from matrices does not take (the analytic method's closed-form
    /// contact schemes are the planar model's only).
    MethodOption {
        /// The method.
        method: &'static str,
        /// The option.
        option: &'static str,
    },
    /// A scalar outside its valid range.
    OutOfRange {
        /// Which value.
        what: &'static str,
        /// The value.
        value: f64,
        /// Its valid range.
        valid: Range,
    },
}

impl From<LinalgError> for MatrixError {
    fn from(e: LinalgError) -> Self {
        MatrixError::Linalg(e)
    }
}

impl fmt::Display for MatrixError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            MatrixError::Linalg(e) => write!(f, "{e}"),
            MatrixError::TooLarge { dofs, capacity } => write!(
                f,
                "the model has {dofs} degrees of freedom; this build holds at most {capacity}"
            ),
            MatrixError::Shape {
                what,
                got,
                expected,
            } => write!(f, "{what} has {got} entries; it must have {expected}"),
            MatrixError::Dof { what, index, dofs } => write!(
                f,
                "{what} = {index} is not a degree of freedom of the model: it must be in [0, {}]",
                dofs.saturating_sub(1)
            ),
            MatrixError::StationOverlap { index } => write!(
                f,
                "the rub station uses degree of freedom {index} twice: its rotor x, rotor y, stator x and stator y must be four different degrees of freedom"
            ),
            MatrixError::NonFinite { what, index, value } => {
                write!(f, "{what} [{index}] = {value} is not a finite number")
            }
            MatrixError::MethodOption { method, option } => write!(
                f,
                "{option} is not available for a rotor from matrices: the {method} method's linearized closed forms are the paper's planar model's only; a rotor from matrices takes its contact as a Taylor segment at the method's tolerance (omit the option)"
            ),
            MatrixError::OutOfRange { what, value, valid } => write!(
                f,
                "{what} = {} is out of range: it must be in {valid}",
                Number(value)
            ),
        }
    }
}

impl core::error::Error for MatrixError {}
