//! The stator ring with mass in fixed steps (issue 28, `docs/MODEL.md` §17): [`RingStepper`]
//! runs the ring's n = 4 matrix model ([`crate::matrix::ring_model`]) with the
//! [`MatrixStepper`], keeping the parameter table's names for its inputs. The stepper a caller
//! builds from any problem is [`super::AnyStepper`] (`any.rs`).

use super::inputs::at_speed;
use super::matrix::{MatrixStepReport, MatrixStepper, MatrixStepperConfig, OwnedModel};
use super::{StepReport, StepperConfig, StepperError};
use crate::matrix::{RING_CAPACITY, ring_model, ring_start};
use crate::params::{ParamError, Parameter, Params, Problem, Range, State};
use crate::propagate::{Event, PropagationError, Regime};

/// The ring's state: centre (x_s, y_s) and its velocity, clearances and clearances per τ.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RingState {
    /// x_s.
    pub xs: f64,
    /// y_s.
    pub ys: f64,
    /// x_s'.
    pub vxs: f64,
    /// y_s'.
    pub vys: f64,
}

/// The ring model's stepper (`stator_mass_ratio` > 0): a [`MatrixStepper`] of the ring model
/// with the parameters it was stated from. Plain memory (no heap): it can live in a caller's
/// block.
#[derive(Clone)]
pub struct RingStepper {
    params: Params,
    inner: MatrixStepper<OwnedModel<RING_CAPACITY>, RING_CAPACITY>,
}

/// Refuse m̂ = 0 where the ring's stepper runs (the planar [`Stepper`] runs it).
pub(super) fn check_ring(params: &Params) -> Result<(), StepperError> {
    if params.stator_mass_ratio > 0.0 {
        Ok(())
    } else {
        // The ring's stepper's range of m̂ (0 is the planar stepper's, and a running stepper
        // does not change between the two).
        let table = Parameter::StatorMassRatio.range();
        Err(ParamError::OutOfRange {
            parameter: Parameter::StatorMassRatio,
            value: params.stator_mass_ratio,
            range: Range::above(0.0, table.max),
        }
        .into())
    }
}

pub(super) fn state_model(params: &Params) -> Result<OwnedModel<RING_CAPACITY>, StepperError> {
    Ok(OwnedModel(
        ring_model(params).map_err(PropagationError::from)?,
    ))
}

impl RingStepper {
    /// Validate `problem` (m̂ > 0) and `config`, state the ring model and start the method at
    /// the problem's start: the rotor's initial state and the ring's (`xs0` … `vys0`).
    ///
    /// # Errors
    /// The parameter's [`ParamError`] (for m̂ = 0: out of the ring stepper's range (0, 1e3]),
    /// [`StepperError::InvalidConfig`] for the configuration, or what [`MatrixStepper::new`]
    /// reports.
    pub fn new(problem: &Problem, config: MatrixStepperConfig) -> Result<Self, StepperError> {
        problem.validate()?;
        check_ring(&problem.params)?;
        let model = state_model(&problem.params)?;
        let inner = MatrixStepper::new(model, problem.start_time, ring_start(problem), config)?;
        Ok(RingStepper {
            params: problem.params,
            inner,
        })
    }

    /// Advance exactly `dt` ([`MatrixStepper::step`]): the state is y = (x, y, x_s, y_s, x',
    /// y', x_s', y_s').
    ///
    /// # Errors
    /// As [`MatrixStepper::step`]; the stepper is then back at the step's start.
    pub fn step(&mut self, dt: f64) -> Result<MatrixStepReport<RING_CAPACITY>, StepperError> {
        self.inner.step(dt)
    }

    /// As [`RingStepper::step`], ending at the first switch inside the step.
    ///
    /// # Errors
    /// As [`MatrixStepper::step`].
    pub fn step_to_switch(
        &mut self,
        dt: f64,
    ) -> Result<MatrixStepReport<RING_CAPACITY>, StepperError> {
        self.inner.step_to_switch(dt)
    }

    /// Replace the parameters from the current time on (m̂ stays > 0): the ring model is
    /// re-stated and the method restarted at the current state. On error nothing changes.
    ///
    /// # Errors
    /// The parameter's error (m̂ = 0 included, [`ParamError::OutOfRange`]).
    pub fn set_params(&mut self, params: &Params) -> Result<(), StepperError> {
        params.validate()?;
        check_ring(params)?;
        let model = state_model(params)?;
        self.inner.set_model(model)?;
        self.params = *params;
        Ok(())
    }

    /// The input force u = (`fx`, `fy`) on the rotor from the current time on (each in its
    /// table range): the model re-stated ([`RingStepper::set_params`]) when it changes.
    ///
    /// # Errors
    /// The parameter's range error; nothing changes.
    pub fn set_input_force(&mut self, fx: f64, fy: f64) -> Result<(), StepperError> {
        Parameter::ForceX.check(fx)?;
        Parameter::ForceY.check(fy)?;
        if (fx, fy) == (self.params.force_x, self.params.force_y) {
            return Ok(());
        }
        self.set_params(&Params {
            force_x: fx,
            force_y: fy,
            ..self.params
        })
    }

