//! The Taylor contact solver of a rotor from matrices (`docs/MODEL.md` §16, §17): contact,
//! slipping and rolling segments by Taylor steps ([`MatrixExpansion`]); each step's switch
//! functions searched as polynomials (`crate::taylor::roots`: Descartes isolation, so no sign
//! change inside a step is missed; a start on the switch surface divides its root out), an
//! exit put on z = 1 of the step's polynomial state by the one refinement; targets served from
//! the same polynomials. The solver of the `taylor` and `analytic` methods' contact.
//!
//! Tolerance semantics: `tol` bounds each step's truncation error relative to
//! max(1, |state|) (order p = ⌈−ln(tol)/2 + 1⌉, `crate::taylor::expansion::order_for`).

use crate::driver::SegmentStart;
use core::ops::Deref;

use super::model::MatrixModel;
use super::numerical::max_step;
use super::series::{MatrixExpansion, Switch};
use super::state::MatrixState;
use crate::driver::{Located, SegmentSolver, System};
use crate::field::{self, SlipZero};
use crate::propagate::{Event, EventKind, PropagationError};
use crate::taylor::expansion::order_for;
use crate::taylor::roots::first_exit;

/// A matrix model's contact solver: Taylor steps on the regime's field.
#[derive(Clone)]
pub struct TaylorContact<M, const CAP: usize> {
    model: M,
    expansion: MatrixExpansion<CAP>,
    max_step: f64,
    /// The segment's start time: step starts are kept in time since it (`local`).
    origin: f64,
    /// The computed step: its start (since `origin`), length (up to its switch when it holds
    /// one), start state and end state.
    local: f64,
    length: f64,
    start: [f64; CAP],
    end: [f64; CAP],
    stepped: bool,
    /// Whether the current step is the segment's first (its start counts as inside).
    first_step: bool,
    /// The switch that ends the segment, once a step holds it.
    exit: Option<Event<MatrixState<CAP>>>,
    slip: f64,
}

impl<M: Deref<Target = MatrixModel<CAP>>, const CAP: usize> TaylorContact<M, CAP> {
    /// A contact solver for `model` at tolerance `tol`, not yet started.
    pub fn new(model: M, tol: f64) -> Self {
        let expansion = MatrixExpansion::new(&model, order_for(tol));
        let max_step = max_step(&model);
        TaylorContact {
            model,
            expansion,
            max_step,
            origin: 0.0,
            local: 0.0,
            length: 0.0,
            start: [0.0; CAP],
            end: [0.0; CAP],
            stepped: false,
            first_step: true,
            exit: None,
            slip: 0.0,
        }
    }

    fn state(&self, y: [f64; CAP]) -> MatrixState<CAP> {
        MatrixState::from_array(self.model.dofs(), y)
    }

    /// The earliest switch in the current expansion over `[0, h]`: local time and which.
    fn earliest(&self, h: f64, skip: Option<Switch>) -> Option<(f64, Switch)> {
        let mut first: Option<(f64, Switch)> = None;
        for &sw in self.expansion.switches() {
            if Some(sw) == skip {
                continue;
            }
            let c = self.expansion.switch_polynomial(sw);
            let scale = self.expansion.rounding_scale(sw, &self.model);
            // The polynomial is signed already; the root polished (`precise`) as before the
            // planar solver's `Crossing` (its `past` is not used here).
            let (order, start) = (self.expansion.order(), self.first_step);
            if let Some(s) = first_exit(&c, 1.0, order, h, scale, start, true).map(|x| x.at)
                && first.is_none_or(|(f, _)| s < f)
            {
                first = Some((s, sw));
            }
        }
        first
    }
}

impl<M: Deref<Target = MatrixModel<CAP>>, const CAP: usize> SegmentSolver<MatrixState<CAP>>
    for TaylorContact<M, CAP>
{
    fn start(&mut self, at: SegmentStart<MatrixState<CAP>>) -> Result<(), PropagationError> {
        let (regime, slip, time, state) = (at.regime, at.slip, at.time, at.state);
        self.slip = slip;
        self.expansion.set_regime(&self.model, regime, slip);
        self.origin = time;
        self.local = 0.0;
        self.length = 0.0;
        self.start = *state.array();
        self.stepped = false;
        self.first_step = true;
        self.exit = None;
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located<MatrixState<CAP>> {
        if let Some(e) = self.exit.filter(|e| e.time <= target) {
            return Located::Switch(e);
        }
        let since = target - self.origin;
        if self.stepped && since <= self.local + self.length {
            Located::Reached(self.state(self.expansion.state_at(since - self.local)))
        } else {
            Located::NeedStep
        }
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        // The forcing phasor from the time at a segment's start, then carried by its series.
        let phasor = if self.stepped {
            self.start = self.end;
            let phasor = self.expansion.phasor_at(self.length);
            self.local += self.length;
            phasor
        } else {
            let p = field::phasor(self.model.running(), self.origin);
            (p.ct, p.st)
        };
        let model: &MatrixModel<CAP> = &self.model;
        let dofs = model.dofs();
        self.expansion.expand(model, &self.start, phasor);
        let h = self.expansion.step_size(dofs).min(self.max_step);
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
            let Some((s, sw)) = self.earliest(h, skip) else {
                break;
            };
            let s = match sw {
                Switch::Boundary => self.expansion.polish_boundary(model, s, h),
                _ => s,
            };
            let time = self.origin + (self.local + s);
            let y = self.expansion.state_at(s);
            let kind = match sw {
                Switch::Boundary => Some(EventKind::Exit),
                Switch::ConeUpper | Switch::ConeLower => Some(EventKind::Slip),
                Switch::SlipVelocity => {
                    let phasor = field::phasor(model.running(), time);
                    match model.friction(&phasor, &y).at_slip_zero(self.slip) {
                        SlipZero::Roll => Some(EventKind::Roll),
                        SlipZero::Reverse => Some(EventKind::Reverse),
                        SlipZero::Touch => None,
                    }
                }
            };
            match kind {
                Some(kind) => {
                    self.length = s;
                    self.exit = Some(Event {
                        time,
                        kind,
                        state: MatrixState::from_array(dofs, y),
                    });
                    break;
                }
                None if s > 0.0 => {
                    self.length = s;
                    break;
                }
                None => skip = Some(sw),
            }
        }
        self.end = self.expansion.state_at(self.length);
        let end = MatrixState::from_array(dofs, self.end);
        if !System::within_bounds(&model, &end) {
            return Err(System::diverged(
                &model,
                self.origin + (self.local + self.length),
                &end,
            ));
        }
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.origin + (self.local + self.length)
    }
}
