//! The stepper of any problem ([`AnyStepper`]): the planar [`Stepper`] for m̂ = 0 (the paper,
//! bit for bit and at its speed: the choice is one match per call), the ring's
//! [`RingStepper`] for m̂ > 0 — what the C ABI and the FMU run.

use super::ring::{RingState, RingStepper, ring_config, rotor_report};
use super::{Snapshot, StepReport, Stepper, StepperConfig, StepperError};
use crate::params::{Params, Problem, State};
use crate::propagate::Regime;

/// The stepper of any problem: the planar [`Stepper`] when m̂ = 0, the ring's when m̂ > 0
/// (the problem decides, not the caller). Plain memory, no heap.
#[allow(
    clippy::large_enum_variant,
    reason = "no heap in the runtime: the ring's model lives inline"
)]
#[derive(Clone, Debug)]
pub enum AnyStepper {
    /// The paper's planar model (m̂ = 0).
    Planar(Stepper),
    /// The stator ring with mass (m̂ > 0).
    Ring(RingStepper),
}

impl AnyStepper {
    /// [`Stepper::new`] for m̂ = 0, [`RingStepper::new`] with [`ring_config`] for m̂ > 0.
    ///
    /// # Errors
    /// As the chosen stepper's constructor.
    pub fn new(problem: &Problem, config: StepperConfig) -> Result<Self, StepperError> {
        if problem.params.stator_mass_ratio > 0.0 {
            Ok(AnyStepper::Ring(RingStepper::new(
                problem,
                ring_config(&config),
            )?))
        } else {
            Ok(AnyStepper::Planar(Stepper::new(problem, config)?))
        }
    }

    /// Advance exactly `dt`; a ring step reports the rotor's states ([`rotor_report`]), the
    /// ring's is [`AnyStepper::ring_state`].
    ///
    /// # Errors
    /// As the stepper's `step`: the planar one unchanged, the ring's back at the step's
    /// start (its method restarted there).
    #[inline]
    pub fn step(&mut self, dt: f64) -> Result<StepReport, StepperError> {
        match self {
            AnyStepper::Planar(s) => s.step(dt),
            AnyStepper::Ring(s) => Ok(rotor_report(&s.step(dt)?)),
        }
    }

    /// As [`AnyStepper::step`], ending at the first switch inside the step.
    ///
    /// # Errors
    /// As the stepper's `step_to_switch`.
    pub fn step_to_switch(&mut self, dt: f64) -> Result<StepReport, StepperError> {
        match self {
            AnyStepper::Planar(s) => s.step_to_switch(dt),
            AnyStepper::Ring(s) => Ok(rotor_report(&s.step_to_switch(dt)?)),
        }
    }

    /// Replace the parameters (m̂ = 0 and m̂ > 0 stay as they started).
    ///
    /// # Errors
    /// As the stepper's `set_params`; for a planar stepper given m̂ > 0,
    /// [`crate::ParamError::RingNeedsMatrixModel`].
    pub fn set_params(&mut self, params: &Params) -> Result<(), StepperError> {
        match self {
            AnyStepper::Planar(s) => s.set_params(params),
            AnyStepper::Ring(s) => s.set_params(params),
        }
    }

    /// The input force on the rotor.
    ///
    /// # Errors
    /// Out of range; nothing changes.
    pub fn set_input_force(&mut self, fx: f64, fy: f64) -> Result<(), StepperError> {
        match self {
            AnyStepper::Planar(s) => s.set_input_force(fx, fy),
            AnyStepper::Ring(s) => s.set_input_force(fx, fy),
        }
    }

    /// The input force in force.
    pub fn input_force(&self) -> (f64, f64) {
        match self {
            AnyStepper::Planar(s) => s.input_force(),
            AnyStepper::Ring(s) => s.input_force(),
        }
    }

    /// The running speed with the phase continuous.
    ///
    /// # Errors
    /// Out of range; nothing changes.
    pub fn set_speed_ratio(&mut self, eta: f64) -> Result<(), StepperError> {
        match self {
            AnyStepper::Planar(s) => s.set_speed_ratio(eta),
            AnyStepper::Ring(s) => s.set_speed_ratio(eta),
        }
    }

    /// The current time τ.
    pub fn time(&self) -> f64 {
        match self {
            AnyStepper::Planar(s) => s.time(),
            AnyStepper::Ring(s) => s.time(),
        }
    }