    /// The input force in force.
    pub fn input_force(&self) -> (f64, f64) {
        (self.params.force_x, self.params.force_y)
    }

    /// The running speed η from the current time on with the forcing phase continuous (φ0
    /// re-based, as [`super::Stepper::set_speed_ratio`]); the ring model is re-stated at the new
    /// speed.
    ///
    /// # Errors
    /// η not finite or out of range; nothing changes.
    pub fn set_speed_ratio(&mut self, eta: f64) -> Result<(), StepperError> {
        match at_speed(&self.params, self.time(), eta)? {
            Some(params) => self.set_params(&params),
            None => Ok(()),
        }
    }

    /// The stepper as it is now (a copy), to [`RingStepper::restore`] later.
    pub fn snapshot(&self) -> RingStepper {
        self.clone()
    }

    /// Go back to `snapshot`.
    pub fn restore(&mut self, snapshot: &RingStepper) {
        self.clone_from(snapshot);
    }

    /// The current time τ.
    pub fn time(&self) -> f64 {
        self.inner.time()
    }

    /// The regime at [`RingStepper::time`].
    pub fn regime(&self) -> Regime {
        self.inner.regime()
    }

    /// The whole state y = (x, y, x_s, y_s, x', y', x_s', y_s').
    pub fn full_state(&self) -> [f64; RING_CAPACITY] {
        *self.inner.state().array()
    }

    /// The rotor's state (x, y, x', y').
    pub fn state(&self) -> State {
        rotor_of(&self.full_state())
    }

    /// The ring's state (x_s, y_s, x_s', y_s').
    pub fn ring_state(&self) -> RingState {
        ring_of(&self.full_state())
    }

    /// The parameters in force.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The slip direction σ of a slipping contact under friction (±1; 0 when free, rolling
    /// or frictionless): the one the propagator's contact segment runs with, decided by the
    /// model's rule at the segment's start (after a `reverse` from λ: w's own sign there is
    /// rounding, so σ is not read back from the state).
    pub fn slip_direction(&self) -> f64 {
        if self.regime() != Regime::Contact {
            return 0.0;
        }
        self.inner.slip()
    }

    /// Build from its parts (words read back, `ring_words.rs`).
    pub(super) fn from_parts(
        params: Params,
        inner: MatrixStepper<OwnedModel<RING_CAPACITY>, RING_CAPACITY>,
    ) -> Self {
        RingStepper { params, inner }
    }

    /// The underlying matrix stepper.
    pub fn matrix(&self) -> &MatrixStepper<OwnedModel<RING_CAPACITY>, RING_CAPACITY> {
        &self.inner
    }
}

impl core::fmt::Debug for RingStepper {
    /// The time, regime and state (the model and the method's solvers are not listed).
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("RingStepper")
            .field("time", &self.time())
            .field("regime", &self.regime())
            .field("state", &self.full_state())
            .field("config", self.inner.config())
            .finish_non_exhaustive()
    }
}

/// The rotor's (x, y, x', y') of a ring state y.
pub fn rotor_of(y: &[f64; RING_CAPACITY]) -> State {
    let [x, yy, _, _, vx, vy, _, _] = *y;
    State::new(x, yy, vx, vy)
}

/// The ring's (x_s, y_s, x_s', y_s') of a ring state y.
pub fn ring_of(y: &[f64; RING_CAPACITY]) -> RingState {
    let [_, _, xs, ys, _, _, vxs, vys] = *y;
    RingState { xs, ys, vxs, vys }
}

/// A ring step's report in the planar vocabulary: the rotor's state at the end and at each
/// switch (the ring's are in the [`MatrixStepReport`]); no sub-steps, no degraded cap.
pub fn rotor_report(report: &MatrixStepReport<RING_CAPACITY>) -> StepReport {
    let mut events = super::EventList::default();
    for e in report.events.iter() {
        events.push(Event {
            time: e.time,
            kind: e.kind,
            state: rotor_of(e.state.array()),
        });
    }
    // Both lists hold EVENT_CAPACITY switches: a matrix list with drops is full, so these
    // pushes land in the planar list's drop count.
    for _ in 0..report.events.dropped() {
        events.push(Event {
            time: report.time,
            kind: crate::propagate::EventKind::Enter,
            state: State::new(0.0, 0.0, 0.0, 0.0),
        });
    }
    StepReport {
        time: report.time,
        state: rotor_of(report.state.array()),
        regime: report.regime,
        events,
        substeps: 0,
        capped: false,
        search_capped: false,
        error_estimate: 0.0,
    }
}

/// The ring stepper's configuration from the planar one: the same `dt`, the default method
/// (taylor) and switch cap (the planar scheme and sub-step counts do not apply).
pub fn ring_config(config: &StepperConfig) -> MatrixStepperConfig {
    MatrixStepperConfig::with_dt(config.dt)
}
