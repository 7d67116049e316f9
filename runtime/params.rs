//! Physical parameters, initial states, presets and their validation.
//!
//! All quantities are dimensionless as in the paper: lengths in units of the radial clearance,
//! time τ = ω_n t, stiffnesses relative to the rotor stiffness. The symbol table lives in
//! `ARCHITECTURE.md`; in short `speed_ratio` = η, `damping_ratio` = ν (ζ in the paper's Table 1),
//! `mass_ratio` = η_m, `eccentricity_ratio` = ρ̂, `phase` = φ0, `k_**` = K̂_**, `offset_*` = ε̂_*.

use core::fmt;

/// Largest magnitude accepted for any parameter or state value. Beyond it the model leaves its
/// physical domain and `f64` intermediate terms (η⁴, K²) could overflow.
pub const MAX_MAGNITUDE: f64 = 1.0e6;

/// Parameters of the rotor–stator model (`model.md` §1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// η: running speed over the rotor's natural frequency. Must be > 0.
    pub speed_ratio: f64,
    /// ν: viscous damping ratio of the rotor. Must be ≥ 0 (ν ≥ 1 is over-damped and allowed).
    pub damping_ratio: f64,
    /// η_m: unbalance mass over disk mass. Must be > 0.
    pub mass_ratio: f64,
    /// ρ̂: unbalance eccentricity over the clearance. Must be > 0.
    pub eccentricity_ratio: f64,
    /// φ0: phase of the unbalance at τ = 0, in radians.
    pub phase: f64,
    /// K̂xx: stator support stiffness, x force per x displacement. Must be ≥ 0.
    pub k_xx: f64,
    /// K̂xy: stator support stiffness, x force per y displacement (cross-coupling, any sign).
    pub k_xy: f64,
    /// K̂yx: stator support stiffness, y force per x displacement (cross-coupling, any sign).
    pub k_yx: f64,
    /// K̂yy: stator support stiffness, y force per y displacement. Must be ≥ 0.
    pub k_yy: f64,
    /// ε̂x: static offset of the stator centre from the rotor's rest position, x.
    pub offset_x: f64,
    /// ε̂y: static offset of the stator centre from the rotor's rest position, y.
    pub offset_y: f64,
}

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

/// The named presets (`model.md` §9).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// The Fig. 2 caption's stiffnesses (K̂xx = K̂xy = K̂yx = 20, K̂yy = 40) with the offset
    /// ε̂ = (0.3, −0.2) that the paper's Table 1 leaves blank: our reading, which shows the mix of
    /// periodic, quasi-periodic and chaotic responses the paper reports.
    Paper,
    /// The text's stiffnesses (K̂xx = K̂xy = K̂yx = 2, K̂yy = 40) with ε̂ = (0, 0), as printed.
    /// Every η ≥ 1.5 of Fig. 2 ends on the non-contact synchronous orbit.
    PaperText,
}

impl Preset {
    /// Every preset, in the order `presets` lists them.
    pub const ALL: [Preset; 2] = [Preset::Paper, Preset::PaperText];

    /// The preset's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Preset::Paper => "paper",
            Preset::PaperText => "paper-text",
        }
    }

    /// One line saying where the preset comes from.
    pub const fn description(self) -> &'static str {
        match self {
            Preset::Paper => {
                "Fig. 2 caption: Kxx = Kxy = Kyx = 20, Kyy = 40, offset (0.3, -0.2) (our reading of the blank Table 1 offsets)"
            }
            Preset::PaperText => {
                "paper text: Kxx = Kxy = Kyx = 2, Kyy = 40, offset (0, 0) as printed"
            }
        }
    }

    /// The preset with the given name, if any.
    pub fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The preset's problem: parameters, initial state (0.1, 0.1, 0, 0) at τ0 = 0, η = 1.5.
    pub const fn problem(self) -> Problem {
        let (k_cross, offset_x, offset_y) = match self {
            Preset::Paper => (20.0, 0.3, -0.2),
            Preset::PaperText => (2.0, 0.0, 0.0),
        };
        Problem {
            params: Params {
                speed_ratio: 1.5,
                damping_ratio: 0.125,
                mass_ratio: 0.005,
                eccentricity_ratio: 70.0,
                phase: 0.0,
                k_xx: k_cross,
                k_xy: k_cross,
                k_yx: k_cross,
                k_yy: 40.0,
                offset_x,
                offset_y,
            },
            initial: State::new(0.1, 0.1, 0.0, 0.0),
            start_time: 0.0,
        }
    }
}

