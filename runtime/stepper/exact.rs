//! The exact path of a step: free pieces on the closed-form `FreeSegment`, contact sub-steps of
//! exprb43/exprb2, switches located by the capped search of [`super::search`].

use super::friction::Slip;
use super::report::StepReport;
use super::search::locate_with;
use super::{Stepper, StepperError, check_bounded};
use crate::analytic::free::FreeSegment;
use crate::analytic::linear::ContactConstants;
use crate::analytic::schemes::{SubStep, exprb2_with, exprb43_with};
use crate::analytic::segment::{Point, Segment};
use crate::analytic::switch::{Direction, Search};
use crate::field;
use crate::geometry;
use crate::params::State;
use crate::propagate::{Event, EventKind, PropagationError, Regime};
use crate::registration::ContactScheme;

/// Relative slack when rounding the remaining span to a whole number of nominal sub-steps.
const SUBSTEP_SLACK: f64 = 1e-9;

impl Stepper {
    /// The step from the current state over `dt`, piece by piece; fills the report's events,
    /// sub-step count, cap flag and error estimate. Returns the end state, regime and slip, and
    /// with `stop_at_switch` the switch time where the step stopped at its first switch.
    pub(super) fn exact_step(
        &self,
        dt: f64,
        stop_at_switch: bool,
        report: &mut StepReport,
    ) -> Result<(State, Regime, Slip, Option<f64>), StepperError> {
        let t0 = self.time;
        let nominal = dt / f64::from(self.config.contact_substeps);
        let mut budget = self.config.max_substeps;
        let (mut s, mut state, mut regime) = (0.0, self.state, self.regime);
        let mut slip = self.slip;
        // The contact sub-steps' slot (written in place: a sub-step is too large to return).
        let mut sub = SubStep::zeroed();
        loop {
            let rem = dt - s;
            if rem <= 0.0 || rem.is_nan() {
                return Ok((state, regime, slip, None));
            }
            let t = t0 + s;
            match regime {
                Regime::Free => match self.free_piece(t, state, rem, report) {
                    Err(end) => return Ok((end, regime, slip, None)),
                    Ok((se, p)) => {
                        report.events.push(Event {
                            time: t + se,
                            kind: EventKind::Enter,
                            state: p.state,
                        });
                        check_bounded(t + se, p.state)?;
                        (s, state, regime) = (s + se, p.state, Regime::Contact);
                        slip =
                            Slip::at(&self.params, regime, t + se, &state, Some(EventKind::Enter));
                        if stop_at_switch {
                            return Ok((state, regime, slip, Some(t + se)));
                        }
                    }
                },
                Regime::Contact | Regime::Rolling if budget == 0 => {
                    // Cap exhausted: one last sub-step to the end, no switch search.
                    report.capped = true;
                    let end = if regime == Regime::Rolling {
                        self.rolling_substep(t, state, rem, &slip, report)?.0
                    } else {
                        self.substep(t, state, rem, slip.sigma, report, &mut sub)?;
                        sub.end
                    };
                    let end_regime = field::regime_of(&self.params, t0 + dt, &end);
                    let slip = Slip::at(&self.params, end_regime, t0 + dt, &end, None);
                    return Ok((end, end_regime, slip, None));
                }
                Regime::Contact | Regime::Rolling => {
                    // Whole nominal sub-steps over the rest, equal lengths, no slivers.
                    let k = whole_substeps(rem / nominal);
                    let h = if budget == 1 && k > 1 {
                        report.capped = true;
                        rem
                    } else {
                        rem / f64::from(k)
                    };
                    budget -= 1;
                    let (end, found) = if regime == Regime::Rolling {
                        self.rolling_substep(t, state, h, &slip, report)?
                    } else {
                        self.substep(t, state, h, slip.sigma, report, &mut sub)?;
                        let exit = self
                            .exit_in(&sub, state, report)
                            .map(|(sx, p)| (sx, p.state, EventKind::Exit));
                        let limit = exit.map_or(sub.length, |(sx, _, _)| sx);
                        (sub.end, self.slip_in(&sub, t, state, &slip, limit).or(exit))
                    };
                    match found {
                        Some((sx, p, kind)) => {
                            report.events.push(Event {
                                time: t + sx,
                                kind,
                                state: p,
                            });
                            regime = kind.regime_after();
                            slip = Slip::at(&self.params, regime, t + sx, &p, Some(kind));
                            (s, state) = (s + sx, p);
                            if stop_at_switch {
                                return Ok((state, regime, slip, Some(t + sx)));
                            }
                        }
                        None if h == rem => return Ok((end, regime, slip, None)),
                        None => (s, state) = (s + h, end),
                    }
                }
            }
        }
    }

