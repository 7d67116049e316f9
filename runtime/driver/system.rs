//! What the driver knows of a model ([`System`]), and the paper's planar model as one.

use super::boundary::start_side;
use super::within_bounds;
use crate::field;
use crate::params::{Params, State};
use crate::propagate::{EventKind, PropagationError, Regime};

/// A model the [`super::Piecewise`] driver runs: its state, and the four decisions the driver
/// takes itself (every other question is a segment solver's).
pub trait System {
    /// The model's state (positions and velocities).
    type State: Copy;

    /// The regime of a start at `(time, state)` and the state the solvers start from: on the
    /// contact surface within rounding, the side the motion takes, and the state moved onto it
    /// (`docs/MODEL.md` §6 case 14); elsewhere the side of the surface and `state` unchanged.
    fn start_side(&self, time: f64, state: &Self::State) -> (Regime, Self::State);

    /// The slip direction σ = ±1 of a slipping contact segment starting at `(time, state)`
    /// after a switch of kind `cause` (`None` at the problem's start); 0 without friction.
    fn slip_direction(&self, time: f64, state: &Self::State, cause: Option<EventKind>) -> f64;

    /// Whether `state` is finite and within the divergence radius.
    fn within_bounds(&self, state: &Self::State) -> bool;

    /// The error reporting that `state` at `time` left the divergence radius.
    fn diverged(&self, time: f64, state: &Self::State) -> PropagationError;
}

/// The paper's planar model: the rotor's (x, y, x', y').
impl System for Params {
    type State = State;

    #[inline(always)]
    fn start_side(&self, time: f64, state: &State) -> (Regime, State) {
        start_side(self, time, state)
    }

    #[inline]
    fn slip_direction(&self, time: f64, state: &State, cause: Option<EventKind>) -> f64 {
        field::slip_direction(self, time, state, cause)
    }

    #[inline(always)]
    fn within_bounds(&self, state: &State) -> bool {
        within_bounds(state)
    }

    fn diverged(&self, time: f64, state: &State) -> PropagationError {
        PropagationError::Diverged {
            time,
            state: *state,
        }
    }
}

/// The planar model borrowed: the fixed-step stepper's driver runs on the stepper's own
/// parameters in place (a [`Params`] is ~300 bytes: a copy per step was measurable).
#[derive(Clone, Copy)]
pub struct Borrowed<'a>(pub &'a Params);

impl System for Borrowed<'_> {
    type State = State;

    #[inline(always)]
    fn start_side(&self, time: f64, state: &State) -> (Regime, State) {
        self.0.start_side(time, state)
    }

    #[inline]
    fn slip_direction(&self, time: f64, state: &State, cause: Option<EventKind>) -> f64 {
        self.0.slip_direction(time, state, cause)
    }

    #[inline(always)]
    fn within_bounds(&self, state: &State) -> bool {
        self.0.within_bounds(state)
    }

    fn diverged(&self, time: f64, state: &State) -> PropagationError {
        self.0.diverged(time, state)
    }
}
