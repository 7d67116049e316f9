//! The hybrid method (`model.md` §8): exact closed-form free flight, adaptive DOP853 on the
//! nonlinear contact field inside contact, exits located on DOP853's dense output and free flight
//! restarted there. The forcing is carried through contact as a rotating phasor (two extra
//! states, c' = −ηs, s' = ηc), so the contact right-hand side needs no trigonometry.
//!
//! Tolerance semantics: free flight is exact (rounding only); in contact `tol` is DOP853's
//! relative and absolute tolerance per step, as for [`crate::Method::Dop853`].

use crate::analytic::free::FreeConstants;
use crate::analytic::free_flight::{FreeAdvance, FreeFlight};
use crate::field;
use crate::params::{Params, Problem, State};
use crate::propagate::{
    Event, EventKind, Propagate, PropagationError, Regime, check_target, within_bounds,
};
use crate::reference::{
    BASE_STEP_BUDGET, Dop853, Dop853Dense, Dop853Step, Integrator, Interpolant, MIN_TOLERANCE,
    PhasorRotorSystem, STEPS_PER_TIME_UNIT, SUBDIVISIONS, Tolerance, switch_in_deferred_step,
};

#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
enum Piece {
    Free(FreeFlight),
    /// In contact; the current step (if any) is [`HybridPropagator::step`].
    Contact {
        stepped: bool,
        exit: Option<(f64, [f64; 6])>,
    },
}

/// The hybrid method (see [`crate::Method::Hybrid`]).
///
/// Work in contact, per accepted DOP853 step: the 12 stages of the step and f at its end (the
/// next step's first stage). The dense output (three more evaluations) is built only for a step
/// that holds an exit, a minimum of z, or a requested time: the exit test examines the switching
/// function on sub-intervals no longer than those of the reference propagators
/// (h_max / [`SUBDIVISIONS`]), which for contact steps (much shorter than h_max) is the step
/// itself, given by its exact end states. Each contact after the first starts with the step size
/// the previous contact ended with, instead of a fresh initial guess.
pub struct HybridPropagator {
    params: Params,
    free: FreeConstants,
    contact: PhasorRotorSystem,
    integrator: Integrator<Dop853, 6>,
    h_max: f64,
    /// The step size proposed at the end of the last contact.
    carried_step: Option<f64>,
    step: Dop853Step<6>,
    dense: Option<Dop853Dense<6>>,
    time: f64,
    state: State,
    piece: Piece,
}

impl HybridPropagator {
    /// Validate `problem` and `tol` (finite, ≥ 1e-14) and start at the problem's start time.
    pub fn new(problem: &Problem, tol: f64) -> Result<Self, PropagationError> {
        problem.validate()?;
        if !(tol.is_finite() && (MIN_TOLERANCE..=1.0).contains(&tol)) {
            return Err(PropagationError::InvalidOption {
                what: "tol",
                value: tol,
            });
        }
        let params = problem.params;
        let contact = PhasorRotorSystem {
            params,
            regime: Regime::Contact,
        };
        let (t0, s0) = (problem.start_time, problem.initial);
        // A quarter of the shorter of the forcing period and 2π, as the reference integrators.
        let h_max = 0.25 * params.forcing_period().min(core::f64::consts::TAU);
        let integrator = Integrator::new(
            &contact,
            t0,
            PhasorRotorSystem::initial(&params, t0, &s0),
            Tolerance::uniform(tol),
            h_max,
        );
        let free = FreeConstants::new(&params);
        let piece = match field::regime_of(&params, t0, &s0) {
            Regime::Free => Piece::Free(FreeFlight::new(&params, &free, t0, s0)),
            Regime::Contact => Piece::Contact {
                stepped: false,
                exit: None,
            },
        };
        Ok(HybridPropagator {
            params,
            free,
            contact,
            integrator,
            h_max,
            carried_step: None,
            step: Dop853Step::default(),
            dense: None,
            time: t0,
            state: s0,
            piece,
        })
    }

