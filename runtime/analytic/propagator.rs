//! The analytic method: exact free flight ([`FreeFlightSolver`], shared with the hybrid and
//! taylor methods) and re-linearized closed-form contact ([`ExprbContact`]), with switches
//! located on the closed forms (`docs/MODEL.md` §4–§8), strung together by the piecewise driver.

use super::free_flight::FreeFlightSolver;
use super::linear::{ContactConstants, max_contact_stiffness};
use super::schemes::{SubStep, exprb2_with, exprb43_with};
use super::segment::Segment;
use super::switch::{Budget, Direction, SlipVelocity, first_crossing_to, first_slip_switch};
use crate::driver::SegmentStart;
use crate::driver::within_bounds;
use crate::driver::{ByRegime, Located, Piecewise, SegmentSolver};
use crate::geometry;
use crate::math;
use crate::params::ValidRange;
use crate::params::{Params, Problem, State};
use crate::propagate::{Event, EventKind, PropagationError, Regime};
use crate::reference::{Dop853, ReferenceSolver};
use crate::registration::{ContactScheme, MethodInfo, Registered, Settings};

/// Default fixed sub-step of exprb2 (switch error ≈ 1e-6 on the paper's cases, `docs/MODEL.md`
/// §8).
pub const DEFAULT_EXPRB2_STEP: f64 = 1e-3;
/// Most step attempts for one accepted exprb43 sub-step before giving up.
const MAX_ATTEMPTS: u32 = 60;

/// The rounding each contact sub-step adds to the state, in units of ε times the contact
/// frequency ω = √‖Kl‖ (relative to the step control's scale 1 + |w|): every sub-step starts a
/// closed form from a state rounded to a few ulps of |q|, and the stiff mode turns a position
/// error δ into a velocity error ωδ. A truncation error target below it only adds sub-steps,
/// and with them rounding: exprb43's step control never asks for less (issue 32: at K̂ = 1e5
/// a tolerance of 1e-14 took 730 sub-steps per contact and ended 2.7e-12 off, 3e-13 took 310
/// and 1.5e-13).
const STEP_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// Contact by exprb2 or exprb43 sub-steps (`docs/MODEL.md` §8), each re-linearized at its start,
/// its exit searched on the sub-step's closed form.
pub struct ExprbContact {
    params: Params,
    /// What every linearization of `params` shares.
    constants: ContactConstants,
    scheme: ContactScheme,
    /// exprb43's error target: the method's tolerance, or the rounding the sub-steps add
    /// where that is larger ([`STEP_ROUNDING`]).
    tol: f64,
    fixed_step: Option<f64>,
    max_step: f64,
    next_step: f64,
    /// Rounding carried by the sum of sub-step lengths (Kahan): without it, a fixed sub-step
    /// added 10⁷ times drifts the time by its rounding bias (≈ 3e-8 at τ ≈ 250, step 1e-5),
    /// which floors exprb2's switch-time accuracy.
    time_carry: f64,
    /// Two sub-step slots: the current one (`steps[current]`) and the one the next sub-step is
    /// computed in, swapped by index on acceptance (a sub-step is too large to copy around).
    steps: [SubStep; 2],
    current: usize,
    /// Start of the current sub-step.
    t0: f64,
    /// The switch inside the current sub-step (local time, state, kind), if any: the exit, or
    /// under friction `reverse` or `roll` where the slip velocity reaches 0.
    exit: Option<(f64, State, EventKind)>,
    /// The slip direction σ of the segment (0: frictionless).
    slip: f64,
    /// The slip switch's offset and scale for this segment ([`SlipVelocity`]).
    slip_offset: f64,
    slip_scale: f64,
}

