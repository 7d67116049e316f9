//! The ring's stepper as plain words (an FMU's serialized state): the same width as the
//! planar [`Snapshot`]'s, so a saved state holds either. Restored, the method restarts at the
//! saved time and state on the saved side (regime and slip direction: right after a `reverse`
//! the slip velocity is 0 to rounding, so the side is not decided afresh from it), with the
//! saved time anchor: stepping on agrees with the original run within the method's tolerance,
//! not bit for bit (a copy, [`RingStepper::snapshot`], is bit for bit).

use super::inputs::problem_and_tail;
use super::matrix::{MatrixStepper, MatrixStepperConfig};
use super::ring::{RingStepper, check_ring, state_model};
use super::{Snapshot, StepperError};
use crate::driver::SegmentStart;
use crate::matrix::{MatrixState, RING_CAPACITY};
use crate::method::Method;
use crate::params::{Parameter, Problem};
use crate::propagate::Regime;

/// Marks a ring stepper's words ("ringstep").
const MARKER: u64 = 0x7269_6e67_7374_6570;
/// The words after the model parameters: the configuration and anchor, y, the side (regime
/// code, σ) and the marker.
const TAIL: usize = 8 + RING_CAPACITY + 2 + 1;
const _: () = assert!(Parameter::MODEL_COUNT + TAIL <= Snapshot::WORDS);

impl RingStepper {
    /// The stepper as [`Snapshot::WORDS`] words: the model parameters in table order, the
    /// configuration, the time anchor, y, the regime (0 free, 1 contact, 2 rolling) and slip
    /// direction, and a marker.
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
        let regime = match self.regime() {
            Regime::Free => 0,
            Regime::Contact => 1,
            Regime::Rolling => 2,
        };
        let values = Parameter::ALL
            .iter()
            .filter(|p| p.is_model())
            .map(|p| p.get(&problem).to_bits())
            .chain(head)
            .chain(y)
            .chain([regime, inner.slip().to_bits(), MARKER]);
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
        let (y_words, side) = rest.split_at(RING_CAPACITY);
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
        for (o, &w) in y.iter_mut().zip(y_words) {
            *o = f(w);
        }
        let (regime, slip) = match *side {
            [regime, slip, ..] => (regime, f(slip)),
            _ => (u64::MAX, f64::NAN),
        };
        let regime = match regime {
            0 => Regime::Free,
            1 => Regime::Contact,
            2 => Regime::Rolling,
            other => return Err(invalid("ring stepper regime", other)),
        };
        // σ = ±1 only in a slipping contact; 0 anywhere.
        if !(slip == 0.0 || (regime == Regime::Contact && (slip == 1.0 || slip == -1.0))) {
            return Err(StepperError::InvalidConfig {
                what: "ring stepper slip direction",
                value: slip,
            });
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
        let at = SegmentStart {
            regime,
            slip,
            time: f(time),
            state: start,
        };
        let mut inner = MatrixStepper::resume(state_model(&params)?, at, config)?;
        inner.set_anchor(f(dt), f(anchor_time), anchor_steps)?;
        Ok(RingStepper::from_parts(params, inner))
    }
}
