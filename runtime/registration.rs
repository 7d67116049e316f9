//! What a method tells the registry (`method.rs`) about itself: its facts ([`MethodInfo`]: name,
//! tolerance range, …), how it is built ([`Registered`], from the [`Settings`] the registry
//! resolves from the user's options) and the contact scheme a closed-form method takes. The
//! methods implement these and the registry lists the methods; neither imports the other's
//! module back (the registry depends on the methods, the methods on this module).

use crate::params::{Problem, ValidRange};
use crate::propagate::{Propagate, PropagationError};

/// The fixed contact sub-step of exprb2 and of fixed-step exprb43 (`--step`), in units of τ.
/// Below 1e-6 a run takes hours for what 1e-6 gives to 1e-9 in switch times; above 0.1 the
/// sub-step exceeds the contact period of stiff stators and exprb2's switch times err by
/// O(1) (measured on the paper preset at η = 1.2 and 2.5 against DOP853 at tol 1e-13).
pub const STEP_RANGE: ValidRange = ValidRange {
    min: 1e-6,
    max: 0.1,
};

/// What the registry knows about a method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MethodInfo {
    /// Command-line name.
    pub name: &'static str,
    /// One line for help texts.
    pub description: &'static str,
    /// Tolerance when none is given.
    pub default_tolerance: f64,
    /// Tolerances whose answers are meaningful (measured: `docs/MODEL.md` §13).
    pub tolerance_range: ValidRange,
    /// Whether it integrates the full equations numerically, so that it can serve as the
    /// reference of `compare` and `fig2`.
    pub numerical_reference: bool,
    /// Whether it takes a contact scheme and a fixed sub-step ([`Settings::contact_scheme`],
    /// [`Settings::step`]).
    pub contact_scheme: bool,
}

impl MethodInfo {
    /// The one tolerance validation: `tol` in [`MethodInfo::tolerance_range`], else
    /// [`PropagationError::InvalidOption`] naming the method, the value and the range.
    pub fn check_tolerance(&self, tol: f64) -> Result<(), PropagationError> {
        let valid = self.tolerance_range;
        if valid.contains(tol) {
            Ok(())
        } else {
            Err(PropagationError::InvalidOption {
                method: self.name,
                what: "tol",
                value: tol,
                valid,
            })
        }
    }

    /// The fixed contact sub-step validation: `step` in [`STEP_RANGE`], else
    /// [`PropagationError::InvalidOption`] naming the method.
    pub fn check_step(&self, step: f64) -> Result<(), PropagationError> {
        if STEP_RANGE.contains(step) {
            Ok(())
        } else {
            Err(PropagationError::InvalidOption {
                method: self.name,
                what: "step",
                value: step,
                valid: STEP_RANGE,
            })
        }
    }
}

/// A method's entry in the registry: its facts and how to build it from its [`Settings`].
pub trait Registered: Propagate + Sized {
    /// The method's facts.
    const INFO: MethodInfo;
    /// Start the method on `problem` with validated `settings`.
    fn build(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError>;
    /// Continue a run from a state it reached: as [`Registered::build`], but the problem's
    /// initial state and start time are not checked against the parameter table's start
    /// ranges (a run may leave them); the state is checked for divergence only. The caller has
    /// validated the parameters (a speed held over a step of a speed profile).
    fn resume(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError>;
}

/// What a method is built with: the options the registry resolved for it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The tolerance in force (the given one or the method's default).
    pub tol: f64,
    /// The contact scheme of a method that takes one ([`MethodInfo::contact_scheme`]).
    pub contact_scheme: ContactScheme,
    /// A fixed contact sub-step in [`STEP_RANGE`] (exprb2 always uses a fixed sub-step;
    /// exprb43 uses it instead of step control when given).
    pub step: Option<f64>,
}

/// The analytic method's contact scheme (`docs/MODEL.md` §8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactScheme {
    /// Exponential Rosenbrock–Euler: the paper's closed-form step re-linearized at every sub-step
    /// start, fixed sub-step, second order.
    Exprb2,
    /// Hochbruck–Ostermann exprb43: fourth order, embedded third-order estimate, adaptive.
    Exprb43,
}

impl ContactScheme {
    /// Every scheme; a scheme's index here is its code in the C ABI (`ROTOR_RUB_SCHEME_*`).
    pub const ALL: [ContactScheme; 2] = [ContactScheme::Exprb2, ContactScheme::Exprb43];

    /// The scheme's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            ContactScheme::Exprb2 => "exprb2",
            ContactScheme::Exprb43 => "exprb43",
        }
    }

    /// The scheme's code in the C ABI: its index in [`ContactScheme::ALL`].
    pub const fn code(self) -> i32 {
        match self {
            ContactScheme::Exprb2 => 0,
            ContactScheme::Exprb43 => 1,
        }
    }

    /// The scheme with the given C ABI code.
    pub fn from_code(code: i32) -> Option<ContactScheme> {
        ContactScheme::ALL.into_iter().find(|s| s.code() == code)
    }

    /// The scheme with the given name.
    pub fn from_name(name: &str) -> Option<ContactScheme> {
        ContactScheme::ALL.into_iter().find(|s| s.name() == name)
    }
}
