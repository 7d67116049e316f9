//! The hybrid method (`docs/MODEL.md` §8): exact closed-form free flight, adaptive DOP853 on the
//! nonlinear contact field inside contact, exits located on DOP853's dense output and free flight
//! restarted there. The forcing is carried through contact as a rotating phasor (two extra
//! states, c' = −ηs, s' = ηc), so the contact right-hand side needs no trigonometry.
//!
//! Tolerance semantics: free flight is exact (rounding only); in contact `tol` is DOP853's
//! relative and absolute tolerance per step, as for [`crate::Method::Dop853`].

use crate::analytic::free_flight::FreeFlightSolver;
use crate::coefficients::{ModelParams, Phasor};
use crate::driver::SegmentStart;
use crate::driver::within_bounds;
use crate::driver::{ByRegime, Located, Piecewise, SegmentSolver};
use crate::field::{self, Field};
use crate::params::ValidRange;
use crate::params::{Params, Problem, State};
use crate::propagate::{Event, PropagationError, Regime};
use crate::reference::{
    Dop853, Dop853Dense, Dop853Step, Found, Integrator, Interpolant, OdeSystem, PhasorRotorSystem,
    REFERENCE_BUDGET, ReferenceSolver, SUBDIVISIONS, Switches, Tolerance, switch_in_deferred_step,
};
use crate::registration::{MethodInfo, Registered, Settings};

/// The contact field of [`PhasorRotorSystem`] with the model parameters in the generated code's
/// form prepared once per segment instead of at every stage.
#[derive(Clone, Copy, Debug)]
struct ContactField {
    model: ModelParams,
    /// Frictionless contact, or slipping in a direction.
    field: Field,
}

impl OdeSystem<6> for ContactField {
    #[inline(always)]
    fn rhs(&self, _t: f64, y: &[f64; 6]) -> [f64; 6] {
        phasor_rhs(&self.model, self.field, y)
    }
}

/// [`ContactField`] for frictionless contact: the field fixed at compile time, so the contact
/// steps (the hybrid method's hot path) need no dispatch.
struct Frictionless<'a>(&'a ModelParams);

impl OdeSystem<6> for Frictionless<'_> {
    #[inline(always)]
    fn rhs(&self, _t: f64, y: &[f64; 6]) -> [f64; 6] {
        phasor_rhs(self.0, Field::Contact, y)
    }
}

/// The 6-state field [x', y', x'', y'', c', s'] of `field` with the forcing carried as a phasor
/// (c, s) = (cos θ, sin θ), c' = −η s, s' = η c.
#[inline(always)]
fn phasor_rhs(model: &ModelParams, field: Field, y: &[f64; 6]) -> [f64; 6] {
    let [x, yy, vx, vy, c, s] = *y;
    let (ax, ay) = field::acceleration(
        model,
        field,
        &Phasor { ct: c, st: s },
        &State::new(x, yy, vx, vy),
    );
    let eta = model.speed_ratio;
    [vx, vy, ax, ay, -eta * s, eta * c]
}

/// DOP853 on the 6-state contact field (rotor plus forcing phasor).
///
/// Work per accepted step: the 12 stages of the step and f at its end (the next step's first
/// stage). The dense output (three more evaluations) is built only for a step that holds an exit,
/// a minimum of z, or a requested time: the exit test examines the switching function on
/// sub-intervals no longer than those of the reference propagators (max step /
/// [`SUBDIVISIONS`]), which for contact steps (much shorter than the max step) is the step
/// itself, given by its exact end states. Each contact after the first starts with the step size
/// the previous contact ended with, instead of a fresh initial guess.
pub struct Dop853Contact {
    params: Params,
    system: ContactField,
    integrator: Integrator<Dop853, 6>,
    max_step: f64,
    /// The step size proposed at the end of the last contact.
    carried_step: Option<f64>,
    /// Whether the current contact has taken a step (`step` holds it).
    stepped: bool,
    step: Dop853Step<6>,
    dense: Option<Dop853Dense<6>>,
    /// The switch ending the contact segment (exit, or under friction reverse or roll), once a
    /// step holds it.
    exit: Option<Found<6>>,
    /// The segment's switch functions.
    switches: Switches,
}

impl Dop853Contact {
    /// The contact solver of `params` started at `(t0, s0)` in slip direction `slip`.
    #[inline]
    fn new(params: &Params, tol: f64, slip: f64, t0: f64, s0: State) -> Self {
        let mut solver = Self::unstarted(params, tol, t0, s0);
        solver.begin(slip, t0, s0);
        solver
    }

    /// Start a contact segment at `(time, state)` ([`SegmentSolver::start`]): the slip
    /// direction, the switch functions, and the integration, with the step size the last
    /// contact ended with.
    #[inline]
    fn begin(&mut self, slip: f64, time: f64, state: State) {
        self.system.field = Field::of(Regime::Contact, slip);
        let y = PhasorRotorSystem::initial(&self.params, time, &state);
        self.switches = Switches::new(&self.params, Regime::Contact, slip, time, &y);
        match self.carried_step {
            Some(step) => self
                .integrator
                .restart_with_step(&self.system, time, y, step),
            None => self.integrator.restart(&self.system, time, y),
        }
        self.stepped = false;
        self.exit = None;
    }

