//! Propagation on a speed profile (`docs/MODEL.md` §14): [`VariableSpeedPropagator`] runs the
//! chosen method segment by segment, one segment per profile piece (or per held step), and
//! restarts it at each segment's end from the state reached there.
//!
//! How each method treats a changing speed:
//! - **dop853, rk45**: the full equations with η(τ), θ(τ) and the speed-change force
//!   ([`super::RampField`]), one integration per profile piece (the force's rate jumps at the points).
//! - **hybrid**: where a piece holds its speed the forcing is harmonic and the constant-speed
//!   hybrid runs (exact free flight); where the speed changes it is not, and DOP853 integrates
//!   both regimes (free flight numerical too), as dop853 does.
//! - **analytic**: where a piece holds its speed, the constant-speed analytic method; where it
//!   changes, the speed is held constant over steps of 1/[`VariableSpeedOptions::speed_holds`]
//!   of a forcing period ([`crate::speed::HeldSpeed`]) and the constant-speed closed forms run on each step
//!   with the held forcing (exact for the held speed and rate; the error is the speed's change
//!   inside a step, measured in `tests/variable_speed.rs`).
//!
//! A profile that never changes its speed runs exactly the constant-speed method: every
//! method's output is then the constant-speed run's, bit for bit.

use super::options::{SPEED_HOLDS_RANGE, VariableSpeedError, VariableSpeedOptions};
use super::segment::{Inner, Program, check_held_unbalance, check_profile_fits};
use crate::method::Method;
use crate::params::{Params, Problem, State};
use crate::propagate::{Event, Propagate, PropagationError, Regime, check_target};
use crate::speed::{SpeedPiece, SpeedProfile};

/// Any method on a speed profile (see the module documentation). No heap: the profile's points
/// are borrowed.
pub struct VariableSpeedPropagator<'a> {
    program: Program<'a>,
    piece: SpeedPiece,
    segment_end: f64,
    inner: Inner,
    segments: u64,
}

impl<'a> VariableSpeedPropagator<'a> {
    /// Start `options`' method on `profile` from `problem`'s initial state at the profile's
    /// first time (which must be the problem's start time). The problem's speed ratio is not
    /// used (the profile gives η); its phase φ0 is the unbalance's phase at τ = 0 as at a
    /// constant speed: θ = η_0 τ + φ0 on the first piece.
    pub fn new(
        problem: &Problem,
        profile: SpeedProfile<'a>,
        options: &VariableSpeedOptions,
    ) -> Result<Self, VariableSpeedError> {
        let first = profile.first_piece(problem.params.phase);
        let checked = Problem {
            params: Params {
                speed_ratio: first.speed_ratio,
                ..problem.params
            },
            ..*problem
        };
        checked.validate().map_err(PropagationError::from)?;
        options.options.validate()?;
        let holds = f64::from(options.speed_holds);
        if !SPEED_HOLDS_RANGE.contains(holds) {
            return Err(PropagationError::InvalidOption {
                method: Method::Analytic.name(),
                what: "speed_holds",
                value: holds,
                valid: SPEED_HOLDS_RANGE,
            }
            .into());
        }
        check_profile_fits(problem, &profile)?;
        if options.options.method == Method::Analytic {
            check_held_unbalance(&profile, &problem.params)?;
        }
        let program = Program {
            profile,
            params: problem.params,
            options: *options,
            phase_origin: first.phase_at(first.start),
        };
        let (inner, segment_end) = program.segment(&first, first.start, problem.initial)?;
        Ok(VariableSpeedPropagator {
            program,
            piece: first,
            segment_end,
            inner,
            segments: 1,
        })
    }

    /// The speed profile.
    pub fn profile(&self) -> &SpeedProfile<'a> {
        &self.program.profile
    }

    /// The profile piece of the current segment.
    pub fn piece(&self) -> &SpeedPiece {
        &self.piece
    }

    /// The number of segments started so far (pieces, or held steps of the analytic method).
    pub fn segments(&self) -> u64 {
        self.segments
    }

    /// The end of the current segment (∞ on the last piece).
    pub fn segment_end(&self) -> f64 {
        self.segment_end
    }

    /// Start the segment beginning at `(time, state)`.
    fn next_segment(&mut self, time: f64, state: State) -> Result<(), PropagationError> {
        self.piece = self.program.profile.piece_holding(self.piece, time);
        let (inner, end) = self.program.segment(&self.piece, time, state)?;
        self.inner = inner;
        self.segment_end = end;
        self.segments = self.segments.saturating_add(1);
        Ok(())
    }
}

impl Propagate for VariableSpeedPropagator<'_> {
    fn time(&self) -> f64 {
        self.inner.get().time()
    }

    fn state(&self) -> State {
        self.inner.get().state()
    }

    fn regime(&self) -> Regime {
        self.inner.get().regime()
    }

    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        if !check_target(target, self.time())? {
            return Ok(None);
        }
        loop {
            let now = self.time();
            if now >= self.segment_end {
                self.next_segment(now, self.state())?;
            }
            let stop = target.min(self.segment_end);
            if let Some(event) = self.inner.get_mut().advance(stop)? {
                return Ok(Some(event));
            }
            if stop >= target {
                return Ok(None);
            }
        }
    }
}
