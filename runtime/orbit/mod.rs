//! Periodic orbits and their stability (`docs/MODEL.md` §18): a period-k orbit is a fixed point of
//! the stroboscopic map P^k (k forcing periods from the section τ = 0 mod 2π/η); it is found by
//! Newton's method on P^k(s) − s (shooting) with the monodromy matrix ∂P^k/∂s from the segments,
//! and its Floquet multipliers are the monodromy's eigenvalues.
//!
//! - [`stroboscopic_map`] (`map.rs`): P^k by any propagation method, with the monodromy matrix:
//!   closed-form transition matrices in free flight, the variational equations (generated
//!   Jacobians, DOP853) in contact (`segments.rs`, `variational.rs`), saltation matrices at the
//!   switches (`saltation.rs`); and the orbit's extrema of z and |q| (`extrema.rs`).
//! - [`shoot`] (`shooting.rs`): Newton's method on P^k(s) − s from a guess, with the residual of
//!   each iteration (quadratic convergence).
//! - [`PeriodicOrbit`] (`floquet.rs`): the orbit, its multipliers, stability, minimal period.
//!
//! `no_std`, no heap: a map's section states and a shot's residuals live in fixed arrays
//! ([`MAX_PERIOD`], [`MAX_ITERATIONS`]). Continuation along a parameter, which stores a branch,
//! is the CLI library's (`rotor_rub_cli::orbit`).
//!
//! ```
//! use rotor_rub::orbit::{ShootingSettings, shoot};
//! use rotor_rub::{Preset, State};
//!
//! // The paper rotor's full annular rub at η = 2.2 (period 1), from a guess near it.
//! let mut params = Preset::Paper.problem().params;
//! params.speed_ratio = 2.2;
//! let guess = State::new(-1.5, 2.4, -5.0, -3.0);
//! let shot = shoot(&params, guess, 1, &ShootingSettings::default())?;
//! let orbit = shot.orbit;
//! assert!(orbit.residual < 1e-10);
//! println!("multipliers {:?}, stable: {}", orbit.multipliers, orbit.stable());
//! # Ok::<(), rotor_rub::orbit::OrbitError>(())
//! ```

mod extrema;
mod floquet;
mod map;
mod matrix;
mod saltation;
mod segments;
mod shooting;
mod variational;

use core::fmt;

pub use extrema::{Extremum, Summary};
pub use floquet::PeriodicOrbit;
pub use map::{
    DEFAULT_METHOD, DEFAULT_TRAJECTORY_TOL, DEFAULT_VARIATIONAL_TOL, MapObserver, MapPoint,
    MapSettings, stroboscopic_map,
};
pub use matrix::{IDENTITY, Mat4, apply, eigenvalues_of, mul, solve};
pub use saltation::{continuous, saltation};
pub use shooting::{
    DEFAULT_TOLERANCE, MAX_ITERATIONS, ShootingSettings, Shot, TOLERANCE_RANGE, newton_step, shoot,
    shoot_observed,
};
pub use variational::{AUGMENTED, Augmented, jacobian};

use crate::linalg::LinalgError;
use crate::propagate::{EventKind, PropagationError};

/// The longest orbit handled, in forcing periods (the response classes' longest period too).
pub const MAX_PERIOD: usize = 32;

/// Why an orbit was not found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OrbitError {
    /// The propagation failed (invalid parameters or options, divergence, …).
    Propagation(PropagationError),
    /// A period k outside 1 ..= [`MAX_PERIOD`].
    InvalidPeriod {
        /// The k asked for.
        periods: u32,
    },
    /// A shooting option outside its range.
    InvalidSetting {
        /// Its name.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Its valid range.
        valid: crate::params::ValidRange,
    },
    /// A switch tangential to the field before it (∇h·f⁻ = 0): its saltation matrix does not
    /// exist.
    Tangential {
        /// When.
        time: f64,
        /// Which switch.
        kind: EventKind,
    },
    /// The Newton matrix M − I (or the monodromy's eigenvalues) could not be computed.
    Linalg(LinalgError),
    /// Newton's method did not reach the tolerance.
    NotConverged {
        /// Iterations made.
        iterations: u32,
        /// The last residual |P^k(s) − s|∞.
        residual: f64,
    },
}

impl fmt::Display for OrbitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            OrbitError::Propagation(e) => write!(f, "{e}"),
            OrbitError::InvalidPeriod { periods } => write!(
                f,
                "period = {periods} is out of range: it must be an integer in [1, {MAX_PERIOD}] (forcing periods)"
            ),
            OrbitError::InvalidSetting { what, value, valid } => write!(
                f,
                "{what} = {value:e} is out of range for shooting: it must be in {valid}"
            ),
            OrbitError::Tangential { time, kind } => write!(
                f,
                "the {} switch at time {time:e} is tangential to the field: the orbit's monodromy matrix does not exist there",
                kind.name()
            ),
            OrbitError::Linalg(e) => write!(f, "{e}"),
            OrbitError::NotConverged {
                iterations,
                residual,
            } => write!(
                f,
                "Newton's method did not converge to a periodic orbit in {iterations} iterations (last residual {residual:e}): start nearer to the orbit, or it does not exist here"
            ),
        }
    }
}

impl core::error::Error for OrbitError {}

impl From<PropagationError> for OrbitError {
    fn from(e: PropagationError) -> Self {
        OrbitError::Propagation(e)
    }
}

impl From<LinalgError> for OrbitError {
    fn from(e: LinalgError) -> Self {
        OrbitError::Linalg(e)
    }
}