impl ExprbContact {
    fn new(params: &Params, scheme: ContactScheme, tol: f64, fixed_step: Option<f64>) -> Self {
        // Fastest frequencies: forcing η, free 1, contact ≤ √(sup over z ≥ 1 of ‖Kl‖).
        let omega = params.speed_ratio.max(1.0 + params.damping_ratio);
        let omega_contact = math::sqrt(max_contact_stiffness(params)).max(omega);
        ExprbContact {
            params: *params,
            constants: ContactConstants::new(params),
            scheme,
            tol: tol.max(STEP_ROUNDING * omega_contact),
            fixed_step: match scheme {
                ContactScheme::Exprb2 => Some(fixed_step.unwrap_or(DEFAULT_EXPRB2_STEP)),
                ContactScheme::Exprb43 => fixed_step,
            },
            max_step: 1.0 / omega_contact,
            next_step: 0.1 / omega_contact,
            time_carry: 0.0,
            steps: [SubStep::zeroed(), SubStep::zeroed()],
            current: 0,
            t0: 0.0,
            exit: None,
            slip: 0.0,
            slip_offset: 0.0,
            slip_scale: 1.0,
        }
    }

    /// Compute the sub-step from `(t0, state)` (step control for adaptive exprb43) and its exit.
    fn sub_step(&mut self, t0: f64, state: State) -> Result<(), PropagationError> {
        if !within_bounds(&state) {
            return Err(PropagationError::Diverged { time: t0, state });
        }
        let min_step = 1e-12 * (1.0 + math::abs(t0));
        let mut attempts = 0;
        let next = 1 - self.current;
        let slot = self
            .steps
            .get_mut(next)
            .ok_or(PropagationError::SingularContact { time: t0 })?;
        loop {
            let dt = self
                .fixed_step
                .unwrap_or(self.next_step.clamp(min_step, self.max_step));
            let slip = self.slip;
            match self.scheme {
                ContactScheme::Exprb2 => exprb2_with(&self.constants, slip, t0, state, dt, slot),
                ContactScheme::Exprb43 => {
                    exprb43_with(&self.constants, slip, t0, state, dt, self.tol, slot)
                }
            }
            .map_err(|_| PropagationError::SingularContact { time: t0 })?;
            if self.fixed_step.is_some() {
                break;
            }
            let error = slot.error;
            let factor = if error > 0.0 {
                // 0.9·error^(−1/4), by two square roots (a power costs ten times more).
                0.9 / math::sqrt(math::sqrt(error))
            } else {
                4.0
            };
            if error <= 1.0 {
                self.next_step = dt * factor.min(4.0);
                break;
            }
            self.next_step = dt * factor.clamp(0.1, 0.9);
            attempts += 1;
            if attempts >= MAX_ATTEMPTS || self.next_step < min_step {
                return Err(PropagationError::StepSizeUnderflow { time: t0 });
            }
        }
        if !slot.end.is_finite() {
            return Err(PropagationError::Diverged {
                time: t0 + slot.length,
                state: slot.end,
            });
        }
        let model = self.constants.model();
        let start = geometry::point(model, state);
        // The sub-step's end is the segment's point at its length: no need to evaluate it again.
        let end = geometry::point(model, slot.end);
        let exit = first_crossing_to(&slot.segment, 0.0, start, slot.length, end, Direction::Down);
        self.exit = exit.map(|(s, p)| (s, p.state, EventKind::Exit));
        if self.slip != 0.0 {
            let limit = exit.map_or(slot.length, |(s, _)| s);
            let f = SlipVelocity::new(
                &slot.segment,
                t0,
                self.slip,
                self.slip_offset,
                self.slip_scale,
            );
            if let Some(found) = first_slip_switch(&f, state, limit, &Budget::EXPLORE) {
                self.exit = Some(found);
            }
        }
        self.t0 = t0;
        self.current = next;
        Ok(())
    }

    fn current(&self) -> &SubStep {
        let [a, b] = &self.steps;
        if self.current == 0 { a } else { b }
    }
}

