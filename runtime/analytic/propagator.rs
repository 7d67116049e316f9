//! The analytic propagator: exact free flight, re-linearized closed-form contact, switches
//! located on the closed forms (`model.md` §4–§8).

use super::free::{FreeConstants, FreeSegment};
use super::schemes::{SubStep, exprb2, exprb43};
use super::segment::{Point, Segment, point_of};
use super::switch::{Direction, first_crossing};
use crate::field;
use crate::math;
use crate::method::ContactScheme;
use crate::params::{Params, Problem, State};
use crate::propagate::{DIVERGENCE_RADIUS, Event, EventKind, Propagate, PropagationError, Regime};

/// Default fixed sub-step of exprb2 (switch error ≈ 1e-6 on the paper's cases, `model.md` §8).
pub const DEFAULT_EXPRB2_STEP: f64 = 1e-3;
/// Most step attempts for one accepted exprb43 sub-step before giving up.
const MAX_ATTEMPTS: u32 = 60;

#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
enum Piece {
    Free {
        t0: f64,
        segment: FreeSegment,
        searched: f64,
        last: Point,
        settled: bool,
    },
    Contact {
        t0: f64,
        step: SubStep,
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
    chunk: f64,
    h_max: f64,
    h_next: f64,
    time: f64,
    state: State,
    piece: Piece,
}

/// The regime of a state, deciding a start exactly on z = 1 by the radial velocity and then the
/// radial acceleration (`model.md` §6 case 14).
pub fn initial_regime(params: &Params, tau: f64, state: &State) -> Regime {
    let p = point_of(*state, params.offset_x, params.offset_y);
    let on_boundary = math::abs(p.h) <= 4.0 * f64::EPSILON;
    if !on_boundary {
        return if p.h > 0.0 {
            Regime::Contact
        } else {
            Regime::Free
        };
    }
    if p.dh != 0.0 {
        return if p.dh > 0.0 {
            Regime::Contact
        } else {
            Regime::Free
        };
    }
    // h'' = 2(|r'|² + (r − ε)·r''); on z = 1 both fields agree (g = 0).
    let (ax, ay) = field::acceleration(params, Regime::Free, tau, state);
    let (u, v) = (state.x - params.offset_x, state.y - params.offset_y);
    let ddh = 2.0 * (state.vx * state.vx + state.vy * state.vy + u * ax + v * ay);
    if ddh > 0.0 {
        Regime::Contact
    } else {
        Regime::Free
    }
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
        let mut me = AnalyticPropagator {
            params,
            scheme,
            tol,
            fixed_step,
            free: FreeConstants::new(&params),
            chunk: 0.5 / omega,
            h_max: 1.0 / omega_contact,
            h_next: 0.1 / omega_contact,
            time: problem.start_time,
            state: problem.initial,
            piece: Piece::Free {
                t0: 0.0,
                segment: FreeSegment::new(
                    &params,
                    &FreeConstants::new(&params),
                    0.0,
                    problem.initial,
                ),
                searched: 0.0,
                last: point_of(problem.initial, 0.0, 0.0),
                settled: false,
            },
        };
        let t0 = problem.start_time;
        me.piece = match initial_regime(&params, t0, &problem.initial) {
            Regime::Free => me.free_piece(t0, problem.initial)?,
            Regime::Contact => me.contact_piece(t0, problem.initial)?,
        };
        Ok(me)
    }

    fn check_bounded(&self, t: f64, state: State) -> Result<(), PropagationError> {
        let r = math::hypot(state.x, state.y);
        if !(state.is_finite() && r <= DIVERGENCE_RADIUS) {
            return Err(PropagationError::Diverged { time: t, state });
        }
        Ok(())
    }

    fn free_piece(&self, t0: f64, state: State) -> Result<Piece, PropagationError> {
        self.check_bounded(t0, state)?;
        let segment = FreeSegment::new(&self.params, &self.free, t0, state);
        let last = point_of(state, self.params.offset_x, self.params.offset_y);
        Ok(Piece::Free {
            t0,
            segment,
            searched: 0.0,
            last,
            settled: false,
        })
    }

    fn contact_piece(&mut self, t0: f64, state: State) -> Result<Piece, PropagationError> {
        self.check_bounded(t0, state)?;
        let h_min = 1e-12 * (1.0 + math::abs(t0));
        let mut attempts = 0;
        let step = loop {
            let h = self
                .fixed_step
                .unwrap_or(self.h_next.clamp(h_min, self.h_max));
            let step = match self.scheme {
                ContactScheme::Exprb2 => exprb2(&self.params, t0, state, h),
                ContactScheme::Exprb43 => exprb43(&self.params, t0, state, h, self.tol),
            }
            .map_err(|_| PropagationError::SingularContact { time: t0 })?;
            if self.fixed_step.is_some() {
                break step;
            }
            let factor = if step.error > 0.0 {
                0.9 * math::pow(step.error, -0.25)
            } else {
                4.0
            };
            if step.error <= 1.0 {
                self.h_next = h * factor.min(4.0);
                break step;
            }
            self.h_next = h * factor.clamp(0.1, 0.9);
            attempts += 1;
            if attempts >= MAX_ATTEMPTS || self.h_next < h_min {
                return Err(PropagationError::StepSizeUnderflow { time: t0 });
            }
        };
        if !step.end.is_finite() {
            return Err(PropagationError::Diverged {
                time: t0 + step.h,
                state: step.end,
            });
        }
        let start = point_of(state, self.params.offset_x, self.params.offset_y);
        let exit = first_crossing(&step.segment, 0.0, start, step.h, Direction::Down, step.h);
        Ok(Piece::Contact { t0, step, exit })
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
            Piece::Free { .. } => Regime::Free,
            Piece::Contact { .. } => Regime::Contact,
        }
    }

    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        if !(target.is_finite() && target >= self.time) {
            return Err(PropagationError::InvalidTarget {
                target,
                current: self.time,
            });
        }
        if target == self.time {
            return Ok(None);
        }
        loop {
            match &mut self.piece {
                Piece::Free {
                    t0,
                    segment,
                    searched,
                    last,
                    settled,
                } => {
                    let s_target = target - *t0;
                    if !*settled && segment.reach_after(*searched) < 1.0 {
                        // No contact can happen again: free flight to any time needs no search.
                        *settled = true;
                    }
                    if !*settled {
                        let chunk = self.chunk;
                        if let Some((s, p)) = first_crossing(
                            segment,
                            *searched,
                            *last,
                            s_target,
                            Direction::Up,
                            chunk,
                        ) {
                            let t = *t0 + s;
                            let state = p.state;
                            self.piece = self.contact_piece(t, state)?;
                            self.time = t;
                            self.state = state;
                            return Ok(Some(Event {
                                time: t,
                                kind: EventKind::Enter,
                                state,
                            }));
                        }
                    }
                    let p = segment.point(s_target);
                    *searched = s_target;
                    *last = p;
                    self.time = target;
                    self.state = p.state;
                    return Ok(None);
                }
                Piece::Contact { t0, step, exit } => {
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
                    let (t_next, state) = (*t0 + step.h, step.end);
                    self.piece = self.contact_piece(t_next, state)?;
                }
            }
        }
    }
}
