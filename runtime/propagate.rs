//! The one interface every propagation method implements, and the drivers built on it: the events
//! iterator, dense sampling and stroboscopic (Poincaré) sampling.
//!
//! A method only has to provide [`Propagate::advance`]: move forward to a target time or to the
//! next contact switch, whichever comes first. Sampling never changes the trajectory: a method
//! evaluates its own continuous representation at a sample time (closed form or dense output) and
//! keeps its internal step sequence.

use core::fmt;

use crate::params::{ParamError, State};

/// Contact regime (`docs/MODEL.md` §1, §10): free flight for z < 1, contact for z > 1; under
/// friction (μ > 0) contact either slips (`Contact`, with a slip direction σ the methods track)
/// or rolls without slip (`Rolling`, dry whip).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Regime {
    /// No contact: the rotor moves freely inside the clearance.
    Free,
    /// The rotor presses on the stator (slipping on it when there is friction).
    Contact,
    /// The rotor rolls on the stator without slip (μ > 0 only): w ≡ 0, |λ| ≤ μN.
    Rolling,
}

impl Regime {
    /// `free`, `contact` or `rolling`, as written in sample files.
    pub const fn name(self) -> &'static str {
        match self {
            Regime::Free => "free",
            Regime::Contact => "contact",
            Regime::Rolling => "rolling",
        }
    }

    /// Whether the rotor touches the stator (contact or rolling).
    pub const fn in_contact(self) -> bool {
        !matches!(self, Regime::Free)
    }
}

/// What a switch does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// Contact starts (z crosses 1 upwards).
    Enter,
    /// Contact ends (z crosses 1 downwards, from slipping or rolling).
    Exit,
    /// The slip direction reverses while in contact (w crosses 0, |λ| > μN).
    Reverse,
    /// Rolling starts (w reaches 0 with |λ| ≤ μN).
    Roll,
    /// Rolling ends and slipping resumes (|λ| reaches μN), σ = sign λ.
    Slip,
}

impl EventKind {
    /// Every kind, in the order of their C codes.
    pub const ALL: [EventKind; 5] = [
        EventKind::Enter,
        EventKind::Exit,
        EventKind::Reverse,
        EventKind::Roll,
        EventKind::Slip,
    ];

    /// `enter`, `exit`, `reverse`, `roll` or `slip`, as written in event files.
    pub const fn name(self) -> &'static str {
        match self {
            EventKind::Enter => "enter",
            EventKind::Exit => "exit",
            EventKind::Reverse => "reverse",
            EventKind::Roll => "roll",
            EventKind::Slip => "slip",
        }
    }

    /// The regime after the switch.
    pub const fn regime_after(self) -> Regime {
        match self {
            EventKind::Enter | EventKind::Reverse | EventKind::Slip => Regime::Contact,
            EventKind::Exit => Regime::Free,
            EventKind::Roll => Regime::Rolling,
        }
    }
}

/// A switch: time, kind and the state at the switch (where z = 1 for `enter`/`exit`, w = 0 for
/// `reverse`/`roll`, |λ| = μN for `slip`).
///
/// `S` is the model's state: the paper's planar [`State`] by default, a matrix model's
/// `crate::matrix::MatrixState` for a rotor from matrices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event<S = State> {
    /// Switch time τ.
    pub time: f64,
    /// Entry or exit.
    pub kind: EventKind,
    /// State at the switch.
    pub state: S,
}

