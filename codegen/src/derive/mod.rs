//! Derivation steps: differentiation and linear solves on the expression graph.

pub mod diff;
pub mod linsolve;

pub use diff::{derivative, nth_derivative, partial};
pub use linsolve::{SolveError, determinant, solve_linear};
