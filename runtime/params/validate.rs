//! Valid ranges and the validation of a problem against the parameter table, with typed errors
//! that name the value and its valid range.

use core::fmt;

use super::{Parameter, Params, Problem};

/// A closed interval `[min, max]`, or `(min, max]` when `min_open`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// Lower bound.
    pub min: f64,
    /// Upper bound (included).
    pub max: f64,
    /// Whether `min` itself is excluded.
    pub min_open: bool,
}

impl Range {
    /// `[min, max]`.
    pub const fn closed(min: f64, max: f64) -> Self {
        Self {
            min,
            max,
            min_open: false,
        }
    }

    /// `(min, max]`.
    pub const fn above(min: f64, max: f64) -> Self {
        Self {
            min,
            max,
            min_open: true,
        }
    }

    /// Whether `value` lies in the range (never for NaN).
    pub fn contains(&self, value: f64) -> bool {
        let low = if self.min_open {
            value > self.min
        } else {
            value >= self.min
        };
        low && value <= self.max
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let open = if self.min_open { '(' } else { '[' };
        write!(f, "{open}{}, {}]", Number(self.min), Number(self.max))
    }
}

/// A closed range `[min, max]` of valid values of a method option.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValidRange {
    /// Smallest valid value.
    pub min: f64,
    /// Largest valid value.
    pub max: f64,
}

impl ValidRange {
    /// Whether `x` lies in the range (never for NaN).
    pub fn contains(&self, x: f64) -> bool {
        x >= self.min && x <= self.max
    }
}

impl fmt::Display for ValidRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{:e}, {:e}]", self.min, self.max)
    }
}

/// A number for messages: plain when short, `{:e}` otherwise (never 300 digits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Number(pub f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = crate::math::abs(self.0);
        if a == 0.0 || (1.0e-3..1.0e6).contains(&a) || !a.is_finite() {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Why a parameter set or initial state was rejected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamError {
    /// The value is NaN or infinite.
    NonFinite {
        /// The offending parameter.
        parameter: Parameter,
        /// Its value.
        value: f64,
    },
    /// The value lies outside the parameter's valid range.
    OutOfRange {
        /// The offending parameter.
        parameter: Parameter,
        /// Its value.
        value: f64,
        /// The valid range (the table's).
        range: Range,
    },
    /// `friction_coefficient` > 0 with a stator stiffness whose symmetric part is not positive
    /// definite (K̂xx ≤ 0, K̂yy ≤ 0 or K̂xx K̂yy − ((K̂xy + K̂yx)/2)² ≤ 0).
    FrictionNeedsDefiniteStator {
        /// μ.
        friction_coefficient: f64,
        /// K̂xx K̂yy − ((K̂xy + K̂yx)/2)², the determinant of the symmetric part.
        determinant: f64,
    },
    /// A stator ring parameter (`contact_stiffness`, `stator_damping`, the ring's start state)
    /// away from its default while `stator_mass_ratio` = 0: the massless ring has no contact
    /// spring, damping or state of its own (its support K_s is the contact), so the value would
    /// be ignored.
    RingWithoutMass {
        /// The ring parameter.
        parameter: Parameter,
        /// Its value.
        value: f64,
    },
    /// `stator_mass_ratio` > 0 (a stator ring with mass, an 8-state model) given to an entry
    /// point that runs the planar 4-state model only (the planar methods' propagators, the
    /// planar `crate::Stepper`). The ring runs through the matrix models
    /// (`crate::matrix::ring_model`), which the CLI and Python choose by themselves, as
    /// `crate::stepper::AnyStepper` (what the C ABI and the FMU run) chooses the ring's
    /// stepper; refused here rather than run as if the ring were massless.
    RingNeedsMatrixModel {
        /// The stator mass ratio m̂.
        stator_mass_ratio: f64,
    },
}

impl ParamError {
    /// The parameter the error is about, if it is about one.
    pub const fn parameter(&self) -> Option<Parameter> {
        match *self {
            ParamError::NonFinite { parameter, .. } | ParamError::OutOfRange { parameter, .. } => {
                Some(parameter)
            }
            ParamError::FrictionNeedsDefiniteStator { .. } => Some(Parameter::FrictionCoefficient),
            ParamError::RingWithoutMass { parameter, .. } => Some(parameter),
            ParamError::RingNeedsMatrixModel { .. } => Some(Parameter::StatorMassRatio),
        }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ParamError::NonFinite { parameter, value } => {
                write!(f, "{parameter} = {value} is not a finite number")
            }
            ParamError::OutOfRange {
                parameter,
                value,
                range,
            } => write!(
                f,
                "{parameter} = {} is out of range: it must be in {range}",
                Number(value)
            ),
            ParamError::FrictionNeedsDefiniteStator {
                friction_coefficient,
                determinant,
            } => write!(
                f,
                "friction_coefficient = {} needs a stator stiffness with a positive definite symmetric part (k_xx > 0, k_yy > 0 and k_xx·k_yy − ((k_xy + k_yx)/2)² > 0; it is {}): otherwise the normal contact force can be negative",
                Number(friction_coefficient),
                Number(determinant)
            ),
            ParamError::RingWithoutMass { parameter, value } => write!(
                f,
                "{parameter} = {} has no effect while stator_mass_ratio = 0 (the massless ring's support K_s is the contact spring): set stator_mass_ratio in (0, 1e3] for a ring with mass, or leave {parameter} at its default {}",
                Number(value),
                Number(parameter.info().default)
            ),
            ParamError::RingNeedsMatrixModel { stator_mass_ratio } => write!(
                f,
                "stator_mass_ratio = {} states a stator ring with mass, which this entry point does not run: it runs the planar model (stator_mass_ratio = 0) only; the ring runs as a matrix model (the CLI's and Python's simulate choose it themselves)",
                Number(stator_mass_ratio)
            ),
        }
    }
}

