//! The piecewise-analytical method: exact free flight and re-linearized closed-form contact.
//!
//! Module map: [`basis`] (scalar functions EC/ES and the matrix-function coefficients),
//! [`segment`] (what a closed-form piece offers), [`free`] (free-flight segment), [`free_flight`] (free flight searched for the next contact), [`linear`]
//! (linearized contact segment), [`schemes`] (exprb2, exprb43), [`switch`] (switch location),
//! [`propagator`] (the state machine).

pub mod basis;
pub mod forced;
pub mod free;
pub mod free_flight;
pub mod linear;
pub mod propagator;
pub mod schemes;
pub mod segment;
pub mod series;
pub mod switch;

pub use propagator::{AnalyticPropagator, DEFAULT_EXPRB2_STEP};

/// Default accuracy target of the analytic method's adaptive contact scheme (exprb43).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;
