//! Propagation while the running speed changes (`docs/MODEL.md` §14): run-ups, coast-downs and
//! any piecewise-linear speed profile ([`crate::speed`]). [`VariableSpeedPropagator`] runs a
//! method on a profile behind [`crate::Propagate`]; [`SpeedProfileStepper`] is the fixed-step
//! stepper on one; [`RampField`] is the equations of motion on one piece of it.
//! [`Revolutions`] reduces a run to one row per forcing period (largest and smallest radius,
//! contact, whirl, switches) and [`find_jumps`] finds where the response jumps.

mod field;
mod jumps;
mod options;
mod period;
mod propagator;
mod revolutions;
mod segment;
mod stepper;

pub use field::{RampField, RampSystem};
pub use jumps::{Jump, JumpSearch, Jumps, MAX_JUMPS, find_jumps};
pub use options::{
    DEFAULT_SPEED_HOLDS, SPEED_HOLDS_RANGE, VariableSpeedError, VariableSpeedOptions,
};
pub use period::{Revolution, SpeedDirection, WHIRL_THRESHOLD, WhirlDirection};
pub use propagator::VariableSpeedPropagator;
pub use revolutions::Revolutions;
pub use stepper::SpeedProfileStepper;
