//! rotor-rub: a Jeffcott rotor rubbing on an anisotropically supported stator, propagated segment
//! by segment with closed forms derived at build time.
//!
//! `#![no_std]`, no heap, no panics on finite input. See `ARCHITECTURE.md` for the map.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]
// No panic paths in library code (tests may unwrap): checked by clippy in `.ci/run`.
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing
    )
)]

pub mod analytic;
pub mod coefficients;
pub mod compare;
pub mod driver;
pub mod field;
pub mod geometry;
pub mod hybrid;
pub mod linalg;
pub mod math;
pub mod method;
pub mod orbit;
pub mod params;
pub mod propagate;
pub mod reference;
pub mod refine;
pub mod registration;
pub mod rounding;
pub mod speed;
pub mod stepper;
#[cfg(feature = "proptest")]
pub mod strategies;
pub mod taylor;
pub mod variable_speed;

pub use method::{ContactScheme, Method, Options, Propagator};
pub use params::{ParamError, Parameter, Params, Preset, Problem, State};
pub use propagate::{
    Event, EventKind, Propagate, PropagationError, Regime, Sample, advance_to, events, poincare,
    poincare_times, samples,
};
pub use stepper::{EventList, StepReport, Stepper, StepperConfig, StepperError};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