    /// The contact solver of `params`, not started: built ahead of the first contact, it
    /// evaluates nothing until the driver starts it there ([`SegmentSolver::start`]; see
    /// [`ReferenceSolver::unstarted`]).
    #[inline]
    fn unstarted(params: &Params, tol: f64, t0: f64, s0: State) -> Self {
        let system = ContactField {
            model: ModelParams::of(params),
            field: Field::Contact,
        };
        let max_step = 0.25 * params.forcing_period().min(core::f64::consts::TAU);
        let y0 = PhasorRotorSystem::initial(params, t0, &s0);
        Dop853Contact {
            params: *params,
            system,
            integrator: Integrator::unstarted(t0, y0, Tolerance::uniform(tol), max_step),
            max_step,
            carried_step: None,
            stepped: false,
            step: Dop853Step::default(),
            dense: None,
            exit: None,
            switches: Switches::with_offset(params, Regime::Contact, 0.0, 0.0),
        }
    }

    /// The state at `t` inside the current step (from its dense output).
    fn state_at(&mut self, t: f64) -> State {
        let y = if t == self.step.t1 {
            self.step.y1
        } else {
            let dense = match self.dense {
                Some(d) => d,
                None => {
                    let d = if self.system.field == Field::Contact {
                        self.step.dense(&Frictionless(&self.system.model))
                    } else {
                        self.step.dense(&self.system)
                    };
                    self.dense = Some(d);
                    d
                }
            };
            dense.eval(t)
        };
        PhasorRotorSystem::rotor_state(&y)
    }
}

impl SegmentSolver for Dop853Contact {
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let (slip, time, state) = (at.slip, at.time, at.state);
        self.begin(slip, time, state);
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located {
        if let Some((t, y, kind)) = self.exit.filter(|(t, _, _)| *t <= target) {
            self.carried_step = Some(self.integrator.proposed_step());
            return Located::Switch(Event {
                time: t,
                kind,
                state: PhasorRotorSystem::rotor_state(&y),
            });
        }
        if self.stepped && target <= self.step.t1 {
            Located::Reached(self.state_at(target))
        } else {
            Located::NeedStep
        }
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        let system = self.system;
        if system.field == Field::Contact {
            self.step_on(&Frictionless(&system.model))
        } else {
            self.step_on(&system)
        }
    }

    fn computed_to(&self) -> f64 {
        self.integrator.time()
    }
}

impl Dop853Contact {
    /// [`SegmentSolver::step`] on `system`, the segment's field.
    #[inline(always)]
    fn step_on<F: OdeSystem<6>>(&mut self, system: &F) -> Result<(), PropagationError> {
        self.dense = None;
        self.integrator
            .step_deferred(system, f64::INFINITY, &mut self.step)?;
        let end = PhasorRotorSystem::rotor_state(&self.step.y1);
        if !within_bounds(&end) {
            return Err(PropagationError::Diverged {
                time: self.step.t1,
                state: end,
            });
        }
        // Sub-intervals no longer than the reference propagators' shortest (max step / 8).
        let ratio = (self.step.t1 - self.step.t0) / self.max_step * SUBDIVISIONS as f64;
        let subdivisions = if ratio <= 1.0 {
            1
        } else {
            (libm::ceil(ratio) as usize).min(SUBDIVISIONS)
        };
        self.exit = switch_in_deferred_step(
            &mut self.integrator,
            system,
            &self.step,
            &self.switches,
            subdivisions,
            &mut self.dense,
        );
        self.stepped = true;
        Ok(())
    }
}

/// The hybrid method (see [`crate::Method::Hybrid`]).
pub struct HybridPropagator(
    Piecewise<ByRegime<FreeFlightSolver, Dop853Contact, ReferenceSolver<Dop853>>>,
);

impl HybridPropagator {
    /// Validate `problem` and `tol` ([`MethodInfo::tolerance_range`]) and start at the problem's
    /// start time.
    #[inline(always)]
    pub fn new(problem: &Problem, tol: f64) -> Result<Self, PropagationError> {
        problem.validate()?;
        Self::start(problem, tol)
    }

    /// As [`HybridPropagator::new`] without checking the problem (see [`Registered::resume`]).
    #[inline(always)]
    fn start(problem: &Problem, tol: f64) -> Result<Self, PropagationError> {
        Self::INFO.check_tolerance(tol)?;
        let params = problem.params;
        let t0 = problem.start_time;
        Piecewise::new(problem, Some(REFERENCE_BUDGET), |at| {
            let (regime, slip, s0) = (at.regime, at.slip, at.state);
            // The solver of the starting regime starts at the problem start; the others are
            // started by the driver at their first segment.
            let contact = if regime == Regime::Contact {
                Dop853Contact::new(&params, tol, slip, t0, s0)
            } else {
                Dop853Contact::unstarted(&params, tol, t0, s0)
            };
            let rolling = if regime == Regime::Rolling {
                ReferenceSolver::new(params, Regime::Rolling, 0.0, t0, s0, tol)
            } else {
                ReferenceSolver::unstarted(params, Regime::Rolling, t0, s0, tol)
            };
            Ok(ByRegime {
                free: FreeFlightSolver::new(&params, t0, s0),
                contact,
                rolling,
            })
        })
        .map(HybridPropagator)
    }
}

impl Registered for HybridPropagator {
    const INFO: MethodInfo = MethodInfo {
        name: "hybrid",
        description: "closed-form free flight, DOP853 in contact",
        default_tolerance: crate::reference::DEFAULT_TOLERANCE,
        tolerance_range: ValidRange {
            min: 1e-14,
            max: 1e-3,
        },
        numerical_reference: false,
        contact_scheme: false,
    };

    #[inline(always)]
    fn build(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
        HybridPropagator::new(problem, settings.tol)
    }

    fn resume(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
        HybridPropagator::start(problem, settings.tol)
    }
}

crate::driver::propagate_through_driver!(HybridPropagator);
