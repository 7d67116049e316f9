//! The reference propagators: an adaptive Runge–Kutta integration of the full piecewise equations
//! (`docs/MODEL.md` §1) behind [`Propagate`], with switches located on the dense output.
//!
//! How a run proceeds:
//! - The regime at the start is decided by [`crate::field::regime_of`]; the field is always the current
//!   regime's, never chosen by the sign of h.
//! - Steps are taken freely (never shortened to a requested time); after each accepted step the
//!   first switch inside it is searched by [`first_crossing_subdivided`]. A found switch is refined on the
//!   dense output to the resolution of `f64`, and the state there is recomputed by one explicit
//!   step of exactly the needed size from the step's start; a few Newton corrections on that
//!   step solution ([`super::polish_switch`]) then put the switch state on z = 1 to
//!   rounding level.
//!   The integration restarts at the switch on the other regime's field, the switch time
//!   counting as inside the new regime.
//! - A requested time inside the current step is served from its dense output, so sampling never
//!   changes the step sequence or the trajectory.
//! - Errors: [`PropagationError::Diverged`] when a step ends beyond
//!   [`crate::propagate::DIVERGENCE_RADIUS`] of the rest position (`within_bounds`); [`PropagationError::StepSizeUnderflow`] when the step size collapses or one
//!   `advance` call exceeds its step budget ([`BASE_STEP_BUDGET`]). After a divergence or an
//!   underflow the propagator stays at its last good time and returns the same error again.
//!
//! Tolerance semantics: per step, `rtol = atol = tol` in Hairer's mixed norm
//! (`‖err_i / (tol + tol·max(|y0_i|, |y1_i|))‖_rms ≤ 1`). This bounds the local error, not the
//! global one. Measured on free flight over 50 forcing periods at `tol = 1e-12`, the global error
//! is 2e-12 (DOP853) and 1e-12 (RK45); switch times of the Fig. 2 cases change by less than 2e-11
//! between `tol = 1e-12` and `1e-13`. Contacts whose penetration depth in z is below about
//! `10·tol` may be missed — or made: on an orbit that only grazes z = 1 the integrated orbit
//! crosses it by the truncation error (the exactly grazing orbit z ≡ 1: thousands of contacts up
//! to 8e-11 deep at tol 1e-10, where the closed forms see none). `crate::compare` sets contacts
//! only one run has that are shallower than that aside ([`crate::compare::contact_resolution`]).

use super::dop853::Dop853;
use super::integrator::{AcceptedStep, Integrator, Stats};
use super::ode::OdeSystem;
use super::rk45::Rk45;
use super::scheme::{Interpolant, Scheme, Tolerance};
use super::switch::{Switches, switch_in_step};
use super::system::PreparedRotorSystem;
use crate::driver::SegmentStart;
use crate::driver::within_bounds;
use crate::driver::{Located, Piecewise, SegmentSolver, Solvers, StepBudget};
use crate::params::ValidRange;
use crate::params::{Params, Problem, State};
use crate::propagate::{Event, Propagate, PropagationError, Regime};
use crate::registration::{MethodInfo, Registered, Settings};

/// Step budget of one [`Propagate::advance`] call: this many steps plus
/// [`STEPS_PER_TIME_UNIT`] per unit of the requested time span. Exceeding it reports
/// [`PropagationError::StepSizeUnderflow`] (the steps became too small to make progress).
pub const BASE_STEP_BUDGET: f64 = 1.0e6;

/// See [`BASE_STEP_BUDGET`].
pub const STEPS_PER_TIME_UNIT: f64 = 1.0e5;

/// The step budget of the numerical methods (reference and hybrid).
pub const REFERENCE_BUDGET: StepBudget = StepBudget {
    base: BASE_STEP_BUDGET,
    per_time_unit: STEPS_PER_TIME_UNIT,
};

/// The fields a [`ReferenceSolver`] integrates: one 4-state system per regime and slip
/// direction. The model's parameters are one ([`PreparedRotorSystem`], constant speed); a speed profile's
/// piece is another (`variable_speed::RampField`).
pub trait FieldFamily: Copy {
    /// The system of one regime.
    type System: OdeSystem<4>;
    /// The field of `regime` with slip direction `slip`.
    fn system(&self, regime: Regime, slip: f64) -> Self::System;
    /// The parameters the switch functions use; their speed ratio sets the largest step.
    fn params(&self) -> &Params;
}

impl FieldFamily for Params {
    type System = PreparedRotorSystem;

    #[inline]
    fn system(&self, regime: Regime, slip: f64) -> PreparedRotorSystem {
        PreparedRotorSystem::new(self, regime, slip)
    }

    fn params(&self) -> &Params {
        self
    }
}

