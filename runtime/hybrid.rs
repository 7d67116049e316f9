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
use crate::math;
use crate::params::{Params, Problem, State};
use crate::propagate::{DIVERGENCE_RADIUS, Event, EventKind, Propagate, PropagationError, Regime};
use crate::reference::{
    AcceptedStep, BASE_STEP_BUDGET, Dop853, Dop853Dense, Integrator, Interpolant, MIN_TOLERANCE,
    PhasorRotorSystem, STEPS_PER_TIME_UNIT, Tolerance, switch_in_step,
};

type Step = AcceptedStep<6, Dop853Dense<6>>;
/// A switch inside a step: time and 6-state.
type Switch = (f64, [f64; 6]);

#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
enum Piece {
    Free(FreeFlight),
    Contact {
        step: Option<Step>,
        exit: Option<Switch>,
    },
}

/// The hybrid method (see [`crate::Method::Hybrid`]).
pub struct HybridPropagator {
    params: Params,
    free: FreeConstants,
    contact: PhasorRotorSystem,
    integrator: Integrator<Dop853, 6>,
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
                step: None,
                exit: None,
            },
        };
        Ok(HybridPropagator {
            params,
            free,
            contact,
            integrator,
            time: t0,
            state: s0,
            piece,
        })
    }

    fn enter_contact(&mut self, time: f64, state: State) {
        let y = PhasorRotorSystem::initial(&self.params, time, &state);
        self.integrator.restart(&self.contact, time, y);
        self.piece = Piece::Contact {
            step: None,
            exit: None,
        };
    }

    /// One DOP853 step in contact, with the exit inside it if any.
    fn contact_step(&mut self) -> Result<(Step, Option<Switch>), PropagationError> {
        let step = self.integrator.step(&self.contact, f64::INFINITY)?;
        let end = PhasorRotorSystem::rotor_state(&step.y1);
        if !end.is_finite() || math::hypot(end.x, end.y) > DIVERGENCE_RADIUS {
            return Err(PropagationError::Diverged {
                time: step.t1,
                state: end,
            });
        }
        let exit = switch_in_step(
            &mut self.integrator,
            &self.contact,
            &step,
            &self.params,
            Regime::Contact,
        );
        Ok((step, exit))
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
        if !(target.is_finite() && target >= self.time) {
            return Err(PropagationError::InvalidTarget {
                target,
                current: self.time,
            });
        }
        if target == self.time {
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
                Piece::Contact { step, exit } => {
                    if let Some((t, y)) = exit.filter(|(t, _)| *t <= target) {
                        let state = PhasorRotorSystem::rotor_state(&y);
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
                    if let Some(s) = step.as_ref().filter(|s| target <= s.t1) {
                        let y = if target == s.t1 {
                            s.y1
                        } else {
                            s.dense.eval(target)
                        };
                        self.time = target;
                        self.state = PhasorRotorSystem::rotor_state(&y);
                        return Ok(None);
                    }
                    if steps >= budget {
                        return Err(PropagationError::StepSizeUnderflow {
                            time: self.integrator.time(),
                        });
                    }
                    steps += 1.0;
                    let (new_step, new_exit) = self.contact_step()?;
                    self.piece = Piece::Contact {
                        step: Some(new_step),
                        exit: new_exit,
                    };
                }
            }
        }
    }
}