    /// The rotor's state.
    pub fn state(&self) -> State {
        match self {
            AnyStepper::Planar(s) => s.state(),
            AnyStepper::Ring(s) => s.state(),
        }
    }

    /// The ring's state: at rest (all 0) for the planar model, whose ring does not move.
    pub fn ring_state(&self) -> RingState {
        match self {
            AnyStepper::Planar(_) => RingState::default(),
            AnyStepper::Ring(s) => s.ring_state(),
        }
    }

    /// The regime.
    pub fn regime(&self) -> Regime {
        match self {
            AnyStepper::Planar(s) => s.regime(),
            AnyStepper::Ring(s) => s.regime(),
        }
    }

    /// The slip direction σ of a slipping contact (±1; 0 when free, rolling or frictionless).
    pub fn slip_direction(&self) -> f64 {
        match self {
            AnyStepper::Planar(s) => s.slip_direction(),
            AnyStepper::Ring(s) => s.slip_direction(),
        }
    }

    /// How the planar stepper resolves contact for the parameters in force: its contact
    /// sub-steps per step of `dt` ([`Stepper::contact_substeps`]) and the longest step the
    /// configured cap resolves ([`Stepper::largest_resolved_dt`]). `None` for the ring with
    /// mass, whose adaptive methods choose their own steps inside a step (its work per step is
    /// bounded by `max_switches` and the step budget instead).
    pub fn contact_resolution(&self) -> Option<(u32, f64)> {
        match self {
            AnyStepper::Planar(s) => Some((s.contact_substeps(), s.largest_resolved_dt())),
            AnyStepper::Ring(_) => None,
        }
    }

    /// The parameters in force.
    pub fn params(&self) -> &Params {
        match self {
            AnyStepper::Planar(s) => s.params(),
            AnyStepper::Ring(s) => s.params(),
        }
    }

    /// What [`AnyStepper::restore`] rebuilds the stepper from: the planar [`Snapshot`] (plain
    /// data a quarter of the stepper's size) or a copy of the ring's stepper.
    pub fn snapshot(&self) -> AnySnapshot {
        match self {
            AnyStepper::Planar(s) => AnySnapshot::Planar(s.snapshot()),
            AnyStepper::Ring(s) => AnySnapshot::Ring(s.snapshot()),
        }
    }

    /// The stepper a snapshot was taken of (bit for bit: stepping on gives the same bits).
    ///
    /// # Errors
    /// As [`Stepper::restore`] for a planar snapshot.
    pub fn restore(snapshot: &AnySnapshot) -> Result<AnyStepper, StepperError> {
        match snapshot {
            AnySnapshot::Planar(s) => Ok(AnyStepper::Planar(Stepper::restore(s)?)),
            AnySnapshot::Ring(s) => Ok(AnyStepper::Ring(s.clone())),
        }
    }

    /// The stepper as [`Snapshot::WORDS`] words: the planar [`Snapshot::to_words`] or
    /// [`RingStepper::to_words`] (told apart by their markers).
    pub fn to_words(&self) -> [u64; Snapshot::WORDS] {
        match self {
            AnyStepper::Planar(s) => s.snapshot().to_words(),
            AnyStepper::Ring(s) => s.to_words(),
        }
    }

    /// The stepper written by [`AnyStepper::to_words`].
    ///
    /// # Errors
    /// As [`Snapshot::from_words`] and [`Stepper::restore`], or [`RingStepper::from_words`].
    pub fn from_words(words: &[u64; Snapshot::WORDS]) -> Result<AnyStepper, StepperError> {
        if RingStepper::is_ring_words(words) {
            Ok(AnyStepper::Ring(RingStepper::from_words(words)?))
        } else {
            Ok(AnyStepper::Planar(Stepper::restore(
                &Snapshot::from_words(words)?,
            )?))
        }
    }
}

/// An [`AnyStepper`]'s snapshot.
#[allow(
    clippy::large_enum_variant,
    reason = "no heap in the runtime: the ring's stepper is copied inline"
)]
#[derive(Clone, Debug)]
pub enum AnySnapshot {
    /// The planar stepper's.
    Planar(Snapshot),
    /// A copy of the ring's stepper.
    Ring(RingStepper),
}
