//! The fixed-step stepper of a rotor from matrices ([`MatrixStepper`], `docs/MODEL.md` §17):
//! the stator ring with mass (its n = 4 instance, [`super::RingStepper`]) and any model of
//! n ≤ CAP/2 degrees of freedom, in const-generic storage, no heap, no panic.
//!
//! # How a step is taken
//! The stepper holds one [`MatrixPropagator`] of the configured method (default `taylor` at its
//! default tolerance: exact free flight of rotor and ring, contact and rolling by the Taylor
//! series of the generated station law — the most accurate of the fast methods, its switch
//! times agree with the 30-digit reference to ~1e-14, and it needs no dense-output
//! interpolation between the steps; `hybrid` is the other fast choice). A step of `dt` asks
//! the propagator for the time anchor + k·dt (no drift: the time is re-derived from the anchor
//! at each step, as the planar stepper's); every switch on the way is located by the method's
//! own search (z = |d| with both bodies moving, grazing included — the same guarantee as a
//! variable-step run) and reported in the step's [`MatrixEvents`]. Between switches the method
//! takes its own steps inside `dt`: the states at k·dt are the samples of a variable-step run
//! at those times.
//!
//! # Worst-case work per step
//! At most [`MatrixStepperConfig::max_switches`] switches per step, and per stretch between two
//! switches at most the propagator's step budget (`REFERENCE_BUDGET`: a base plus a count per
//! unit of time of integration steps; exact free flight costs one closed-form evaluation per
//! search chunk). A step that would need more switches is refused with
//! [`StepperError::BudgetExceeded`], a stretch that would need more integration steps with
//! [`crate::PropagationError::StepSizeUnderflow`]; in both cases, and on any other error, the
//! stepper goes back to the step's start time and state, its method restarted there on the
//! side it was on (the regime and slip direction kept, [`MatrixPropagator::resume`]; a new
//! free-flight decomposition, paid on failure only: copying the propagator before every step
//! instead would be 60–75 % of a step's cost; stepping on agrees with an uninterrupted run
//! within the method's tolerance). There is no degraded mode: a shorter step gets through.
//!
//! Measured (`dt` = 1e-3, the paper's rotor with m̂ = 1, k̂_c = 100, ĉ = 0.5, on a loaded
//! 2-core machine): 1.1–1.5 µs per step on average for taylor and hybrid alike, heavy or
//! sparse rub; the stepper is 39 KiB (the ring model and the method's solvers inline).
//!
//! # Inputs between steps
//! [`MatrixStepper::set_input`] (the input force, held until the next call) and
//! [`MatrixStepper::set_model`] (a new statement: a new speed, stiffness, …) re-state the model
//! and restart the propagator at the current time and state (a new free-flight decomposition:
//! the cost of building the stepper); [`MatrixStepper::snapshot`] and
//! [`MatrixStepper::restore`] roll back.

use core::ops::Deref;

use super::MAX_STEP;
use super::report::{EventList, StepperError};
use crate::driver::SegmentStart;
use crate::matrix::{MatrixModel, MatrixPropagator, MatrixState};
use crate::method::{Method, Options};
use crate::propagate::{Event, EventKind, Propagate, PropagationError, Regime};

/// Largest accepted [`MatrixStepperConfig::max_switches`].
pub const MAX_SWITCHES: u32 = 1024;

/// A matrix model held by value: the stepper that holds it is self-contained (plain memory, no
/// heap, no borrow), so it can live in a caller's block (the C ABI) or be copied whole. Each of
/// the method's solvers holds its own copy.
#[derive(Clone, Debug)]
pub struct OwnedModel<const CAP: usize>(pub MatrixModel<CAP>);

impl<const CAP: usize> Deref for OwnedModel<CAP> {
    type Target = MatrixModel<CAP>;

    fn deref(&self) -> &MatrixModel<CAP> {
        &self.0
    }
}

