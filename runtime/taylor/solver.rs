//! The Taylor contact solver (`docs/MODEL.md` §16): contact, slipping and rolling segments by
//! Taylor steps of the generated recurrences; each step's switch functions searched as
//! polynomials ([`super::roots`]), targets served from the same polynomials.

use super::expansion::{Expansion, Switch, order_for};
use super::roots::{Crossing, first_exit};
use crate::coefficients::ModelParams;
use crate::driver::SegmentStart;
use crate::driver::{Located, SegmentSolver, switch_time};
use crate::field::{self, SlipZero};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::{
    DIVERGENCE_RADIUS, Event, EventKind, PropagationError, Regime, within_bounds,
};

/// A contact regime's solver: Taylor steps on the regime's field.
pub struct TaylorContact {
    model: ModelParams,
    expansion: Expansion,
    max_step: f64,
    /// The segment's start time: step starts are kept in time since it (`local`), so that they
    /// accumulate rounding of their own size, not of the absolute time's.
    origin: f64,
    /// The computed step: its start (since `origin`), length (up to its switch when it holds
    /// one) and start state.
    local: f64,
    length: f64,
    start: State,
    /// The state and the forcing phasor at the step's end (the next step's start).
    end: State,
    end_phasor: (f64, f64),
    stepped: bool,
    /// Whether the current step is the segment's first (its start counts as inside).
    first_step: bool,
    /// The switch that ends the segment, once a step holds it.
    exit: Option<Event>,
    regime: Regime,
    slip: f64,
}

impl TaylorContact {
    /// A solver for `params` at tolerance `tol`, started at `(t0, s0)` in frictionless contact.
    pub fn new(params: &Params, tol: f64, t0: f64, s0: State) -> Self {
        TaylorContact {
            model: ModelParams::of(params),
            expansion: Expansion::new(&ModelParams::of(params), order_for(tol)),
            // A quarter of the shorter of the forcing period and 2π, as the other methods.
            max_step: 0.25 * params.forcing_period().min(core::f64::consts::TAU),
            origin: t0,
            local: 0.0,
            length: 0.0,
            start: s0,
            end: s0,
            end_phasor: (1.0, 0.0),
            stepped: false,
            first_step: true,
            exit: None,
            regime: Regime::Contact,
            slip: 0.0,
        }
    }

    fn phasor(&self, t: f64) -> (f64, f64) {
        let p = field::phasor(&self.model, t);
        (p.ct, p.st)
    }

    /// The earliest switch in the current expansion over `[0, h]`: where and which.
    fn earliest(&self, h: f64, skip: Option<Switch>) -> Option<(Crossing, Switch)> {
        let mut first: Option<(Crossing, Switch)> = None;
        for &sw in self.expansion.switches() {
            if Some(sw) == skip {
                continue;
            }
            let (c, sign) = self.expansion.switch_series(sw);
            let scale = self.expansion.rounding_scale(sw, &self.model);
            // An exit is refined on the step's state polynomial afterwards (`polish_boundary`).
            let precise = sw != Switch::Boundary;
            let (order, start) = (self.expansion.order(), self.first_step);
            if let Some(x) = first_exit(c, sign, order, h, scale, start, precise)
                && first.is_none_or(|(f, _)| x.at < f.at)
            {
                first = Some((x, sw));
            }
        }
        first
    }

    /// What a zero of the slip velocity at local time `crossing.at` is ([`field::at_slip_zero`]
    /// there). A touch there only to rounding of the friction cone — σw falls through its
    /// rounding band just after, so the motion does leave σw ≥ 0 — is decided where the fall is
    /// resolved (`crossing.past`): at a start on w = 0 with |λ| = μN to rounding the margin's
    /// rate says roll or reverse, and a touch there would restart the search on the same zero at
    /// no distance, step after step (issue 32 item 3's sibling: a start on the cone's edge).
    fn slip_zero(&self, crossing: Crossing, state: &State) -> Option<EventKind> {
        let decide = |s: f64, state: &State| {
            let time = self.origin + (self.local + s);
            let phasor = field::phasor(&self.model, time);
            match field::at_slip_zero(&self.model, &phasor, state, self.slip) {
                SlipZero::Roll => Some(EventKind::Roll),
                SlipZero::Reverse => Some(EventKind::Reverse),
                SlipZero::Touch => None,
            }
        };
        decide(crossing.at, state).or_else(|| {
            (crossing.past > crossing.at)
                .then(|| decide(crossing.past, &self.expansion.state_at(crossing.past)))
                .flatten()
        })
    }
}

impl SegmentSolver for TaylorContact {
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let (regime, slip, time, state) = (at.regime, at.slip, at.time, at.state);
        self.regime = regime;
        self.slip = slip;
        self.expansion.set_regime(&self.model, regime, slip);
        self.origin = time;
        self.local = 0.0;
        self.length = 0.0;
        self.start = state;
        self.stepped = false;
        self.first_step = true;
        self.exit = None;
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located {
        if let Some(e) = self.exit.filter(|e| e.time <= target) {
            return Located::Switch(e);
        }
        let since = target - self.origin;
        if self.stepped && since <= self.local + self.length {
            Located::Reached(self.expansion.state_at(since - self.local))
        } else {
            Located::NeedStep
        }
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        // The forcing phasor from the time at a segment's start, then carried by its series.
        let phasor = if self.stepped {
            self.start = self.end;
            let phasor = self.end_phasor;
            self.local += self.length;
            phasor
        } else {
            self.phasor(self.origin)
        };
        self.expansion.expand(&self.start, phasor);
        let h = self.expansion.step_size().min(self.max_step);
        if !(h > 0.0 && h.is_finite()) {
            return Err(PropagationError::StepSizeUnderflow {
                time: self.origin + self.local,
            });
        }
        self.length = h;
        self.first_step = !self.stepped;
        self.stepped = true;
        let mut skip = None;
        // A touch of w = 0 ends the step there (the next one starts on it); one found at the
        // step start itself is rounding and looked past.
        for _ in 0..2 {
            let Some((crossing, sw)) = self.earliest(h, skip) else {
                break;
            };
            let s = match sw {
                Switch::Boundary => self.expansion.polish_boundary(&self.model, crossing.at, h),
                _ => crossing.at,
            };
            let (time, since) = switch_time(self.origin, self.local + s);
            let at = since - self.local;
            // (The stored time's local time, within the step: else the root itself.)
            let state = self
                .expansion
                .state_at(if at > 0.0 && at <= h { at } else { s });
            let kind = match sw {
                Switch::Boundary => Some(EventKind::Exit),
                Switch::ConeUpper | Switch::ConeLower => Some(EventKind::Slip),
                Switch::SlipVelocity => self.slip_zero(crossing, &state),
            };
            match kind {
                Some(kind) => {
                    self.length = s;
                    self.exit = Some(Event { time, kind, state });
                    break;
                }
                None if s > 0.0 => {
                    self.length = s;
                    break;
                }
                None => skip = Some(sw),
            }
        }
        let (end, end_phasor) = self.expansion.point_at(self.length);
        self.end = end;
        self.end_phasor = end_phasor;
        // |x| + |y| ≥ |q|: within it the state is within bounds without a `hypot` per step.
        let near = end.is_finite() && math::abs(end.x) + math::abs(end.y) <= DIVERGENCE_RADIUS;
        if !near && !within_bounds(&end) {
            return Err(PropagationError::Diverged {
                time: self.origin + (self.local + self.length),
                state: end,
            });
        }
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.origin + (self.local + self.length)
    }
}