/// Which parameter or state value a [`ParamError`] is about. The names are the public field names
/// (and the CLI's `--set` names).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `speed_ratio`
    SpeedRatio,
    /// `damping_ratio`
    DampingRatio,
    /// `mass_ratio`
    MassRatio,
    /// `eccentricity_ratio`
    EccentricityRatio,
    /// `phase`
    Phase,
    /// `k_xx`
    KXx,
    /// `k_xy`
    KXy,
    /// `k_yx`
    KYx,
    /// `k_yy`
    KYy,
    /// `offset_x`
    OffsetX,
    /// `offset_y`
    OffsetY,
    /// `x0 (initial x)`
    X0,
    /// `y0 (initial y)`
    Y0,
    /// `vx0 (initial x')`
    Vx0,
    /// `vy0 (initial y')`
    Vy0,
    /// `start_time (τ0)`
    StartTime,
}

impl Field {
    /// Every field, in the order of the documentation.
    pub const ALL: [Field; 16] = [
        Field::SpeedRatio,
        Field::DampingRatio,
        Field::MassRatio,
        Field::EccentricityRatio,
        Field::Phase,
        Field::KXx,
        Field::KXy,
        Field::KYx,
        Field::KYy,
        Field::OffsetX,
        Field::OffsetY,
        Field::X0,
        Field::Y0,
        Field::Vx0,
        Field::Vy0,
        Field::StartTime,
    ];