/// How the matrix stepper takes its steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixStepperConfig {
    /// The step length the stepper expects (any `dt` in (0, [`MAX_STEP`]] may be stepped;
    /// a new length re-anchors the time).
    pub dt: f64,
    /// The method that locates the switches and integrates between them (default
    /// [`Method::Taylor`]).
    pub method: Method,
    /// Its tolerance (`None`: the method's default).
    pub tol: Option<f64>,
    /// Cap on switches inside one step (1 ..= [`MAX_SWITCHES`]): a step that holds more is
    /// refused ([`StepperError::BudgetExceeded`]), the stepper back at the step's start.
    pub max_switches: u32,
}

impl Default for MatrixStepperConfig {
    /// dt = 1e-3, taylor at its default tolerance, at most 64 switches per step.
    fn default() -> Self {
        MatrixStepperConfig {
            dt: 1e-3,
            method: Method::Taylor,
            tol: None,
            max_switches: 64,
        }
    }
}

impl MatrixStepperConfig {
    /// The default configuration with step length `dt`.
    pub fn with_dt(dt: f64) -> Self {
        MatrixStepperConfig {
            dt,
            ..MatrixStepperConfig::default()
        }
    }

    /// The propagator's options.
    pub fn options(&self) -> Options {
        Options {
            tol: self.tol,
            ..Options::with_method(self.method)
        }
    }

    fn validate(&self) -> Result<(), StepperError> {
        if !(1..=MAX_SWITCHES).contains(&self.max_switches) {
            return Err(StepperError::InvalidConfig {
                what: "max_switches",
                value: f64::from(self.max_switches),
            });
        }
        if !(self.dt > 0.0 && self.dt <= MAX_STEP) {
            return Err(StepperError::InvalidConfig {
                what: "dt",
                value: self.dt,
            });
        }
        Ok(())
    }
}

/// The switches inside one matrix step, in time order (the planar stepper's list over the
/// model's state).
pub type MatrixEvents<const CAP: usize> = EventList<MatrixState<CAP>>;

impl<const CAP: usize> Default for MatrixEvents<CAP> {
    fn default() -> Self {
        EventList::empty(Event {
            time: 0.0,
            kind: EventKind::Enter,
            state: MatrixState::full([0.0; CAP]),
        })
    }
}

/// The result of one [`MatrixStepper::step`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixStepReport<const CAP: usize> {
    /// The time at the step end.
    pub time: f64,
    /// The state y = (q, q') at the step end.
    pub state: MatrixState<CAP>,
    /// The regime at the step end.
    pub regime: Regime,
    /// The switches inside the step, (t0, t0 + dt].
    pub events: MatrixEvents<CAP>,
}

/// The fixed-step stepper of a rotor from matrices (see the module docs). `M` holds the model:
/// [`OwnedModel`] for a self-contained stepper, or any shared pointer (`Arc`, `&`).
#[derive(Clone)]
pub struct MatrixStepper<M: crate::driver::System, const CAP: usize> {
    model: M,
    config: MatrixStepperConfig,
    propagator: MatrixPropagator<M, CAP>,
    /// The step length of the current anchor.
    dt: f64,
    anchor_time: f64,
    anchor_steps: u64,
}

