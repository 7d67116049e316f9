//! The segments of a run on a speed profile: which method runs on a piece (or a held step of
//! it) and where the segment ends (`docs/MODEL.md` §14; the rules are listed in
//! `propagator.rs`).

use super::field::RampField;
use super::options::{VariableSpeedError, VariableSpeedOptions};
use crate::driver::Piecewise;
use crate::method::{Method, Propagator};
use crate::params::{Parameter, Params, Problem, State};
use crate::propagate::{Propagate, PropagationError};
use crate::reference::{Dop853, REFERENCE_BUDGET, ReferenceSolver, Rk45};
use crate::speed::{HeldSpeed, SpeedPiece, SpeedProfile};

/// The method run on the current segment.
#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
pub(super) enum Inner {
    /// A constant-speed method on a held (or constant) speed.
    Held(Propagator),
    /// DOP853 on a changing speed.
    Dop853(Piecewise<ReferenceSolver<Dop853, RampField>>),
    /// RK45 on a changing speed.
    Rk45(Piecewise<ReferenceSolver<Rk45, RampField>>),
}

impl Inner {
    pub(super) fn get(&self) -> &dyn Propagate {
        match self {
            Inner::Held(p) => p,
            Inner::Dop853(p) => p,
            Inner::Rk45(p) => p,
        }
    }

    pub(super) fn get_mut(&mut self) -> &mut dyn Propagate {
        match self {
            Inner::Held(p) => p,
            Inner::Dop853(p) => p,
            Inner::Rk45(p) => p,
        }
    }
}

/// What a run on a profile keeps to start its segments.
#[derive(Clone, Copy, Debug)]
pub(super) struct Program<'a> {
    pub(super) profile: SpeedProfile<'a>,
    pub(super) params: Params,
    pub(super) options: VariableSpeedOptions,
    /// θ at the profile's start: the held steps' phase grid starts there.
    pub(super) phase_origin: f64,
}

impl Program<'_> {
    /// The segment beginning at `(time, state)` on `piece`: the method to run and where the
    /// segment ends.
    pub(super) fn segment(
        &self,
        piece: &SpeedPiece,
        time: f64,
        state: State,
    ) -> Result<(Inner, f64), PropagationError> {
        let changing = piece.rate != 0.0;
        Ok(match self.options.options.method {
            Method::Dop853 | Method::Rk45 => (self.ramp(piece, time, state)?, piece.end),
            Method::Hybrid | Method::Taylor if changing => {
                (self.ramp(piece, time, state)?, piece.end)
            }
            Method::Analytic if changing => {
                let end = self.hold_end(piece, time);
                let held = HeldSpeed::between((piece, time), (piece, end));
                (self.held(held, time, state)?, end)
            }
            Method::Hybrid | Method::Taylor | Method::Analytic => (
                self.held(HeldSpeed::of_piece(piece), time, state)?,
                piece.end,
            ),
        })
    }

    /// The constant-speed method on a held speed from `(time, state)`.
    fn held(&self, held: HeldSpeed, time: f64, state: State) -> Result<Inner, PropagationError> {
        let problem = Problem {
            params: held.params(&self.params),
            initial: state,
            start_time: time,
        };
        Propagator::resume(&problem, &self.options.options).map(Inner::Held)
    }

    /// The numerical method on `piece`'s changing speed from `(time, state)`.
    fn ramp(&self, piece: &SpeedPiece, time: f64, state: State) -> Result<Inner, PropagationError> {
        let field = RampField::new(&self.params, *piece);
        // What the driver sees at the start (a start on z = 1 is decided with this field).
        let problem = Problem {
            params: Params {
                speed_ratio: piece.speed_at(time),
                phase: piece.phase_constant,
                ..self.params
            },
            initial: state,
            start_time: time,
        };
        let tol = self.options.options.tolerance();
        let budget = Some(REFERENCE_BUDGET);
        Ok(match self.options.options.method {
            Method::Rk45 => Inner::Rk45(Piecewise::new(&problem, budget, |at| {
                Ok(ReferenceSolver::new(
                    field, at.regime, at.slip, time, at.state, tol,
                ))
            })?),
            _ => Inner::Dop853(Piecewise::new(&problem, budget, |at| {
                Ok(ReferenceSolver::new(
                    field, at.regime, at.slip, time, at.state, tol,
                ))
            })?),
        })
    }

    /// The end of the held step starting at `time` on `piece`: the next point of the phase
    /// grid θ_origin + k·2π/holds after `time`, or the piece's end — also where the grid point
    /// lies within a sliver of it (a ramp over whole periods ends on the grid, in floating
    /// point up to ~1e-13 before the piece's end: that sliver joins the step before it instead
    /// of being a held step of its own, issue 32).
    fn hold_end(&self, piece: &SpeedPiece, time: f64) -> f64 {
        let step = core::f64::consts::TAU / f64::from(self.options.speed_holds);
        let done = (piece.phase_at(time) - self.phase_origin) / step;
        let mut k = libm::floor(done) + 1.0;
        // A start on a grid point computed a rounding below it: skip the zero-length step.
        let min_length = 1e-9 * step / piece.speed_at(time);
        loop {
            let end = piece
                .time_of_phase(self.phase_origin + k * step)
                .map_or(piece.end, |t| t.min(piece.end));
            if piece.end - end <= min_length {
                return piece.end;
            }
            if end - time > min_length {
                return end;
            }
            k += 1.0;
        }
    }
}

/// A profile the problem can run on: friction only at a constant speed (a changing speed's
/// slip direction is not modelled), and the profile starts at the problem's start time.
pub(super) fn check_profile_fits(
    problem: &Problem,
    profile: &SpeedProfile,
) -> Result<(), VariableSpeedError> {
    let mu = problem.params.friction_coefficient;
    if mu > 0.0 && !profile.is_constant() {
        return Err(VariableSpeedError::Friction {
            friction_coefficient: mu,
        });
    }
    if problem.start_time != profile.start() {
        return Err(VariableSpeedError::StartTime {
            start_time: problem.start_time,
            profile_start: profile.start(),
        });
    }
    Ok(())
}

/// The analytic method's held steps carry the speed-change force in the unbalance: check that
/// the scaled eccentricity ratio ([`HeldSpeed::eccentricity_scale`]) stays in the table's range
/// on every piece that changes speed (at its lowest speed, with a margin for rounding).
pub(super) fn check_held_unbalance(
    profile: &SpeedProfile<'_>,
    params: &Params,
) -> Result<(), VariableSpeedError> {
    let range = Parameter::EccentricityRatio.info().range;
    for pair in profile.points().windows(2) {
        let [a, b] = pair else { continue };
        let rate = (b.speed_ratio - a.speed_ratio) / (b.time - a.time);
        let low = a.speed_ratio.min(b.speed_ratio);
        let held = HeldSpeed {
            speed_ratio: low,
            rate,
            phase_constant: 0.0,
        };
        let at_low = Params {
            speed_ratio: low,
            ..*params
        };
        let needed = params.eccentricity_ratio * held.eccentricity_scale(&at_low).0;
        if !range.contains(needed * (1.0 + 1e-9)) {
            return Err(VariableSpeedError::HeldUnbalance {
                speed_ratio: low,
                rate,
                eccentricity_ratio: needed,
                range,
            });
        }
    }
    Ok(())
}