/// Why a propagation stopped early.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PropagationError {
    /// The problem failed validation.
    InvalidProblem(ParamError),
    /// A rotor from matrices that cannot be stated or decomposed (`crate::matrix`).
    InvalidModel(crate::matrix::MatrixError),
    /// A target time before the current time, or not finite.
    InvalidTarget {
        /// The requested time.
        target: f64,
        /// The current time.
        current: f64,
    },
    /// The motion grows without bound (flutter, `docs/MODEL.md` §6 case 3): the displacement passed
    /// the divergence limit at `time`.
    Diverged {
        /// When the limit was passed.
        time: f64,
        /// The state then (for a matrix model: the rub station's relative displacement d and
        /// its rate d', the contact's own coordinates).
        state: State,
    },
    /// The linearized contact stiffness is singular (det Kl = 0, `docs/MODEL.md` §6 case 9) or the
    /// contact forcing is exactly resonant (case 10) at `time`.
    SingularContact {
        /// When.
        time: f64,
    },
    /// An adaptive method could not meet its tolerance with a representable step at `time`.
    StepSizeUnderflow {
        /// When.
        time: f64,
    },
    /// A method option (tolerance, step size, sub-step count) outside its valid range.
    InvalidOption {
        /// The method or component the option belongs to (`rk45`, `stepper`, …).
        method: &'static str,
        /// The option's name (`tol`, `step`, `dt`, …).
        what: &'static str,
        /// Its value.
        value: f64,
        /// Its valid range.
        valid: crate::params::ValidRange,
    },
}

impl fmt::Display for PropagationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PropagationError::InvalidProblem(e) => write!(f, "invalid problem: {e}"),
            PropagationError::InvalidModel(e) => write!(f, "invalid model: {e}"),
            PropagationError::InvalidTarget { target, current } => write!(
                f,
                "target time {target:e} is invalid: it must be finite and not before the current time {current:e}"
            ),
            PropagationError::Diverged { time, state } => write!(
                f,
                "the motion diverged at time {time:e} (x = {:e}, y = {:e}): the contact feeds energy faster than damping removes it",
                state.x, state.y
            ),
            PropagationError::SingularContact { time } => write!(
                f,
                "the linearized contact system is singular or resonant at time {time:e}"
            ),
            PropagationError::StepSizeUnderflow { time } => write!(
                f,
                "the step size underflowed at time {time:e}: the tolerance cannot be met"
            ),
            PropagationError::InvalidOption {
                method,
                what,
                value,
                valid,
            } => write!(
                f,
                "{what} = {value:e} is out of range for {method}: it must be in {valid}"
            ),
        }
    }
}

impl core::error::Error for PropagationError {}

impl From<crate::matrix::MatrixError> for PropagationError {
    fn from(e: crate::matrix::MatrixError) -> Self {
        PropagationError::InvalidModel(e)
    }
}

impl From<ParamError> for PropagationError {
    fn from(e: ParamError) -> Self {
        PropagationError::InvalidProblem(e)
    }
}

/// Displacement from the rest position (in clearances) beyond which a trajectory is declared
/// [`PropagationError::Diverged`].
pub const DIVERGENCE_RADIUS: f64 = 1.0e4;

/// Whether `state` is finite and within [`DIVERGENCE_RADIUS`] of the rest position: the one
/// divergence test every method applies.
#[inline]
pub fn within_bounds(state: &State) -> bool {
    state.is_finite() && crate::math::hypot(state.x, state.y) <= DIVERGENCE_RADIUS
}

/// A propagation method: analytic, hybrid or a reference integrator. `S` is the model's state
/// (the paper's planar [`State`] by default).
pub trait Propagate<S = State> {
    /// The current time τ.
    fn time(&self) -> f64;
    /// The state at [`Propagate::time`].
    fn state(&self) -> S;
    /// The regime at [`Propagate::time`] (after any switch reported at that time).
    fn regime(&self) -> Regime;
    /// Advance to `target` or to the next switch, whichever comes first.
    ///
    /// Returns `Ok(Some(event))` with `time() == event.time` when a switch at or before `target`
    /// stopped it, `Ok(None)` with `time() == target` otherwise. A target equal to the current
    /// time returns `Ok(None)` at once; a switch is never reported twice.
    fn advance(&mut self, target: f64) -> Result<Option<Event<S>>, PropagationError>;
}

/// The check every [`Propagate::advance`] starts with: an error for a target that is not finite
/// or before `current`; `Ok(false)` when the target is the current time (nothing to do).
pub fn check_target(target: f64, current: f64) -> Result<bool, PropagationError> {
    if !(target.is_finite() && target >= current) {
        return Err(PropagationError::InvalidTarget { target, current });
    }
    Ok(target > current)
}

