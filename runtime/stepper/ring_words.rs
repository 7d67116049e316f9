//! The ring's stepper as plain words (an FMU's serialized state): the same width as the
//! planar [`Snapshot`]'s, so a saved state holds either. Restored, the method restarts at the
//! saved time and state (its regime decided there afresh, as at any start), with the saved time
//! anchor: stepping on agrees with the original run within the method's tolerance, not bit for
//! bit (a copy, [`RingStepper::snapshot`], is bit for bit).

use super::inputs::problem_and_tail;
use super::matrix::{MatrixStepper, MatrixStepperConfig};
use super::ring::{RingStepper, check_ring, state_model};
use super::{Snapshot, StepperError};
use crate::matrix::{MatrixState, RING_CAPACITY};
use crate::method::Method;
use crate::params::{Parameter, Problem};

/// Marks a ring stepper's words ("ringstep").
const MARKER: u64 = 0x7269_6e67_7374_6570;
/// The words after the model parameters.
const TAIL: usize = 8 + RING_CAPACITY + 1;
const _: () = assert!(Parameter::MODEL_COUNT + TAIL <= Snapshot::WORDS);

impl RingStepper {
    /// The stepper as [`Snapshot::WORDS`] words: the model parameters in table order, the
    /// configuration, the time anchor, y, and a marker.
    pub fn to_words(&self) -> [u64; Snapshot::WORDS] {
        let mut out = [0u64; Snapshot::WORDS];
        let problem = Problem {
            params: *self.params(),
            ..Problem::DEFAULT
        };
        let inner = self.matrix();
        let c = inner.config();
        let (dt, anchor_time, anchor_steps) = inner.anchor();
        let method = Method::ALL.iter().position(|&m| m == c.method).unwrap_or(0) as u64;
        let head = [
            c.dt.to_bits(),
            method,
            c.tol.unwrap_or(f64::NAN).to_bits(),
            u64::from(c.max_switches),
            dt.to_bits(),
            self.time().to_bits(),
            anchor_time.to_bits(),
            anchor_steps,
        ];
        let y = self.full_state().map(f64::to_bits);
        let values = Parameter::ALL
            .iter()
            .filter(|p| p.is_model())
            .map(|p| p.get(&problem).to_bits())
            .chain(head)
            .chain(y)
            .chain([MARKER]);
        for (o, v) in out.iter_mut().zip(values) {
            *o = v;
        }
        out
    }

    /// Whether `words` hold a ring stepper (its marker), not a planar [`Snapshot`].
    pub fn is_ring_words(words: &[u64; Snapshot::WORDS]) -> bool {
        words.get(Parameter::MODEL_COUNT + TAIL - 1) == Some(&MARKER)
    }

    /// The stepper written by [`RingStepper::to_words`], restarted at its saved time and state.
    ///
    /// # Errors
    /// A wrong marker or method code ([`StepperError::InvalidConfig`]), invalid parameters,
    /// configuration, anchor or state (as [`RingStepper::new`]).
    pub fn from_words(words: &[u64; Snapshot::WORDS]) -> Result<RingStepper, StepperError> {
        let invalid = |what, value: u64| StepperError::InvalidConfig {
            what,
            value: value as f64,
        };
        if !Self::is_ring_words(words) {
            return Err(invalid("ring stepper words marker", 0));
        }
        let (problem, t) = problem_and_tail::<TAIL>(words);
        let f = f64::from_bits;
        let [
            dt0,
            method,
            tol,
            max_switches,
            dt,
            time,
            anchor_time,
            anchor_steps,
            rest @ ..,
        ] = t;
        let method = usize::try_from(method)
            .ok()
            .and_then(|i| Method::ALL.get(i).copied())
            .ok_or(invalid("ring stepper method code", method))?;
        let config = MatrixStepperConfig {
            dt: f(dt0),
            method,
            tol: Some(f(tol)).filter(|t| !t.is_nan()),
            max_switches: u32::try_from(max_switches)
                .map_err(|_| invalid("max_switches", max_switches))?,
        };
        let mut y = [0.0; RING_CAPACITY];
        for (o, w) in y.iter_mut().zip(rest) {
            *o = f(w);
        }
        let params = problem.params;
        params.validate()?;
        check_ring(&params)?;
        let start = MatrixState::full(y);
        if !start.is_finite() {
            return Err(StepperError::InvalidStep {
                dt: f(dt),
                time: f(time),
            });
        }
        let mut inner = MatrixStepper::new(state_model(&params)?, f(time), start, config)?;
        inner.set_anchor(f(dt), f(anchor_time), anchor_steps)?;
        Ok(RingStepper::from_parts(params, inner))
    }
}
