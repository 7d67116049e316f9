//! What one fixed step returns: the end state and regime, the switches inside the step in a
//! fixed-capacity list, and the flags that say when a cap changed the result.

use core::fmt;

use crate::params::{ParamError, State};
use crate::propagate::{Event, EventKind, PropagationError, Regime};

/// How many switches one [`StepReport`] holds. More switches inside one step are counted in
/// [`EventList::dropped`], never silently lost.
pub const EVENT_CAPACITY: usize = 4;

/// The switches inside one step, in time order, in a fixed-capacity array (no heap): of the
/// planar stepper (`S` = [`State`]) or of a matrix model's (`S` = its `MatrixState`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventList<S = State> {
    events: [Event<S>; EVENT_CAPACITY],
    len: usize,
    dropped: u32,
}

/// An empty list as a constant: built in read-only memory and copied whole, so a report does not
/// assemble its blank events from small overlapping stores that the copy into the result then
/// reads across (a store-forwarding stall on every free step).
const EMPTY_EVENTS: EventList = EventList::empty(Event {
    time: 0.0,
    kind: EventKind::Enter,
    state: State::new(0.0, 0.0, 0.0, 0.0),
});

impl Default for EventList {
    fn default() -> Self {
        EMPTY_EVENTS
    }
}

impl<S: Copy> EventList<S> {
    /// An empty list whose unused slots hold `blank`.
    pub const fn empty(blank: Event<S>) -> Self {
        EventList {
            events: [blank; EVENT_CAPACITY],
            len: 0,
            dropped: 0,
        }
    }

    /// Append `event`, or count it as dropped when the list is full (the first
    /// [`EVENT_CAPACITY`] switches are kept).
    pub fn push(&mut self, event: Event<S>) {
        if let Some(slot) = self.events.get_mut(self.len) {
            *slot = event;
            self.len += 1;
        } else {
            self.dropped = self.dropped.saturating_add(1);
        }
    }

    /// The kept switches, in time order.
    pub fn as_slice(&self) -> &[Event<S>] {
        self.events.get(..self.len).unwrap_or(&[])
    }

    /// Number of kept switches (at most [`EVENT_CAPACITY`]).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no switch happened inside the step.
    pub fn is_empty(&self) -> bool {
        self.len == 0 && self.dropped == 0
    }

    /// Number of switches that happened inside the step but did not fit (0 unless the list
    /// overflowed). The regime and state at the step end account for them all.
    pub fn dropped(&self) -> u32 {
        self.dropped
    }

    /// Whether switches were dropped.
    pub fn overflowed(&self) -> bool {
        self.dropped > 0
    }

    /// Total number of switches inside the step, kept or dropped.
    pub fn total(&self) -> usize {
        self.len + self.dropped as usize
    }

    /// Iterate over the kept switches.
    pub fn iter(&self) -> core::slice::Iter<'_, Event<S>> {
        self.as_slice().iter()
    }
}

impl<'a, S: Copy> IntoIterator for &'a EventList<S> {
    type Item = &'a Event<S>;
    type IntoIter = core::slice::Iter<'a, Event<S>>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// The result of one [`super::Stepper::step`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepReport {
    /// The time at the step end.
    pub time: f64,
    /// The state at the step end.
    pub state: State,
    /// The regime at the step end (after every switch inside the step).
    pub regime: Regime,
    /// The switches inside the step, (t0, t0 + dt].
    pub events: EventList,
    /// Contact sub-steps taken in this step (0 for a pure free step).
    pub substeps: u32,
    /// Whether the per-step cap on contact sub-steps was hit: the last contact sub-step then
    /// covered the rest of the step (longer than dt / [`super::Stepper::contact_substeps`], so
    /// less accurate), and if the cap was exhausted before the step end, switches in that last
    /// piece were not located (the end regime was then taken from the end state).
    pub capped: bool,
    /// Whether a switch search hit its cap ([`super::MAX_SEARCH_EVALUATIONS`] evaluations or
    /// [`super::MAX_REFINE_ITERATIONS`] refinements): a grazing contact shallower than the
    /// search could resolve may be missing, or a switch time is only known to within its last
    /// bracket. Never seen on the presets; over 5 time units of 3000 random problems
    /// (`strategies`): none at dt = 1e-3 and 1e-2, 16 of ~1.5e5 steps at dt = 0.1 (contact
    /// sub-steps of 0.1, where the closed-form bounds are loose).
    pub search_capped: bool,
    /// Largest exprb43 embedded error estimate of the step's contact sub-steps, max norm
    /// relative to 1 + |w| (the third-order estimate: it overestimates the fourth-order error).
    /// 0 for free steps and for exprb2.
    pub error_estimate: f64,
}

impl StepReport {
    /// The report of a step taken on the free fast path: no switch, no sub-step, no cap.
    #[inline]
    pub(super) fn free(time: f64, state: State) -> Self {
        StepReport {
            time,
            state,
            regime: Regime::Free,
            events: EventList::default(),
            substeps: 0,
            capped: false,
            search_capped: false,
            error_estimate: 0.0,
        }
    }
}

/// Why a stepper could not be built or a step not taken: a propagation error (shared with every
/// method: invalid problem, divergence, singular contact) or one of the stepper's own (its
/// configuration, its step length). A failed step leaves the stepper unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepperError {
    /// What any propagation method reports: [`PropagationError::InvalidProblem`],
    /// [`PropagationError::Diverged`] (`docs/MODEL.md` §6 case 3) or
    /// [`PropagationError::SingularContact`] (cases 9–10).
    Propagation(PropagationError),
    /// A configuration value is out of range (named in `what`).
    InvalidConfig {
        /// The configuration field.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A cap was reached under [`super::OnCap::Fail`]: the step would have needed more than
    /// its bounded work (`max_substeps` contact sub-steps, or a switch search's caps). The
    /// stepper is unchanged; a shorter step (or [`super::OnCap::Degrade`]) gets through.
    BudgetExceeded {
        /// The time at the start of the refused step.
        time: f64,
        /// Contact sub-steps taken before the cap.
        substeps: u32,
    },
    /// The step length is not finite, not in (0, [`super::MAX_STEP`]], or too small to advance
    /// the time.
    InvalidStep {
        /// The requested step.
        dt: f64,
        /// The current time.
        time: f64,
    },
}

impl fmt::Display for StepperError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            StepperError::Propagation(e) => e.fmt(f),
            StepperError::InvalidConfig { what, value } => {
                write!(f, "stepper configuration {what} = {value:e} is invalid")
            }
            StepperError::BudgetExceeded { time, substeps } => write!(
                f,
                "step at time {time:e} exceeded its work budget ({substeps} contact sub-steps, or a switch search's cap): refused, the stepper is unchanged"
            ),
            StepperError::InvalidStep { dt, time } => write!(
                f,
                "step dt = {dt:e} at time {time:e} is invalid: it must be finite, in (0, {:e}], and advance the time",
                super::MAX_STEP
            ),
        }
    }
}

impl core::error::Error for StepperError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            StepperError::Propagation(e) => Some(e),
            _ => None,
        }
    }
}

impl From<PropagationError> for StepperError {
    fn from(e: PropagationError) -> Self {
        StepperError::Propagation(e)
    }
}

impl From<ParamError> for StepperError {
    fn from(e: ParamError) -> Self {
        StepperError::Propagation(PropagationError::InvalidProblem(e))
    }
}
