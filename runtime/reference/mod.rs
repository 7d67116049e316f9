//! Numerical reference integrators (owned by the reference-integrator work; see issue 4).

/// Default `tol` (relative and absolute) of the reference integrators.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
