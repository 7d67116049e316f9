//! A running speed that changes in time (`docs/MODEL.md` §14): the speed ratio η(τ) as a
//! piecewise-linear profile ([`SpeedProfile`], from points or from a [`Ramp`]), the forcing
//! phase θ = ∫η of each linear piece ([`SpeedPiece`]), and the speed held constant over a step
//! for the closed-form methods ([`HeldSpeed`]), and named run-up programs ([`RunupPreset`]).
//! Propagation on a profile is in [`crate::variable_speed`].
//!
//! ```
//! use rotor_rub::speed::{Ramp, RampPace};
//!
//! // From η = 0.5 up to 2 at dη/dτ = 1e-3 and back down, after 20 periods at 0.5.
//! let ramp = Ramp {
//!     start_time: 0.0,
//!     from: 0.5,
//!     to: 2.0,
//!     pace: RampPace::Rate(1e-3),
//!     settle_periods: 20.0,
//!     dwell_periods: 0.0,
//!     one_way: false,
//! };
//! let points = ramp.points()?;
//! let profile = points.profile()?;
//! assert_eq!(profile.points().len(), 4);
//! assert!((profile.end() - (20.0 * core::f64::consts::TAU / 0.5 + 3000.0)).abs() < 1e-9);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

mod hold;
mod piece;
mod presets;
mod profile;
mod ramp;

pub use hold::HeldSpeed;
pub use piece::SpeedPiece;
pub use presets::RunupPreset;
pub use profile::{
    MAX_SPEED_RATE, Quantity, RAMP_RATE_RANGE, SpeedPoint, SpeedProfile, SpeedProfileError,
    speed_range, time_range,
};
pub use ramp::{HOLD_RANGE, MAX_RAMP_POINTS, PERIODS_RANGE, Ramp, RampError, RampPace, RampPoints};
