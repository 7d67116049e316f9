//! The analytic propagator: exact free flight, re-linearized closed-form contact, switches
//! located on the closed forms (`model.md` §4–§8).

use super::free::FreeConstants;
use super::free_flight::{FreeAdvance, FreeFlight};
use super::schemes::{SubStep, exprb2_into, exprb43_into};
use super::segment::{Point, Segment, point_of};
use super::switch::{Direction, first_crossing_to};
use crate::field;
use crate::math;
use crate::method::ContactScheme;
use crate::params::{Params, Problem, State};
use crate::propagate::{
    Event, EventKind, Propagate, PropagationError, Regime, check_target, within_bounds,
};

/// Default fixed sub-step of exprb2 (switch error ≈ 1e-6 on the paper's cases, `model.md` §8).
pub const DEFAULT_EXPRB2_STEP: f64 = 1e-3;
/// Most step attempts for one accepted exprb43 sub-step before giving up.
const MAX_ATTEMPTS: u32 = 60;

#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
enum Piece {
    Free(FreeFlight),
    /// In contact: the current sub-step, from `t0`, is `AnalyticPropagator::current_step`.
    Contact {
        t0: f64,
        exit: Option<(f64, Point)>,
    },
}

/// The piecewise-analytical method (see [`crate::Method::Analytic`]).
pub struct AnalyticPropagator {
    params: Params,
    scheme: ContactScheme,
    tol: f64,
    fixed_step: Option<f64>,
    free: FreeConstants,
    h_max: f64,
    h_next: f64,
    /// Rounding carried by the sum of contact sub-step lengths (Kahan): without it, a fixed
    /// sub-step added 10⁷ times drifts the time by its rounding bias (≈ 3e-8 at τ ≈ 250,
    /// h = 1e-5), which floors exprb2's switch-time accuracy.
    time_carry: f64,
    /// Two sub-step slots: the current one (`steps[current]`) and the one the next sub-step is
    /// computed in, swapped by index on acceptance (a sub-step is too large to copy around).
    steps: [SubStep; 2],
    current: usize,
    time: f64,
    state: State,
    piece: Piece,
}

impl AnalyticPropagator {
    /// Start the analytic method. `tol` drives exprb43's step control; `fixed_step` fixes the
    /// contact sub-step (exprb2 defaults to [`DEFAULT_EXPRB2_STEP`]).
    pub fn new(
        problem: &Problem,
        scheme: ContactScheme,
        tol: f64,
        fixed_step: Option<f64>,
    ) -> Result<Self, PropagationError> {
        problem.validate()?;
        if !(tol.is_finite() && (1e-15..=1.0).contains(&tol)) {
            return Err(PropagationError::InvalidOption {
                what: "tol",
                value: tol,
            });
        }
        if let Some(h) = fixed_step.filter(|h| !(h.is_finite() && *h > 0.0 && *h <= 1.0)) {
            return Err(PropagationError::InvalidOption {
                what: "step",
                value: h,
            });
        }
        let params = problem.params;
        let fixed_step = match scheme {
            ContactScheme::Exprb2 => Some(fixed_step.unwrap_or(DEFAULT_EXPRB2_STEP)),
            ContactScheme::Exprb43 => fixed_step,
        };
        // Fastest frequencies: forcing η, free 1, contact ≤ √(1 + ‖K_s‖_F) (‖J‖ ≤ 1 for z ≥ 1).
        let k = &params;
        let k_norm =
            math::sqrt(k.k_xx * k.k_xx + k.k_xy * k.k_xy + k.k_yx * k.k_yx + k.k_yy * k.k_yy);
        let omega = params.speed_ratio.max(1.0 + params.damping_ratio);
        let omega_contact = math::sqrt(1.0 + k_norm).max(omega);
        let free = FreeConstants::new(&params);
        let mut me = AnalyticPropagator {
            params,
            scheme,
            tol,
            fixed_step,
            free,
            h_max: 1.0 / omega_contact,
            h_next: 0.1 / omega_contact,
            time_carry: 0.0,
            steps: [SubStep::zeroed(), SubStep::zeroed()],
            current: 0,
            time: problem.start_time,
            state: problem.initial,
            piece: Piece::Free(FreeFlight::new(
                &params,
                &free,
                problem.start_time,
                problem.initial,
            )),
        };
        let t0 = problem.start_time;
        me.piece = match field::regime_of(&params, t0, &problem.initial) {
            Regime::Free => me.free_piece(t0, problem.initial)?,
            Regime::Contact => me.contact_piece(t0, problem.initial)?,
        };
        Ok(me)
    }