/// One integrator for both regimes: a switch restarts it on the other regime's field, so the
/// free and the contact solver of [`crate::driver::Solvers`] are the same object.
#[derive(Clone, Copy, Debug)]
pub struct ReferenceSolver<S: Scheme<4>, F: FieldFamily = Params> {
    field: F,
    regime: Regime,
    slip: f64,
    switches: Switches,
    integrator: Integrator<S, 4>,
    step: Option<AcceptedStep<4, S::Dense>>,
    pending: Option<Event>,
}

impl<S: Scheme<4>, F: FieldFamily> ReferenceSolver<S, F> {
    /// A solver of `regime`'s field in `field`'s family (the model's [`Params`], or a ramp's
    /// fields), slip direction `slip`, started at `(t0, state)` with `rtol = atol = tol`.
    pub fn new(field: F, regime: Regime, slip: f64, t0: f64, state: State, tol: f64) -> Self {
        let mut solver = Self::unstarted(field, regime, t0, state, tol);
        solver.begin(regime, slip, t0, state);
        solver
    }

    /// A solver of `regime`'s field built ahead of its segment: nothing is evaluated until the
    /// driver starts it ([`SegmentSolver::start`]) at the segment's first switch. For the
    /// regimes a run does not start in (building a started one costs two field evaluations, the
    /// initial step's power and the switch measures, for a solver that is restarted anyway).
    #[inline]
    pub(crate) fn unstarted(field: F, regime: Regime, t0: f64, state: State, tol: f64) -> Self {
        let params = field.params();
        ReferenceSolver {
            switches: Switches::with_offset(params, regime, 0.0, 0.0),
            integrator: Integrator::unstarted(
                t0,
                state.to_array(),
                Tolerance::uniform(tol),
                max_step(params),
            ),
            field,
            regime,
            slip: 0.0,
            step: None,
            pending: None,
        }
    }

    /// Take `regime`'s field (slip direction `slip`) and restart the integration at
    /// `(time, state)` ([`SegmentSolver::start`]).
    fn begin(&mut self, regime: Regime, slip: f64, time: f64, state: State) {
        self.regime = regime;
        self.slip = slip;
        self.switches = Switches::new(self.field.params(), regime, slip, time, &state.to_array());
        self.step = None;
        self.pending = None;
        let sys = self.system();
        self.integrator.restart(&sys, time, state.to_array());
    }

    fn system(&self) -> F::System {
        self.field.system(self.regime, self.slip)
    }

    /// Work counters of the integration so far.
    pub fn stats(&self) -> Stats {
        self.integrator.stats()
    }
}

impl<S: Scheme<4>, F: FieldFamily> Solvers for ReferenceSolver<S, F> {
    fn solver(&mut self, _regime: Regime) -> &mut dyn SegmentSolver {
        self
    }

    #[inline]
    fn locate(&mut self, _regime: Regime, target: f64) -> Located {
        SegmentSolver::locate(self, target)
    }
}

impl<S: Scheme<4>, F: FieldFamily> SegmentSolver for ReferenceSolver<S, F> {
    /// Switch the field and restart the integration at the switch.
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let (regime, slip, time, state) = (at.regime, at.slip, at.time, at.state);
        self.begin(regime, slip, time, state);
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located {
        if let Some(event) = self.pending
            && target >= event.time
        {
            return Located::Switch(event);
        }
        match &self.step {
            Some(step) if target <= step.t1 => Located::Reached(if target == step.t1 {
                State::from_array(step.y1)
            } else {
                State::from_array(step.dense.eval(target))
            }),
            _ => Located::NeedStep,
        }
    }

    /// Take one step and look for a switch in it.
    fn step(&mut self) -> Result<(), PropagationError> {
        let sys = self.system();
        let step = self.integrator.step(&sys, f64::INFINITY)?;
        let end = State::from_array(step.y1);
        if !within_bounds(&end) {
            return Err(PropagationError::Diverged {
                time: step.t1,
                state: end,
            });
        }
        self.pending = switch_in_step(&mut self.integrator, &sys, &step, &self.switches).map(
            |(time, y, kind)| Event {
                time,
                kind,
                state: State::from_array(y),
            },
        );
        self.step = Some(step);
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.integrator.time()
    }
}

/// The reference propagator for any [`Scheme`] on the 4-state rotor field. Use it through
/// [`Dop853Propagator`] or [`Rk45Propagator`].
#[derive(Clone, Copy, Debug)]
pub struct ReferencePropagator<S: Scheme<4>> {
    driver: Piecewise<ReferenceSolver<S>>,
    events: u64,
}