impl SegmentSolver for ExprbContact {
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let (slip, time, state) = (at.slip, at.time, at.state);
        self.time_carry = 0.0;
        self.slip = slip;
        if slip != 0.0 {
            self.slip_offset = SlipVelocity::start_offset(&self.params, time, &state, slip);
            self.slip_scale = SlipVelocity::scale_at(&self.params, &state);
        }
        self.sub_step(time, state)
    }

    fn locate(&mut self, target: f64) -> Located {
        let step = self.current();
        let s_target = target - self.t0;
        if let Some((s, state, kind)) = self.exit.filter(|(s, _, _)| *s <= s_target) {
            return Located::Switch(Event {
                time: self.t0 + s,
                kind,
                state,
            });
        }
        if s_target <= step.length {
            Located::Reached(if s_target == step.length {
                step.end
            } else {
                step.segment.point(s_target).state
            })
        } else {
            Located::NeedStep
        }
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        let step = self.current();
        let (length, state) = (step.length, step.end);
        // Kahan summation of the sub-step lengths.
        let y = length - self.time_carry;
        let t_next = self.t0 + y;
        self.time_carry = (t_next - self.t0) - y;
        self.sub_step(t_next, state)
    }

    fn computed_to(&self) -> f64 {
        self.t0 + self.current().length
    }
}

/// The piecewise-analytical method (see [`crate::Method::Analytic`]).
pub struct AnalyticPropagator(
    Piecewise<ByRegime<FreeFlightSolver, ExprbContact, ReferenceSolver<Dop853>>>,
);

impl AnalyticPropagator {
    /// Start the analytic method. `tol` drives exprb43's step control (never below the rounding
    /// its sub-steps add, 4ε times the contact frequency, `docs/MODEL.md` §8); `fixed_step`
    /// fixes the contact sub-step (exprb2 defaults to [`DEFAULT_EXPRB2_STEP`]).
    ///
    /// # Errors
    /// [`PropagationError::InvalidProblem`], or [`PropagationError::InvalidOption`] for a `tol`
    /// or `fixed_step` outside its range ([`MethodInfo::tolerance_range`], [`crate::registration::STEP_RANGE`]).
    pub fn new(
        problem: &Problem,
        scheme: ContactScheme,
        tol: f64,
        fixed_step: Option<f64>,
    ) -> Result<Self, PropagationError> {
        problem.validate()?;
        Self::start(problem, scheme, tol, fixed_step)
    }

    /// As [`AnalyticPropagator::new`] without checking the problem (see
    /// [`Registered::resume`]).
    fn start(
        problem: &Problem,
        scheme: ContactScheme,
        tol: f64,
        fixed_step: Option<f64>,
    ) -> Result<Self, PropagationError> {
        Self::INFO.check_tolerance(tol)?;
        if let Some(step) = fixed_step {
            Self::INFO.check_step(step)?;
        }
        let params = problem.params;
        let t0 = problem.start_time;
        Piecewise::new(problem, None, |at| {
            let (regime, s0) = (at.regime, at.state);
            let mut solvers = ByRegime {
                free: FreeFlightSolver::new(&params, t0, s0),
                contact: ExprbContact::new(&params, scheme, tol, fixed_step),
                // Rolling has no known closed form (`docs/MODEL.md` §10): DOP853 at the
                // method's tolerance, started by the driver at the first roll unless the run
                // starts rolling.
                rolling: if regime == Regime::Rolling {
                    ReferenceSolver::new(params, Regime::Rolling, 0.0, t0, s0, tol)
                } else {
                    ReferenceSolver::unstarted(params, Regime::Rolling, t0, s0, tol)
                },
            };
            if regime == Regime::Contact {
                solvers.contact.start(at)?;
            }
            Ok(solvers)
        })
        .map(AnalyticPropagator)
    }
}

impl Registered for AnalyticPropagator {
    const INFO: MethodInfo = MethodInfo {
        name: "analytic",
        description: "piecewise closed form: exact free flight, re-linearized closed-form contact (exprb43 or exprb2)",
        default_tolerance: super::DEFAULT_TOLERANCE,
        tolerance_range: ValidRange {
            min: 1e-14,
            max: 1e-3,
        },
        numerical_reference: false,
        contact_scheme: true,
    };

    fn build(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
        AnalyticPropagator::new(
            problem,
            settings.contact_scheme,
            settings.tol,
            settings.step,
        )
    }

    fn resume(problem: &Problem, settings: &Settings) -> Result<Self, PropagationError> {
        AnalyticPropagator::start(
            problem,
            settings.contact_scheme,
            settings.tol,
            settings.step,
        )
    }
}

crate::driver::propagate_through_driver!(AnalyticPropagator);