    fn enter_contact(&mut self, time: f64, state: State) {
        let y = PhasorRotorSystem::initial(&self.params, time, &state);
        match self.carried_step {
            Some(h) => self.integrator.restart_with_step(&self.contact, time, y, h),
            None => self.integrator.restart(&self.contact, time, y),
        }
        self.piece = Piece::Contact {
            stepped: false,
            exit: None,
        };
    }

    /// One DOP853 step in contact into `self.step`, with the exit inside it if any.
    fn contact_step(&mut self) -> Result<Option<(f64, [f64; 6])>, PropagationError> {
        self.dense = None;
        self.integrator
            .step_deferred(&self.contact, f64::INFINITY, &mut self.step)?;
        let end = PhasorRotorSystem::rotor_state(&self.step.y1);
        if !within_bounds(&end) {
            return Err(PropagationError::Diverged {
                time: self.step.t1,
                state: end,
            });
        }
        // Sub-intervals no longer than the reference propagators' shortest (h_max / 8).
        let ratio = (self.step.t1 - self.step.t0) / self.h_max * SUBDIVISIONS as f64;
        let subdivisions = if ratio <= 1.0 {
            1
        } else {
            (libm::ceil(ratio) as usize).min(SUBDIVISIONS)
        };
        Ok(switch_in_deferred_step(
            &mut self.integrator,
            &self.contact,
            &self.step,
            &self.params,
            Regime::Contact,
            subdivisions,
            &mut self.dense,
        ))
    }

    /// The state at `t` inside the current contact step (from its dense output).
    fn contact_state(&mut self, t: f64) -> State {
        let y = if t == self.step.t1 {
            self.step.y1
        } else {
            let dense = match self.dense {
                Some(d) => d,
                None => {
                    let d = self.step.dense(&self.contact);
                    self.dense = Some(d);
                    d
                }
            };
            dense.eval(t)
        };
        PhasorRotorSystem::rotor_state(&y)
    }
}

impl Propagate for HybridPropagator {
    fn time(&self) -> f64 {
        self.time
    }

    fn state(&self) -> State {
        self.state
    }

    fn regime(&self) -> Regime {
        match self.piece {
            Piece::Free(_) => Regime::Free,
            Piece::Contact { .. } => Regime::Contact,
        }
    }

    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        if !check_target(target, self.time)? {
            return Ok(None);
        }
        let budget = BASE_STEP_BUDGET + STEPS_PER_TIME_UNIT * (target - self.time);
        let mut steps = 0.0;
        loop {
            match &mut self.piece {
                Piece::Free(flight) => match flight.advance(target) {
                    FreeAdvance::Reached(state) => {
                        self.time = target;
                        self.state = state;
                        return Ok(None);
                    }
                    FreeAdvance::Contact { time, state } => {
                        self.enter_contact(time, state);
                        self.time = time;
                        self.state = state;
                        return Ok(Some(Event {
                            time,
                            kind: EventKind::Enter,
                            state,
                        }));
                    }
                },
                Piece::Contact { stepped, exit } => {
                    if let Some((t, y)) = exit.filter(|(t, _)| *t <= target) {
                        let state = PhasorRotorSystem::rotor_state(&y);
                        self.carried_step = Some(self.integrator.proposed_step());
                        self.piece =
                            Piece::Free(FreeFlight::new(&self.params, &self.free, t, state));
                        self.time = t;
                        self.state = state;
                        return Ok(Some(Event {
                            time: t,
                            kind: EventKind::Exit,
                            state,
                        }));
                    }
                    if *stepped && target <= self.step.t1 {
                        self.state = self.contact_state(target);
                        self.time = target;
                        return Ok(None);
                    }
                    if steps >= budget {
                        return Err(PropagationError::StepSizeUnderflow {
                            time: self.integrator.time(),
                        });
                    }
                    steps += 1.0;
                    let new_exit = self.contact_step()?;
                    self.piece = Piece::Contact {
                        stepped: true,
                        exit: new_exit,
                    };
                }
            }
        }
    }
}
