//! Numerical reference integrators (issue 4): adaptive Dormand–Prince 5(4) and DOP853 on the full
//! piecewise equations, with switch location on the dense output.
//!
//! - [`OdeSystem`], [`Scheme`], [`Integrator`]: a small generic adaptive Runge–Kutta core on
//!   fixed-size `[f64; N]` states (no heap), reusable on other systems (the hybrid method's
//!   6-state [`PhasorRotorSystem`]).
//! - [`Rk45`], [`Dop853`]: the two pairs with their dense outputs.
//! - [`first_crossing_subdivided`]: event location on a dense output, grazing contacts included.
//! - [`Dop853Propagator`], [`Rk45Propagator`]: the [`crate::Propagate`] implementations.
//!
//! ```
//! use rotor_rub::reference::{Dop853, Dop853Propagator, Integrator, Interpolant, Tolerance};
//! use rotor_rub::{Preset, Propagate, events};
//!
//! // The paper's preset: switches over 5 forcing periods.
//! let problem = Preset::Paper.problem();
//! let mut prop = Dop853Propagator::new(&problem, 1e-10)?;
//! let end = 5.0 * problem.params.forcing_period();
//! let switches = events(&mut prop, end).collect::<Result<Vec<_>, _>>()?;
//! assert!(switches.len() >= 2);
//!
//! // The integrator core on any closure: y'' = −y over a quarter period.
//! let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
//! let mut integ = Integrator::<Dop853, 2>::new(&f, 0.0, [1.0, 0.0], Tolerance::uniform(1e-12), 1.0);
//! let quarter = core::f64::consts::FRAC_PI_2;
//! while integ.time() < quarter {
//!     let step = integ.step(&f, quarter)?;
//!     let _midpoint = step.dense.eval(0.5 * (step.t0 + step.t1));
//! }
//! assert!(integ.state()[0].abs() < 1e-11);
//! # Ok::<(), rotor_rub::PropagationError>(())
//! ```

mod dop853;
mod events;
mod integrator;
mod ode;
mod propagator;
mod rk45;
mod scheme;
mod switch;
mod system;
mod tableau_dop853;
mod tableau_rk45;

pub use dop853::{Dop853, Dop853Dense, Dop853Step};
pub use events::{SUBDIVISIONS, first_crossing_beyond, first_crossing_subdivided, polish_switch};
pub use integrator::{AcceptedStep, Integrator, MAX_REJECTIONS, Stats};
pub use ode::OdeSystem;
pub use propagator::{
    BASE_STEP_BUDGET, Dop853Propagator, FieldFamily, REFERENCE_BUDGET, ReferencePropagator,
    ReferenceSolver, Rk45Propagator, STEPS_PER_TIME_UNIT,
};
pub use rk45::{Rk45, Rk45Dense};
pub(crate) use scheme::After;
pub use scheme::{Attempt, Controller, Interpolant, Scheme, StepStart, Tolerance};
pub(crate) use switch::LazyDense;
pub use switch::{Found, Function, Switches, switch_in_deferred_step, switch_in_step};
pub use system::{PhasorRotorSystem, PreparedRotorSystem, RotorSystem, inside_measure};

/// Default `tol` (relative and absolute) of the reference integrators.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
