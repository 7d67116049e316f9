//! The piecewise driver (`docs/MODEL.md` §13): the one state machine that strings segments of the
//! regimes together, shared by every method. A method supplies segment solvers; the driver owns
//! what happens between them: target handling, the switch from one regime's solver to the next,
//! divergence at a switch, the step budget, a failure that repeats, and starts on z = 1.
//!
//! # Any model
//! The driver knows a model only through [`System`]: its state type, the side of a start, the
//! slip direction at a contact start and the divergence test. The paper's planar model
//! ([`crate::params::Params`], state [`State`]) and a rotor from matrices
//! (`crate::matrix::MatrixModel`, the model's size a property of its statement) are two
//! systems on the same state machine; [`Located`], [`SegmentSolver`] and [`Solvers`] take the
//! state type as a parameter that defaults to the planar [`State`].
//!
//! # How a method plugs in
//! A [`SegmentSolver`] solves the motion in one regime from a start on: [`SegmentSolver::start`]
//! begins a segment at a switch (or the problem start), [`SegmentSolver::locate`] serves a
//! target time from what it has computed (the state there, the switch that ends the segment, or
//! a request for the next step), and [`SegmentSolver::step`] computes the next step and searches it
//! for the switch. [`Solvers`] hands the driver the solver of each [`Regime`] (and serves its
//! targets by a static match, [`Solvers::locate`]); [`ByRegime`] pairs a free-flight solver with
//! a contact solver. A new regime (rolling, under friction) is one more
//! solver and one more arm in the [`Solvers`] impl; a new switch is one more
//! [`crate::propagate::EventKind`] with its regime after: the state machine stays as it is.
//!
//! # Starts on z = 1
//! The regime at the start comes from [`crate::field::regime_of`] (the sign of h = z² − 1). On
//! z = 1 within [`TOUCH_DEPTH`] the switching function stays within its rounding for a while,
//! and a solver could see sign changes there that are only rounding: a switch at the start
//! instant, or an enter and an exit a few ulps apart (a zero-length contact). So a start on z = 1
//! begins on the side the motion takes once |h| leaves that band, read from the Taylor expansion
//! h0 + h0'·s + ½h0''·s² (z' decides, or z'' where z' is too small to matter), and the solvers
//! start from the position moved radially 2·[`TOUCH_DEPTH`] onto that side (z changes by about
//! 3e-14, below every method's resolution). `time()`, `state()` at the start are the problem's.

mod boundary;
mod piecewise;
mod system;

pub(crate) use boundary::{motion_side, start_side};

/// `impl Propagate for $ty` by delegation to the [`Piecewise`] it wraps (field 0): a method's
/// propagator is a newtype over the driver, and this is all its `Propagate` says.
macro_rules! propagate_through_driver {
    ($ty:ty) => {
        impl $crate::propagate::Propagate for $ty {
            fn time(&self) -> f64 {
                $crate::propagate::Propagate::time(&self.0)
            }
            fn state(&self) -> $crate::params::State {
                $crate::propagate::Propagate::state(&self.0)
            }
            fn regime(&self) -> $crate::propagate::Regime {
                $crate::propagate::Propagate::regime(&self.0)
            }
            fn advance(
                &mut self,
                target: f64,
            ) -> Result<Option<$crate::propagate::Event>, $crate::propagate::PropagationError> {
                $crate::propagate::Propagate::advance(&mut self.0, target)
            }
        }
    };
}
pub use piecewise::Piecewise;
pub(crate) use propagate_through_driver;
pub use system::{Borrowed, System};

use crate::params::State;
use crate::propagate::{Event, PropagationError, Regime};

/// What a segment solver found on the way to a target time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Located<S = State> {
    /// The target lies in the part of the segment already computed: the state there.
    Reached(S),
    /// The segment ends at this switch, at or before the target.
    Switch(Event<S>),
    /// The target lies beyond what has been computed: take a step.
    NeedStep,
}

/// A switch found at local time `local` of a segment starting at `origin`: its time
/// `origin + local` as stored (rounded to f64), and the local time that stored time stands for,
/// at which the switch's state is to be evaluated.
///
/// Why: the next segment starts from (time, state). With the state taken at the exact root
/// `local` but the time rounded by up to half an ulp of the absolute time, each switch shifts
/// the rest of the trajectory in time by that rounding, and the shifts add up as a random walk
/// (τ ≈ 20, 43 switches: 1.2e-14, 3 ulps, from a 30-digit reference). Taking the state at
/// the stored time keeps time and state consistent (2.7e-15); the state then lies off the
/// switching surface by the rounding of the time times the surface's rate, which every search
/// already treats as a start on the surface.
#[inline]
pub fn switch_time(origin: f64, local: f64) -> (f64, f64) {
    let time = origin + local;
    (time, time - origin)
}

