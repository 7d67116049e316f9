//! Physical parameters, initial states, presets and their validation.
//!
//! All quantities are dimensionless as in the paper: lengths in units of the radial clearance,
//! time τ = ω_n t, stiffnesses relative to the rotor stiffness. Every parameter is stated once in
//! the table (`table.rs`: name, symbol, default, valid range, meaning); `validate` checks a
//! problem against it, `presets` names sets of values.

mod presets;
mod table;
mod validate;

pub use presets::Preset;
pub use table::{Info, Parameter, Params};
pub use validate::{Number, ParamError, Range, ValidRange};

/// A state `(x, y, x', y')` of the rotor centre, in clearance units and dimensionless time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct State {
    /// Horizontal displacement x̂.
    pub x: f64,
    /// Vertical displacement ŷ.
    pub y: f64,
    /// Horizontal velocity x̂'.
    pub vx: f64,
    /// Vertical velocity ŷ'.
    pub vy: f64,
}

impl State {
    /// A state from its four components.
    pub const fn new(x: f64, y: f64, vx: f64, vy: f64) -> Self {
        Self { x, y, vx, vy }
    }

    /// The components as an array `[x, y, vx, vy]`.
    pub const fn to_array(self) -> [f64; 4] {
        [self.x, self.y, self.vx, self.vy]
    }

    /// A state from an array `[x, y, vx, vy]`.
    pub const fn from_array(a: [f64; 4]) -> Self {
        Self {
            x: a[0],
            y: a[1],
            vx: a[2],
            vy: a[3],
        }
    }

    /// Whether every component is finite.
    pub fn is_finite(&self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.vx.is_finite() && self.vy.is_finite()
    }
}

/// A parameter set with its initial condition: everything a propagation starts from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Problem {
    /// The model parameters.
    pub params: Params,
    /// The state at `start_time`.
    pub initial: State,
    /// τ0, the time of `initial` (0 unless given).
    pub start_time: f64,
}

impl Problem {
    /// The table's defaults (the `paper` preset).
    pub const DEFAULT: Problem = Problem {
        params: Params::DEFAULT,
        initial: State::new(
            Parameter::X0.info().default,
            Parameter::Y0.info().default,
            Parameter::Vx0.info().default,
            Parameter::Vy0.info().default,
        ),
        start_time: Parameter::StartTime.info().default,
    };
}

impl Params {
    /// The forcing period 2π/η.
    pub fn forcing_period(&self) -> f64 {
        core::f64::consts::TAU / self.speed_ratio
    }
}
