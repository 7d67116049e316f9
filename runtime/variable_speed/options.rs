//! The settings of a run on a speed profile and why one cannot start.

use core::fmt;

use crate::method::{Options, ValidRange};
use crate::params::{Number, Range};
use crate::propagate::PropagationError;
use crate::stepper::StepperError;

/// Held steps per forcing period of the analytic method by default (measured against DOP853
/// at tol 1e-13: `docs/MODEL.md` §14).
pub const DEFAULT_SPEED_HOLDS: u32 = 32;

/// Valid held steps per forcing period: at 1 the speed is held over a whole turn; beyond 4096
/// the steps are shorter than the contact sub-steps and only cost time.
pub const SPEED_HOLDS_RANGE: ValidRange = ValidRange {
    min: 1.0,
    max: 4096.0,
};

/// How to propagate on a speed profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VariableSpeedOptions {
    /// The method and its accuracy settings.
    pub options: Options,
    /// Held steps per forcing period of the analytic method where the speed changes (see the
    /// module documentation); the other methods do not hold the speed.
    pub speed_holds: u32,
}

impl VariableSpeedOptions {
    /// `options` with the default number of held steps.
    pub fn new(options: Options) -> Self {
        VariableSpeedOptions {
            options,
            speed_holds: DEFAULT_SPEED_HOLDS,
        }
    }
}

/// Why a run on a speed profile cannot start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VariableSpeedError {
    /// The problem or the options are invalid (their own error says which value).
    Invalid(PropagationError),
    /// The fixed-step stepper refused its problem or configuration.
    Stepper(StepperError),
    /// Friction with a changing speed: the rolling condition and the slip velocity of the
    /// friction piece assume a constant spin (`docs/MODEL.md` §14).
    Friction {
        /// μ.
        friction_coefficient: f64,
    },
    /// The run starts at the problem's start time, which must be the profile's first time.
    StartTime {
        /// The problem's τ0.
        start_time: f64,
        /// The profile's first time.
        profile_start: f64,
    },
    /// Holding the speed over a step carries the speed-change force in the unbalance (the
    /// analytic method): at this speed and rate the scaled eccentricity ratio leaves the
    /// table's range.
    HeldUnbalance {
        /// The lowest speed ratio of the piece.
        speed_ratio: f64,
        /// Its rate dη/dτ.
        rate: f64,
        /// The eccentricity ratio a held step would need.
        eccentricity_ratio: f64,
        /// The table's range of the eccentricity ratio.
        range: Range,
    },
}

impl fmt::Display for VariableSpeedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            VariableSpeedError::Invalid(e) => write!(f, "{e}"),
            VariableSpeedError::Stepper(e) => write!(f, "{e}"),
            VariableSpeedError::Friction {
                friction_coefficient,
            } => write!(
                f,
                "friction_coefficient = {} with a changing speed is not supported (the friction model assumes a constant spin): use friction_coefficient = 0",
                Number(friction_coefficient)
            ),
            VariableSpeedError::StartTime {
                start_time,
                profile_start,
            } => write!(
                f,
                "the run starts at τ0 = {} but the speed profile starts at τ = {}: they must be equal",
                Number(start_time),
                Number(profile_start)
            ),
            VariableSpeedError::HeldUnbalance {
                speed_ratio,
                rate,
                eccentricity_ratio,
                range,
            } => write!(
                f,
                "the analytic method holds the speed over steps and carries the speed-change force in the unbalance: at speed_ratio = {} and dη/dτ = {} that needs eccentricity_ratio = {}, outside {range}; use a slower rate, a higher speed, or --method dop853 or hybrid",
                Number(speed_ratio),
                Number(rate),
                Number(eccentricity_ratio)
            ),
        }
    }
}

impl core::error::Error for VariableSpeedError {}

impl From<PropagationError> for VariableSpeedError {
    fn from(e: PropagationError) -> Self {
        VariableSpeedError::Invalid(e)
    }
}