/// Where a segment starts: its regime, the slip direction σ (±1 in slipping contact under
/// friction, 0 when no slip is tracked), its time and state. What the driver hands a solver
/// ([`SegmentSolver::start`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentStart<S = State> {
    /// The segment's regime.
    pub regime: Regime,
    /// The slip direction σ.
    pub slip: f64,
    /// The segment's start time.
    pub time: f64,
    /// The state there.
    pub state: S,
}

/// A solver of one regime's segments of a model with state `S`.
pub trait SegmentSolver<S = State> {
    /// Start a segment in `regime` at `(time, state)`; `slip` is the slip direction σ = ±1 of
    /// slipping contact under friction, 0 when no slip is tracked (free flight, rolling, μ = 0).
    /// A solver may compute its first step here.
    fn start(&mut self, at: SegmentStart<S>) -> Result<(), PropagationError>;
    /// Serve `target` (not before the segment start nor before the last target served) from what
    /// has been computed. A closed-form solver may serve every target without steps. Serving a
    /// target never changes the steps taken (sampling does not perturb a run).
    fn locate(&mut self, target: f64) -> Located<S>;
    /// Compute the next step and search it for the switch that ends the segment.
    fn step(&mut self) -> Result<(), PropagationError>;
    /// The time up to which the segment has been computed (reported when the step budget is
    /// exhausted).
    fn computed_to(&self) -> f64;
}

/// The segment solvers of a method, by regime (state `S`).
pub trait Solvers<S = State> {
    /// The solver of `regime`'s segments.
    fn solver(&mut self, regime: Regime) -> &mut dyn SegmentSolver<S>;

    /// [`SegmentSolver::locate`] on the solver of `regime`: what the driver asks for every
    /// target, so an implementation dispatches it statically (inlined) instead of through
    /// [`Self::solver`]'s `dyn` reference.
    #[inline]
    fn locate(&mut self, regime: Regime, target: f64) -> Located<S> {
        self.solver(regime).locate(target)
    }
}

/// A caller's solvers, borrowed: a driver run over solvers that outlive it (the stepper's, built
/// once per step on its stack, with a sub-step slot too large to move).
impl<St, S: Solvers<St> + ?Sized> Solvers<St> for &mut S {
    fn solver(&mut self, regime: Regime) -> &mut dyn SegmentSolver<St> {
        (**self).solver(regime)
    }

    #[inline]
    fn locate(&mut self, regime: Regime, target: f64) -> Located<St> {
        (**self).locate(regime, target)
    }
}

/// A free-flight solver, a contact solver and a rolling solver (rolling occurs only under
/// friction).
pub struct ByRegime<F, C, R> {
    /// Free flight (z < 1).
    pub free: F,
    /// Contact (z > 1), slipping under friction.
    pub contact: C,
    /// Rolling contact (μ > 0, w ≡ 0).
    pub rolling: R,
}

impl<St, F, C, R> Solvers<St> for ByRegime<F, C, R>
where
    F: SegmentSolver<St>,
    C: SegmentSolver<St>,
    R: SegmentSolver<St>,
{
    fn solver(&mut self, regime: Regime) -> &mut dyn SegmentSolver<St> {
        match regime {
            Regime::Free => &mut self.free,
            Regime::Contact => &mut self.contact,
            Regime::Rolling => &mut self.rolling,
        }
    }

    #[inline]
    fn locate(&mut self, regime: Regime, target: f64) -> Located<St> {
        match regime {
            Regime::Free => self.free.locate(target),
            Regime::Contact => self.contact.locate(target),
            Regime::Rolling => self.rolling.locate(target),
        }
    }
}

/// Most steps of one `advance` call: `base` plus `per_time_unit` per unit of the requested span.
/// Exceeding it reports [`PropagationError::StepSizeUnderflow`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepBudget {
    /// Steps allowed whatever the span.
    pub base: f64,
    /// Further steps per unit of time.
    pub per_time_unit: f64,
}

/// Band around z = 1, in h = z² − 1, within which a start counts as on z = 1: a switch function
/// along a method's solution ([`crate::rounding::SOLUTION`], 64 ulps of 1).
pub const TOUCH_DEPTH: f64 = crate::rounding::SOLUTION;

/// [`within_bounds`] with its common case decided without `hypot`: |x|, |y| ≤ 7000 puts the
/// position within 7000·√2 < 9900 of the rest position, inside [`DIVERGENCE_RADIUS`] whatever
/// `hypot`'s rounding (within an ulp); only outside that square the exact test runs. The same
/// answer for every state, about 50 instructions fewer per test.
///
/// [`DIVERGENCE_RADIUS`]: crate::propagate::DIVERGENCE_RADIUS
#[inline(always)]
pub(crate) fn within_bounds(state: &State) -> bool {
    const SQUARE: f64 = 7.0e3;
    const _: () = assert!(SQUARE * 1.415 < crate::propagate::DIVERGENCE_RADIUS);
    if state.is_finite()
        && crate::math::abs(state.x) <= SQUARE
        && crate::math::abs(state.y) <= SQUARE
    {
        return true;
    }
    crate::propagate::within_bounds(state)
}
