//! rotor-rub: a Jeffcott rotor rubbing on an anisotropically supported stator, propagated segment
//! by segment with closed forms derived at build time.
//!
//! `#![no_std]`, no heap, no panics on finite input. `ARCHITECTURE.md` is the map; the modules:
//!
//! - [`params`]: the parameter table (`entries.rs`, read by the generator too), validation,
//!   presets. [`coefficients`]: every generated formula. [`geometry`], [`field`]: the contact
//!   geometry and each regime's field from them. [`rounding`], [`refine`]: the rounding bands and
//!   the one refinement of a bracketed switch.
//! - [`propagate`]: the `Propagate` trait and its consumers (`events`, `samples`, `advance_to`,
//!   `poincare`). [`driver`]: `Piecewise`, the state machine every method runs on.
//!   [`registration`]: what a method tells the registry; [`method`]: the registry (`Method`,
//!   `Options`, `Propagator`). [`compare`]: matching two runs' events, and how deep a contact
//!   only one run has reaches against what both resolve.
//! - The methods: [`analytic`] (exact free flight, closed-form contact by exprb43/exprb2, the
//!   switch kernel that proves intervals free), [`hybrid`] (exact free flight + DOP853 in
//!   contact), [`taylor`] (generated Taylor recurrences, switches as polynomial roots),
//!   [`reference`](mod@reference) (DOP853, RK45, events on dense output).
//! - [`stepper`]: fixed steps for rigs and the C ABI (a precomputed free map, the exact path on
//!   the driver, caps on the work of a step, inputs between steps, snapshots).
//! - [`speed`], [`variable_speed`]: a speed that changes (profiles, ramps, held steps) and
//!   propagation on it, one row per forcing period, jumps.
//! - [`linalg`]: dense linear algebra for matrix models (modal exponential, bounds, harmonic
//!   response), caller-sized and heap-free.
//! - [`orbit`]: periodic orbits by shooting on the stroboscopic map, the monodromy matrix from the
//!   segments (closed-form free flight, variational equations, saltation), Floquet multipliers.
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
pub mod matrix;
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
