//! The exact path of a step: the shared driver ([`crate::driver::Piecewise`]) over the step's
//! solvers (`solvers.rs`: exact free pieces, contact sub-steps of exprb43/exprb2, rolling
//! sub-steps, switches located by the capped search of [`super::search`]), from the step's start
//! to its end or (stopping at a switch) its first switch.

use super::friction::Slip;
use super::report::StepReport;
use super::solvers::{Frame, carried_slip, step_solvers};
use super::{Stepper, StepperError};
use crate::analytic::schemes::SubStep;
use crate::driver::{Borrowed, Piecewise};
use crate::field;
use crate::params::State;
use crate::propagate::{Propagate, Regime};

impl Stepper {
    /// The step from the current state over `dt`, piece by piece; fills the report's events,
    /// sub-step count, cap flags and error estimate. Returns the end state, regime and slip, and
    /// with `stop_at_switch` the switch time where the step stopped at its first switch.
    pub(super) fn exact_step(
        &self,
        dt: f64,
        stop_at_switch: bool,
        report: &mut StepReport,
    ) -> Result<(State, Regime, Slip, Option<f64>), StepperError> {
        let t0 = self.time;
        let frame = Frame::new(self, t0, dt);
        // The contact sub-steps' slot, on this stack (a sub-step is too large to move).
        let mut sub = SubStep::zeroed();
        let mut solvers = step_solvers(&frame, &mut sub, self.regime, self.state, self.slip);
        let mut driver = Piecewise::resume(
            Borrowed(&self.params),
            t0,
            self.state,
            self.regime,
            self.slip.sigma,
            &mut solvers,
        );
        let end = t0 + dt;
        let stopped = loop {
            match driver.advance(end)? {
                Some(event) => {
                    report.events.push(event);
                    if stop_at_switch {
                        break Some(event.time);
                    }
                }
                None => break None,
            }
        };
        let (state, mut regime) = (driver.state(), driver.regime());
        let mut slip = carried_slip(&solvers, regime);
        frame.report_into(report);
        if stopped.is_none() && frame.exhausted() {
            // The budget ran out before the end: the last sub-step went there unsearched, so
            // the regime at the end is read from the end state.
            regime = field::regime_of(&self.params, end, &state);
            slip = Slip::at(&self.params, regime, end, &state, None);
        }
        Ok((state, regime, slip, stopped))
    }
}