impl core::error::Error for ParamError {}

impl Parameter {
    /// The stator ring's own entries: its contact spring, damping and start state, which exist
    /// only with a ring mass (`stator_mass_ratio` > 0; [`ParamError::RingWithoutMass`]).
    pub const RING: [Parameter; 6] = [
        Parameter::ContactStiffness,
        Parameter::StatorDamping,
        Parameter::Xs0,
        Parameter::Ys0,
        Parameter::Vxs0,
        Parameter::Vys0,
    ];

    /// The parameter's public name, e.g. `speed_ratio`.
    pub const fn name(self) -> &'static str {
        self.info().name
    }

    /// The parameter with the given public name.
    pub fn from_name(name: &str) -> Option<Parameter> {
        Parameter::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Whether the parameter is a model parameter (a field of [`Params`]) rather than a start value.
    pub const fn is_model(self) -> bool {
        (self as usize) < Parameter::MODEL_COUNT
    }

    /// Check one value against the parameter's own rule (finite, within its range).
    pub fn check(self, value: f64) -> Result<(), ParamError> {
        let range = self.range();
        if !value.is_finite() {
            Err(ParamError::NonFinite {
                parameter: self,
                value,
            })
        } else if !range.contains(value) {
            Err(ParamError::OutOfRange {
                parameter: self,
                value,
                range,
            })
        } else {
            Ok(())
        }
    }
}

impl fmt::Display for Parameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Params {
    /// Refuse a ring with mass ([`ParamError::RingNeedsMatrixModel`]) where only the planar
    /// model runs: the planar driver ([`crate::driver::Piecewise::new`]) and the stepper call it.
    pub fn planar(&self) -> Result<(), ParamError> {
        if self.stator_mass_ratio > 0.0 {
            return Err(ParamError::RingNeedsMatrixModel {
                stator_mass_ratio: self.stator_mass_ratio,
            });
        }
        Ok(())
    }

    /// Check every model parameter against the table, then the rules that tie parameters together
    /// (`cross_checks`). Returns the first violation in table order.
    pub fn validate(&self) -> Result<(), ParamError> {
        // The model parameters lead the table, so the zip stops after them.
        for (parameter, value) in Parameter::ALL.into_iter().zip(self.values()) {
            parameter.check(value)?;
        }
        cross_checks(self)
    }
}

/// Rules across parameters: ring parameters only with a ring mass ([`ParamError::RingWithoutMass`]);
/// μ > 0 on the massless ring needs a positive definite symmetric part of K_s
/// (`docs/MODEL.md §10`: else the normal force N = (z − 1) nᵀK_s n turns negative in some
/// direction and the Coulomb cone is meaningless). ν = 0 at η = 1 (exact resonance) is valid,
/// its free flight grows secularly (`docs/MODEL.md §11`).
fn cross_checks(p: &Params) -> Result<(), ParamError> {
    if p.stator_mass_ratio == 0.0 {
        // Six lookups by table index (every validation of a planar set runs this: the stepper's
        // set_params on a rig's speed input, for one).
        let values = p.values();
        for parameter in Parameter::RING {
            let value = values.get(parameter as usize).copied().unwrap_or(f64::NAN);
            if value != parameter.info().default {
                return Err(ParamError::RingWithoutMass { parameter, value });
            }
        }
    }
    // With a ring of mass the contact law is k̂_c I (isotropic, N ≥ 0 whatever K_s).
    if p.friction_coefficient > 0.0 && p.stator_mass_ratio == 0.0 {
        let cross = 0.5 * (p.k_xy + p.k_yx);
        let determinant = p.k_xx * p.k_yy - cross * cross;
        if !(p.k_xx > 0.0 && p.k_yy > 0.0 && determinant > 0.0) {
            return Err(ParamError::FrictionNeedsDefiniteStator {
                friction_coefficient: p.friction_coefficient,
                determinant,
            });
        }
    }
    Ok(())
}

impl Problem {
    /// Check every value against the table (finite, in range), then the cross-parameter rules.
    /// Returns the first violation in [`Parameter::ALL`] order.
    pub fn validate(&self) -> Result<(), ParamError> {
        for (parameter, value) in Parameter::ALL.into_iter().zip(self.values()) {
            parameter.check(value)?;
        }
        cross_checks(&self.params)
    }
}