impl<M, const CAP: usize> MatrixStepper<M, CAP>
where
    M: Deref<Target = MatrixModel<CAP>> + Clone,
{
    /// The configured method started on `model` at `(time, start)`, the configuration checked
    /// first ([`StepperError::InvalidConfig`]); the start is the propagator's to refuse
    /// ([`MatrixPropagator::new`]: its regime decided as by every method).
    pub fn new(
        model: M,
        time: f64,
        start: MatrixState<CAP>,
        config: MatrixStepperConfig,
    ) -> Result<Self, StepperError> {
        config.validate()?;
        let propagator = MatrixPropagator::new(model.clone(), time, start, &config.options())?;
        Ok(Self::with(model, config, propagator))
    }

    /// As [`MatrixStepper::new`], continuing a run at `at` on the side it was on
    /// ([`MatrixPropagator::resume`]: the regime and slip direction given, not decided afresh;
    /// a stepper's saved words).
    pub fn resume(
        model: M,
        at: SegmentStart<MatrixState<CAP>>,
        config: MatrixStepperConfig,
    ) -> Result<Self, StepperError> {
        config.validate()?;
        let propagator = MatrixPropagator::resume(model.clone(), at, &config.options())?;
        Ok(Self::with(model, config, propagator))
    }

    fn with(model: M, config: MatrixStepperConfig, propagator: MatrixPropagator<M, CAP>) -> Self {
        let time = propagator.time();
        MatrixStepper {
            model,
            config,
            propagator,
            dt: config.dt,
            anchor_time: time,
            anchor_steps: 0,
        }
    }

    /// Advance exactly `dt` (finite, in (0, [`MAX_STEP`]]): the end state and regime and the
    /// switches in (t, t + dt]. On error the stepper is back at the step's start time and state
    /// (its method restarted there, see the module docs).
    ///
    /// # Errors
    /// [`StepperError::InvalidStep`], [`StepperError::BudgetExceeded`] (more than
    /// `max_switches` switches), or the propagation's error (divergence, step budget).
    pub fn step(&mut self, dt: f64) -> Result<MatrixStepReport<CAP>, StepperError> {
        self.advance(dt, false)
    }

    /// As [`MatrixStepper::step`], but the step ends at the first switch inside it, if any
    /// (an importer's early return): the report's time and state are the switch's.
    ///
    /// # Errors
    /// As [`MatrixStepper::step`].
    pub fn step_to_switch(&mut self, dt: f64) -> Result<MatrixStepReport<CAP>, StepperError> {
        self.advance(dt, true)
    }

    fn advance(
        &mut self,
        dt: f64,
        stop_at_switch: bool,
    ) -> Result<MatrixStepReport<CAP>, StepperError> {
        let time = self.propagator.time();
        if !(dt > 0.0 && dt <= MAX_STEP && time + dt > time) {
            return Err(StepperError::InvalidStep { dt, time });
        }
        let (anchor_time, anchor_steps) = if dt == self.dt {
            (self.anchor_time, self.anchor_steps + 1)
        } else {
            (time, 1)
        };
        let target = (anchor_time + anchor_steps as f64 * dt).max(time);
        // No copy of the propagator per step (it would be 60–75 % of a step's cost): a failed
        // step restarts the method at the step's start, on the side it was on, instead.
        let start = SegmentStart {
            regime: self.propagator.regime(),
            slip: self.propagator.slip(),
            time,
            state: self.propagator.state(),
        };
        let mut events = MatrixEvents::default();
        let stopped = loop {
            match self.propagator.advance(target) {
                Ok(None) => break false,
                Ok(Some(event)) => {
                    events.push(event);
                    if stop_at_switch {
                        break true;
                    }
                    let switches = u32::try_from(events.total()).unwrap_or(u32::MAX);
                    if switches >= self.config.max_switches && self.propagator.time() < target {
                        self.restart(start);
                        return Err(StepperError::BudgetExceeded {
                            time,
                            substeps: switches,
                        });
                    }
                }
                Err(e) => {
                    self.restart(start);
                    return Err(e.into());
                }
            }
        };
        if stopped {
            // Re-anchored at the switch: the next step of `dt` ends at switch + dt.
            self.anchor_time = self.propagator.time();
            self.anchor_steps = 0;
        } else {
            self.anchor_time = anchor_time;
            self.anchor_steps = anchor_steps;
        }
        self.dt = dt;
        Ok(MatrixStepReport {
            time: self.propagator.time(),
            state: self.propagator.state(),
            regime: self.propagator.regime(),
            events,
        })
    }

    /// Back to `start` after a failed step: the method restarted there on the side it was on
    /// ([`MatrixPropagator::resume`]; the time anchor was not moved). A start the method
    /// refuses (it was the method's own position: not expected) leaves the propagator as it is.
    #[cold]
    fn restart(&mut self, start: SegmentStart<MatrixState<CAP>>) {
        if let Ok(p) = MatrixPropagator::resume(self.model.clone(), start, &self.config.options()) {
            self.propagator = p;
        }
    }

    /// Replace the input force (n entries, or empty for none) from the current time on:
    /// the model is re-stated and the method restarted at the current state. On error nothing
    /// changes.
    ///
    /// # Errors
    /// [`PropagationError::InvalidModel`] for a force of the wrong size or not finite, or what
    /// the restart reports.
    pub fn set_input(&mut self, input: &[f64]) -> Result<(), StepperError>
    where
        M: DerefMutModel<CAP>,
    {
        let mut model = self.model.clone();
        model
            .model_mut()
            .set_input(input)
            .map_err(PropagationError::from)?;
        self.set_model(model)
    }

    /// Re-state the model from the current time on (a new speed, stiffness, friction, …; the
    /// same number of degrees of freedom): the method restarts at the current time and state,
    /// the regime decided afresh there (no event is reported for a change). On error nothing
    /// changes.
    ///
    /// # Errors
    /// What [`MatrixPropagator::new`] reports for the new model at the current state.
    pub fn set_model(&mut self, model: M) -> Result<(), StepperError> {
        let time = self.propagator.time();
        let state = self.propagator.state();
        let propagator = MatrixPropagator::new(model.clone(), time, state, &self.config.options())?;
        self.model = model;
        self.propagator = propagator;
        self.anchor_time = time;
        self.anchor_steps = 0;
        Ok(())
    }

    /// The stepper as it is now, to [`MatrixStepper::restore`] later (a copy: plain memory).
    pub fn snapshot(&self) -> Self {
        self.clone()
    }

    /// Go back to `snapshot` (taken of this stepper or another of the same model size).
    pub fn restore(&mut self, snapshot: &Self) {
        self.clone_from(snapshot);
    }

    /// The current time.
    pub fn time(&self) -> f64 {
        self.propagator.time()
    }

    /// The state y = (q, q') at [`MatrixStepper::time`].
    pub fn state(&self) -> MatrixState<CAP> {
        self.propagator.state()
    }

    /// The regime at [`MatrixStepper::time`].
    pub fn regime(&self) -> Regime {
        self.propagator.regime()
    }

    /// The slip direction σ of the current contact segment ([`MatrixPropagator::slip`]).
    pub fn slip(&self) -> f64 {
        self.propagator.slip()
    }

    /// The model in force.
    pub fn model(&self) -> &MatrixModel<CAP> {
        &self.model
    }

    /// The configuration.
    pub fn config(&self) -> &MatrixStepperConfig {
        &self.config
    }

    /// The step length of the current time anchor (the last stepped, or the config's).
    pub fn current_dt(&self) -> f64 {
        self.dt
    }

    /// The time anchor: (step length, anchor time, steps since): the time is anchor + steps·dt.
    pub fn anchor(&self) -> (f64, f64, u64) {
        (self.dt, self.anchor_time, self.anchor_steps)
    }

    /// Set the time anchor (a stepper resumed from saved words; dt in (0, [`MAX_STEP`]], the
    /// time finite).
    ///
    /// # Errors
    /// [`StepperError::InvalidStep`] for an anchor that is not finite or a dt out of range.
    pub fn set_anchor(&mut self, dt: f64, time: f64, steps: u64) -> Result<(), StepperError> {
        if !(dt > 0.0 && dt <= MAX_STEP && time.is_finite()) {
            return Err(StepperError::InvalidStep { dt, time });
        }
        (self.dt, self.anchor_time, self.anchor_steps) = (dt, time, steps);
        Ok(())
    }
}

/// A model holder whose statement can be changed in place (a new input force): [`OwnedModel`].
pub trait DerefMutModel<const CAP: usize> {
    /// The statement, mutable.
    fn model_mut(&mut self) -> &mut MatrixModel<CAP>;
}

impl<const CAP: usize> DerefMutModel<CAP> for OwnedModel<CAP> {
    fn model_mut(&mut self) -> &mut MatrixModel<CAP> {
        &mut self.0
    }
}