    /// The first contact entry of free flight from `state` at `t` within (0, `rem`] as
    /// `Ok((s, point))`, or `Err(end state)` when there is none.
    fn free_piece(
        &self,
        t: f64,
        state: State,
        rem: f64,
        report: &mut StepReport,
    ) -> Result<(f64, Point), State> {
        let p = &self.params;
        let tr = &self.transition;
        let seg =
            FreeSegment::with_offset_distance(p, tr.constants(), tr.offset_distance(), t, state);
        let start = geometry::point(tr.constants().model(), state);
        let end = seg.point(rem);
        // h holds frequencies up to 2·max(η, 1): chunks as in `FreeFlight`.
        let chunk = 0.5 / p.speed_ratio.max(1.0 + p.damping_ratio);
        let found = locate_with(
            &seg,
            (0.0, start),
            (rem, end),
            Direction::Up,
            chunk,
            self.config.budget(),
        );
        resolve(found, report).ok_or(end.state)
    }

    /// One contact sub-step of the configured scheme from `state` at `t` over `h`, into `sub`.
    fn substep(
        &self,
        t: f64,
        state: State,
        h: f64,
        sigma: f64,
        report: &mut StepReport,
        sub: &mut SubStep,
    ) -> Result<(), StepperError> {
        // The contact constants are built per sub-step rather than kept in the stepper: a copy
        // of the parameters and one generated gain (a few ns against a sub-step's hundreds),
        // where a kept copy made every stepper 112 bytes larger, two cache lines that each cold
        // step and parameter change pays (`benches/stepper.rs`).
        let contact = &ContactConstants::new(&self.params);
        match self.config.scheme {
            ContactScheme::Exprb2 => exprb2_with(contact, sigma, t, state, h, sub),
            ContactScheme::Exprb43 => exprb43_with(contact, sigma, t, state, h, 1.0, sub),
        }
        .map_err(|_| PropagationError::SingularContact { time: t })?;
        check_bounded(t + h, sub.end)?;
        report.substeps += 1;
        report.error_estimate = report.error_estimate.max(sub.error);
        Ok(())
    }

    /// The contact exit on the sub-step's continuous extension, if any.
    fn exit_in(
        &self,
        sub: &SubStep,
        state: State,
        report: &mut StepReport,
    ) -> Option<(f64, Point)> {
        let model = self.transition.constants().model();
        let start = geometry::point(model, state);
        let end = geometry::point(model, sub.end);
        let found = locate_with(
            &sub.segment,
            (0.0, start),
            (sub.length, end),
            Direction::Down,
            sub.length,
            self.config.budget(),
        );
        resolve(found, report)
    }
}

/// The switch of a search, if any; a capped search is flagged in the report.
fn resolve(found: Search<Point>, report: &mut StepReport) -> Option<(f64, Point)> {
    match found {
        Search::None => None,
        Search::Unresolved => {
            report.search_capped = true;
            None
        }
        Search::Found { s, point, certain } => {
            report.search_capped |= !certain;
            Some((s, point))
        }
    }
}

/// ⌈q − slack⌉, at least 1 (q ≤ `MAX_SUBSTEPS` here; the cast saturates, never panics).
fn whole_substeps(q: f64) -> u32 {
    let q = q - SUBSTEP_SLACK;
    let k = q as u32;
    let k = if f64::from(k) < q {
        k.saturating_add(1)
    } else {
        k
    };
    k.max(1)
}
