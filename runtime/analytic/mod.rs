//! The piecewise-analytical method: exact free flight and re-linearized closed-form contact.

/// Default accuracy target of the analytic method's adaptive contact scheme (exprb43).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;
