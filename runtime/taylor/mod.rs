//! The `taylor` method (`docs/MODEL.md` §16): exact closed-form free flight, and in contact a
//! Taylor integrator whose coefficient recurrences the generator emits from the model statement
//! (`coefficients::contact_taylor`, `slipping_taylor`, `rolling_taylor`; built by
//! `codegen/src/taylor`).
//!
//! Each contact step expands the regime's field about the step's start to order
//! p = ⌈−ln(tol)/2 + 1⌉ ([`expansion`]), takes the step the last two orders allow (Jorba–Zou),
//! and searches the switch functions — z² − 1, and under friction σw or μN ∓ λ — as
//! polynomials of the step's local time ([`roots`]: Descartes isolation, so no sign change inside
//! a step is missed, and a start on the switch surface divides its root out). Samples and
//! Poincaré points come from the same polynomials. No heap: the series live in a fixed array
//! (orders up to [`kernels::MAX_ORDER`]).
//!
//! Tolerance semantics: free flight is exact (rounding only); in contact `tol` bounds each
//! step's truncation error, relative to max(1, |state|).

pub mod expansion;
pub mod kernels;
pub mod roots;
mod solver;
mod step;

pub use solver::TaylorContact;

use crate::analytic::free_flight::FreeFlightSolver;
use crate::driver::{Located, Piecewise, SegmentSolver, Solvers};
use crate::params::Problem;
use crate::params::ValidRange;
use crate::propagate::{PropagationError, Regime};
use crate::reference::REFERENCE_BUDGET;
use crate::registration::{MethodInfo, Registered, Settings};

/// The taylor method (see [`crate::Method::Taylor`]).
pub struct TaylorPropagator(Piecewise<TaylorSolvers>);

/// Free flight in closed form; contact and rolling by one [`TaylorContact`] (a segment of either
/// starts it afresh, so one set of series serves both: 8 KB less than two).
pub struct TaylorSolvers {
    free: FreeFlightSolver,
    contact: TaylorContact,
}

impl Solvers for TaylorSolvers {
    fn solver(&mut self, regime: Regime) -> &mut dyn SegmentSolver {
        match regime {
            Regime::Free => &mut self.free,
            Regime::Contact | Regime::Rolling => &mut self.contact,
        }
    }

    #[inline]
    fn locate(&mut self, regime: Regime, target: f64) -> Located {
        match regime {
            Regime::Free => self.free.locate(target),
            Regime::Contact | Regime::Rolling => self.contact.locate(target),
        }
    }
}

impl TaylorPropagator {
    /// Validate `problem` and `tol` ([`MethodInfo::tolerance_range`]) and start at the problem's
    /// start time.
    pub fn new(problem: &Problem, tol: f64) -> Result<Self, PropagationError> {
        problem.validate()?;
        Self::start(problem, tol)
    }

    /// As [`TaylorPropagator::new`] without checking the problem (see [`Registered::resume`]).
    fn start(problem: &Problem, tol: f64) -> Result<Self, PropagationError> {
        Self::INFO.check_tolerance(tol)?;
        let params = problem.params;
        let t0 = problem.start_time;
        Piecewise::new(problem, Some(REFERENCE_BUDGET), |at| {
            let s0 = at.state;
            let mut contact = TaylorContact::new(&params, tol, t0, s0);
            // The one solver serves contact and rolling: a run (or a resumed run) that starts
            // rolling starts it on the rolling field, not on the frictionless one it is built
            // with (issue 32 item 3: a start with w = 0 where the λ rule says roll).
            if at.regime != Regime::Free {
                contact.start(at)?;
            }
            Ok(TaylorSolvers {
                free: FreeFlightSolver::new(&params, t0, s0),
                contact,
            })
        })
        .map(TaylorPropagator)
    }
}

impl Registered for TaylorPropagator {
    const INFO: MethodInfo = MethodInfo {
        name: "taylor",
        description: "closed-form free flight, generated Taylor series in contact",
        default_tolerance: crate::reference::DEFAULT_TOLERANCE,
        tolerance_range: ValidRange {
            min: 1e-16,
            max: 1e-3,
        },
        numerical_reference: false,
        contact_scheme: false,
    };

    fn build(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
        TaylorPropagator::new(problem, settings.tol)
    }

    fn resume(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
        TaylorPropagator::start(problem, settings.tol)
    }
}

crate::driver::propagate_through_driver!(TaylorPropagator);