    /// The field's public name, e.g. `speed_ratio`.
    pub const fn name(self) -> &'static str {
        match self {
            Field::SpeedRatio => "speed_ratio",
            Field::DampingRatio => "damping_ratio",
            Field::MassRatio => "mass_ratio",
            Field::EccentricityRatio => "eccentricity_ratio",
            Field::Phase => "phase",
            Field::KXx => "k_xx",
            Field::KXy => "k_xy",
            Field::KYx => "k_yx",
            Field::KYy => "k_yy",
            Field::OffsetX => "offset_x",
            Field::OffsetY => "offset_y",
            Field::X0 => "x0",
            Field::Y0 => "y0",
            Field::Vx0 => "vx0",
            Field::Vy0 => "vy0",
            Field::StartTime => "start_time",
        }
    }

    /// The field with the given public name.
    pub fn from_name(name: &str) -> Option<Field> {
        Field::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The field's value in a problem.
    pub fn get(self, p: &Problem) -> f64 {
        let q = &p.params;
        match self {
            Field::SpeedRatio => q.speed_ratio,
            Field::DampingRatio => q.damping_ratio,
            Field::MassRatio => q.mass_ratio,
            Field::EccentricityRatio => q.eccentricity_ratio,
            Field::Phase => q.phase,
            Field::KXx => q.k_xx,
            Field::KXy => q.k_xy,
            Field::KYx => q.k_yx,
            Field::KYy => q.k_yy,
            Field::OffsetX => q.offset_x,
            Field::OffsetY => q.offset_y,
            Field::X0 => p.initial.x,
            Field::Y0 => p.initial.y,
            Field::Vx0 => p.initial.vx,
            Field::Vy0 => p.initial.vy,
            Field::StartTime => p.start_time,
        }
    }

    /// Set the field's value in a problem (not validated: call [`Problem::validate`]).
    pub fn set(self, p: &mut Problem, value: f64) {
        let q = &mut p.params;
        let slot = match self {
            Field::SpeedRatio => &mut q.speed_ratio,
            Field::DampingRatio => &mut q.damping_ratio,
            Field::MassRatio => &mut q.mass_ratio,
            Field::EccentricityRatio => &mut q.eccentricity_ratio,
            Field::Phase => &mut q.phase,
            Field::KXx => &mut q.k_xx,
            Field::KXy => &mut q.k_xy,
            Field::KYx => &mut q.k_yx,
            Field::KYy => &mut q.k_yy,
            Field::OffsetX => &mut q.offset_x,
            Field::OffsetY => &mut q.offset_y,
            Field::X0 => &mut p.initial.x,
            Field::Y0 => &mut p.initial.y,
            Field::Vx0 => &mut p.initial.vx,
            Field::Vy0 => &mut p.initial.vy,
            Field::StartTime => &mut p.start_time,
        };
        *slot = value;
    }

    /// The rule the field must satisfy, as said in error messages and `--help`.
    pub const fn rule(self) -> &'static str {
        match self {
            Field::SpeedRatio | Field::MassRatio | Field::EccentricityRatio => "must be > 0",
            Field::DampingRatio | Field::KXx | Field::KYy => "must be >= 0",
            _ => "may be any finite value",
        }
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a parameter set or initial state was rejected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamError {
    /// The value is NaN or infinite.
    NonFinite {
        /// The offending field.
        field: Field,
        /// Its value.
        value: f64,
    },
    /// The value must be strictly positive.
    NotPositive {
        /// The offending field.
        field: Field,
        /// Its value.
        value: f64,
    },
    /// The value must not be negative.
    Negative {
        /// The offending field.
        field: Field,
        /// Its value.
        value: f64,
    },
    /// The magnitude exceeds [`MAX_MAGNITUDE`].
    TooLarge {
        /// The offending field.
        field: Field,
        /// Its value.
        value: f64,
    },
    /// Zero damping at η = 1: the free rotor is exactly resonant and has no bounded steady state
    /// (`model.md` §6 case 10).
    UndampedResonance,
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ParamError::NonFinite { field, value } => {
                write!(f, "{field} = {value} is not a finite number")
            }
            ParamError::NotPositive { field, value } => {
                write!(f, "{field} = {value} is invalid: it must be > 0")
            }
            ParamError::Negative { field, value } => {
                write!(f, "{field} = {value} is invalid: it must be >= 0")
            }
            ParamError::TooLarge { field, value } => write!(
                f,
                "{field} = {value} is out of range: its magnitude must be <= {MAX_MAGNITUDE:e}"
            ),
            ParamError::UndampedResonance => f.write_str(
                "damping_ratio = 0 with speed_ratio = 1 is exactly resonant: the response grows without bound",
            ),
        }
    }
}

impl core::error::Error for ParamError {}

impl Problem {
    /// Check every value: finite, within [`MAX_MAGNITUDE`], and the sign rules of [`Field::rule`].
    /// Returns the first violation in [`Field::ALL`] order.
    pub fn validate(&self) -> Result<(), ParamError> {
        for field in Field::ALL {
            let value = field.get(self);
            if !value.is_finite() {
                return Err(ParamError::NonFinite { field, value });
            }
            if crate::math::abs(value) > MAX_MAGNITUDE {
                return Err(ParamError::TooLarge { field, value });
            }
            match field {
                Field::SpeedRatio | Field::MassRatio | Field::EccentricityRatio if value <= 0.0 => {
                    return Err(ParamError::NotPositive { field, value });
                }
                Field::DampingRatio | Field::KXx | Field::KYy if value < 0.0 => {
                    return Err(ParamError::Negative { field, value });
                }
                _ => {}
            }
        }
        Ok(())
    }
}

impl Params {
    /// F = η_m ρ̂ η², the amplitude of the unbalance force (`model.md` notation).
    pub fn forcing_amplitude(&self) -> f64 {
        self.mass_ratio * self.eccentricity_ratio * self.speed_ratio * self.speed_ratio
    }

    /// The forcing period 2π/η.
    pub fn forcing_period(&self) -> f64 {
        core::f64::consts::TAU / self.speed_ratio
    }
}