/// Iterator over the switches up to `end` (see [`events`]).
pub struct Events<'a, P: ?Sized, S = State> {
    propagator: &'a mut P,
    end: f64,
    done: bool,
    state: core::marker::PhantomData<S>,
}

/// The switches of `propagator` from its current time to `end`, in order. An error is yielded
/// once, then the iterator ends.
pub fn events<S, P: Propagate<S> + ?Sized>(propagator: &mut P, end: f64) -> Events<'_, P, S> {
    Events {
        propagator,
        end,
        done: false,
        state: core::marker::PhantomData,
    }
}

impl<S, P: Propagate<S> + ?Sized> Iterator for Events<'_, P, S> {
    type Item = Result<Event<S>, PropagationError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        match self.propagator.advance(self.end) {
            Ok(Some(event)) => Some(Ok(event)),
            Ok(None) => {
                self.done = true;
                None
            }
            Err(e) => {
                self.done = true;
                Some(Err(e))
            }
        }
    }
}

/// One sampled point of a trajectory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<S = State> {
    /// Sample time τ.
    pub time: f64,
    /// State at `time`.
    pub state: S,
    /// Regime at `time`.
    pub regime: Regime,
}

/// Advance to `time`, passing every switch on the way to `on_event`, and return the sample there.
pub fn advance_to<S, P: Propagate<S> + ?Sized>(
    propagator: &mut P,
    time: f64,
    mut on_event: impl FnMut(&Event<S>),
) -> Result<Sample<S>, PropagationError> {
    while let Some(event) = propagator.advance(time)? {
        on_event(&event);
    }
    Ok(Sample {
        time: propagator.time(),
        state: propagator.state(),
        regime: propagator.regime(),
    })
}

/// Iterator over samples at given non-decreasing times (see [`samples`]).
pub struct Samples<'a, P: ?Sized, I, S = State> {
    propagator: &'a mut P,
    times: I,
    done: bool,
    state: core::marker::PhantomData<S>,
}

/// The states at each of `times` (non-decreasing, not before the current time). Switches passed on
/// the way are not reported; use [`advance_to`] to see both.
pub fn samples<S, P, I>(propagator: &mut P, times: I) -> Samples<'_, P, I::IntoIter, S>
where
    P: Propagate<S> + ?Sized,
    I: IntoIterator<Item = f64>,
{
    Samples {
        propagator,
        times: times.into_iter(),
        done: false,
        state: core::marker::PhantomData,
    }
}

impl<S, P: Propagate<S> + ?Sized, I: Iterator<Item = f64>> Iterator for Samples<'_, P, I, S> {
    type Item = Result<Sample<S>, PropagationError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let t = self.times.next()?;
        let r = advance_to(self.propagator, t, |_| {});
        self.done = r.is_err();
        Some(r)
    }
}

/// The stroboscopic times `start + k·period` for k = 1, 2, … of the forcing, where `start` is the
/// first forcing-period boundary at or after the propagator's current time. Forcing-period
/// boundaries are the times τ = k·2π/η (θ = φ0 + 2πk).
pub fn poincare_times(current: f64, speed_ratio: f64, count: usize) -> impl Iterator<Item = f64> {
    let period = core::f64::consts::TAU / speed_ratio;
    let first = libm::ceil(current / period - 1e-9);
    (0..count).map(move |k| (first + k as f64) * period)
}

/// The Poincaré section: the state once per forcing period at τ = k·2π/η, for the next `count`
/// periods (see [`poincare_times`]).
pub fn poincare<S, P: Propagate<S> + ?Sized>(
    propagator: &mut P,
    speed_ratio: f64,
    count: usize,
) -> Samples<'_, P, impl Iterator<Item = f64> + use<P, S>, S> {
    let times = poincare_times(propagator.time(), speed_ratio, count);
    samples(propagator, times)
}