    fn check_bounded(&self, t: f64, state: State) -> Result<(), PropagationError> {
        if !within_bounds(&state) {
            return Err(PropagationError::Diverged { time: t, state });
        }
        Ok(())
    }

    fn free_piece(&self, t0: f64, state: State) -> Result<Piece, PropagationError> {
        self.check_bounded(t0, state)?;
        Ok(Piece::Free(FreeFlight::new(
            &self.params,
            &self.free,
            t0,
            state,
        )))
    }

    fn contact_piece(&mut self, t0: f64, state: State) -> Result<Piece, PropagationError> {
        self.check_bounded(t0, state)?;
        let h_min = 1e-12 * (1.0 + math::abs(t0));
        let mut attempts = 0;
        let next = 1 - self.current;
        loop {
            let h = self
                .fixed_step
                .unwrap_or(self.h_next.clamp(h_min, self.h_max));
            let slot = &mut self.steps[next];
            match self.scheme {
                ContactScheme::Exprb2 => exprb2_into(&self.params, t0, state, h, slot),
                ContactScheme::Exprb43 => exprb43_into(&self.params, t0, state, h, self.tol, slot),
            }
            .map_err(|_| PropagationError::SingularContact { time: t0 })?;
            if self.fixed_step.is_some() {
                break;
            }
            let error = slot.error;
            let factor = if error > 0.0 {
                // 0.9·error^(−1/4), by two square roots (a power costs ten times more).
                0.9 / math::sqrt(math::sqrt(error))
            } else {
                4.0
            };
            if error <= 1.0 {
                self.h_next = h * factor.min(4.0);
                break;
            }
            self.h_next = h * factor.clamp(0.1, 0.9);
            attempts += 1;
            if attempts >= MAX_ATTEMPTS || self.h_next < h_min {
                return Err(PropagationError::StepSizeUnderflow { time: t0 });
            }
        }
        let step = &self.steps[next];
        if !step.end.is_finite() {
            return Err(PropagationError::Diverged {
                time: t0 + step.h,
                state: step.end,
            });
        }
        let (ox, oy) = (self.params.offset_x, self.params.offset_y);
        let start = point_of(state, ox, oy);
        // The sub-step's end is the segment's point at h: no need to evaluate it again.
        let end = point_of(step.end, ox, oy);
        let exit = first_crossing_to(&step.segment, 0.0, start, step.h, end, Direction::Down);
        self.current = next;
        Ok(Piece::Contact { t0, exit })
    }
}

impl Propagate for AnalyticPropagator {
    fn time(&self) -> f64 {
        self.time
    }

    fn state(&self) -> State {
        self.state
    }

    fn regime(&self) -> Regime {
        match self.piece {
            Piece::Free(_) => Regime::Free,
            Piece::Contact { .. } => Regime::Contact,
        }
    }

    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        if !check_target(target, self.time)? {
            return Ok(None);
        }
        loop {
            match &mut self.piece {
                Piece::Free(flight) => match flight.advance(target) {
                    FreeAdvance::Reached(state) => {
                        self.time = target;
                        self.state = state;
                        return Ok(None);
                    }
                    FreeAdvance::Contact { time, state } => {
                        self.time_carry = 0.0;
                        self.piece = self.contact_piece(time, state)?;
                        self.time = time;
                        self.state = state;
                        return Ok(Some(Event {
                            time,
                            kind: EventKind::Enter,
                            state,
                        }));
                    }
                },
                Piece::Contact { t0, exit } => {
                    let step = &self.steps[self.current];
                    let s_target = target - *t0;
                    if let Some((s, p)) = exit.filter(|(s, _)| *s <= s_target) {
                        let t = *t0 + s;
                        let state = p.state;
                        self.piece = self.free_piece(t, state)?;
                        self.time = t;
                        self.state = state;
                        return Ok(Some(Event {
                            time: t,
                            kind: EventKind::Exit,
                            state,
                        }));
                    }
                    if s_target <= step.h {
                        self.time = target;
                        self.state = if s_target == step.h {
                            step.end
                        } else {
                            step.segment.point(s_target).state
                        };
                        return Ok(None);
                    }
                    // Kahan summation of the sub-step lengths.
                    let y = step.h - self.time_carry;
                    let t_next = *t0 + y;
                    self.time_carry = (t_next - *t0) - y;
                    let state = step.end;
                    self.piece = self.contact_piece(t_next, state)?;
                }
            }
        }
    }
}