impl<S: Scheme<4>> ReferencePropagator<S> {
    /// Validate `problem` and `tol` (the range of `method`) and start at the problem's start
    /// time.
    ///
    /// # Errors
    /// [`PropagationError::InvalidProblem`] or [`PropagationError::InvalidOption`] for the
    /// tolerance.
    pub fn new(problem: &Problem, method: &MethodInfo, tol: f64) -> Result<Self, PropagationError> {
        problem.validate()?;
        Self::start(problem, method, tol)
    }

    /// As [`ReferencePropagator::new`] without checking the problem (see
    /// [`Registered::resume`]).
    fn start(problem: &Problem, method: &MethodInfo, tol: f64) -> Result<Self, PropagationError> {
        method.check_tolerance(tol)?;
        let params = problem.params;
        let t0 = problem.start_time;
        let driver = Piecewise::new(problem, Some(REFERENCE_BUDGET), |at| {
            Ok(ReferenceSolver::new(
                params, at.regime, at.slip, t0, at.state, tol,
            ))
        })?;
        Ok(ReferencePropagator { driver, events: 0 })
    }

    /// Work counters of the integration so far.
    pub fn stats(&self) -> Stats {
        self.driver.solvers().integrator.stats()
    }

    /// The number of switches reported so far.
    pub fn event_count(&self) -> u64 {
        self.events
    }

    /// The tolerance (`rtol = atol`).
    pub fn tolerance(&self) -> f64 {
        self.driver.solvers().integrator.tolerance().rtol
    }
}

/// The largest step: a quarter of the shorter of the forcing period and the free natural period
/// 2π, so that the switching function is sampled at least 4·[`super::events::SUBDIVISIONS`]
/// times per period even at loose tolerances.
fn max_step(params: &Params) -> f64 {
    let period = params.forcing_period().min(core::f64::consts::TAU);
    if period > 0.0 {
        0.25 * period
    } else {
        f64::INFINITY
    }
}

impl<S: Scheme<4>> Propagate for ReferencePropagator<S> {
    fn time(&self) -> f64 {
        self.driver.time()
    }

    fn state(&self) -> State {
        self.driver.state()
    }

    fn regime(&self) -> Regime {
        self.driver.regime()
    }

    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        let event = self.driver.advance(target)?;
        if event.is_some() {
            self.events = self.events.saturating_add(1);
        }
        Ok(event)
    }
}

macro_rules! reference_propagator {
    ($(#[$doc:meta])* $name:ident, $scheme:ty, $info:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug)]
        pub struct $name(ReferencePropagator<$scheme>);

        impl $name {
            /// Validate `problem` and `tol` (in the method's [`MethodInfo::tolerance_range`];
            /// `rtol = atol = tol`) and start at the problem's start time.
            ///
            /// # Errors
            /// [`PropagationError::InvalidProblem`], or [`PropagationError::InvalidOption`] for
            /// the tolerance.
            pub fn new(problem: &Problem, tol: f64) -> Result<Self, PropagationError> {
                ReferencePropagator::new(problem, &<Self as Registered>::INFO, tol).map($name)
            }

            /// Work counters of the integration so far.
            pub fn stats(&self) -> Stats {
                self.0.stats()
            }

            /// The number of switches reported so far.
            pub fn event_count(&self) -> u64 {
                self.0.event_count()
            }

            /// The tolerance (`rtol = atol`).
            pub fn tolerance(&self) -> f64 {
                self.0.tolerance()
            }
        }

        impl Registered for $name {
            const INFO: MethodInfo = $info;

            fn build(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
                $name::new(problem, settings.tol)
            }

            fn resume(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
                ReferencePropagator::start(problem, &Self::INFO, settings.tol).map($name)
            }
        }

        crate::driver::propagate_through_driver!($name);
    };
}

reference_propagator!(
    /// Adaptive DOP853 (Dormand–Prince 8(5,3), Hairer's code) on the full piecewise equations,
    /// with switches located on its 7th-order dense output. See the module documentation.
    Dop853Propagator,
    Dop853,
    MethodInfo {
        name: "dop853",
        description: "adaptive Dormand–Prince 8(5,3) on the full equations",
        default_tolerance: super::DEFAULT_TOLERANCE,
        tolerance_range: ValidRange {
            min: 1e-14,
            max: 1e-3
        },
        numerical_reference: true,
        contact_scheme: false,
    }
);

reference_propagator!(
    /// Adaptive Dormand–Prince 5(4) (MATLAB's `ode45`) on the full piecewise equations, with
    /// switches located on its 4th-order dense output. See the module documentation.
    Rk45Propagator,
    Rk45,
    MethodInfo {
        name: "rk45",
        description: "adaptive Dormand–Prince 5(4) (MATLAB's ode45) on the full equations",
        default_tolerance: super::DEFAULT_TOLERANCE,
        tolerance_range: ValidRange {
            min: 1e-14,
            max: 1e-4
        },
        numerical_reference: true,
        contact_scheme: false,
    }
);
