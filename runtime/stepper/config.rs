//! How the stepper takes its steps: the step length Φ is precomputed for, the contact scheme,
//! the sub-step counts and caps, and what a step does when a cap is reached.

use super::{MAX_SUBSTEPS, StepperError};
use crate::analytic::switch::Budget;
use crate::registration::ContactScheme;

/// How the stepper takes its steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepperConfig {
    /// The step length Φ(dt) is precomputed for (a `step` with another length recomputes it).
    pub dt: f64,
    /// The contact scheme: exprb43 (fourth order, default) or exprb2 (second order, cheaper).
    pub scheme: ContactScheme,
    /// Contact sub-steps per `dt` (≥ 1): contact sub-steps are at most dt / `contact_substeps`,
    /// and at most 0.5/ρ_c on a stiff stator (more sub-steps then:
    /// [`super::Stepper::contact_substeps`]).
    pub contact_substeps: u32,
    /// Cap on contact sub-steps in one `step` call (≥ `contact_substeps`): bounds the work of a
    /// step with several switches, or of a step in contact on a stator stiffer than the cap
    /// allows at this `dt` ([`super::Stepper::largest_resolved_dt`]). See
    /// [`super::StepReport::capped`].
    pub max_substeps: u32,
    /// What a step does when a cap is reached: [`OnCap::Degrade`] (the default) finishes the
    /// step less accurately and flags it; [`OnCap::Fail`] returns
    /// [`StepperError::BudgetExceeded`] and leaves the stepper unchanged (a hard real-time
    /// caller then knows the step would have overrun its bounded work).
    pub on_cap: OnCap,
    /// How a located switch's refinement starts: [`SwitchStart::Newton`] (the default, the
    /// analytic method's) or [`SwitchStart::Hermite`] (fewer closed-form evaluations per switch,
    /// the same switch to rounding: for a tighter worst-case step time).
    pub switch_start: SwitchStart,
}

/// How the refinement of a located switch starts (the switch kernel's `Budget::hermite_start`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SwitchStart {
    /// Safeguarded Newton from the bracket's end with the smaller residual.
    #[default]
    Newton,
    /// From the root of the bracket's cubic Hermite interpolant (g, g′ at both ends): one
    /// Newton step on the closed form from there converges.
    Hermite,
}

/// What a step does when its sub-step cap or a switch search's cap is reached.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OnCap {
    /// Finish the step: the last contact sub-step covers the rest, a capped search gives its
    /// last bracket; [`crate::StepReport::capped`] / [`crate::StepReport::search_capped`] say so.
    #[default]
    Degrade,
    /// Return [`StepperError::BudgetExceeded`] instead; the stepper is unchanged.
    Fail,
}

impl Default for StepperConfig {
    /// dt = 1e-3, exprb43, one contact sub-step per step, at most 8 per step.
    fn default() -> Self {
        StepperConfig {
            dt: 1e-3,
            scheme: ContactScheme::Exprb43,
            contact_substeps: 1,
            max_substeps: 8,
            on_cap: OnCap::Degrade,
            switch_start: SwitchStart::Newton,
        }
    }
}

impl StepperConfig {
    /// The default configuration with step length `dt`.
    pub fn with_dt(dt: f64) -> Self {
        StepperConfig {
            dt,
            ..StepperConfig::default()
        }
    }

    /// The switch searches' budget: the capped one, with the configured refinement start.
    pub(super) fn budget(&self) -> &'static Budget {
        match self.switch_start {
            SwitchStart::Newton => &Budget::CAPPED,
            SwitchStart::Hermite => &Budget::CAPPED_HERMITE,
        }
    }

    pub(super) fn validate(&self) -> Result<(), StepperError> {
        let invalid = |what, value: u32| StepperError::InvalidConfig {
            what,
            value: f64::from(value),
        };
        if !(1..=MAX_SUBSTEPS).contains(&self.contact_substeps) {
            return Err(invalid("contact_substeps", self.contact_substeps));
        }
        if !(self.contact_substeps..=MAX_SUBSTEPS).contains(&self.max_substeps) {
            return Err(invalid("max_substeps", self.max_substeps));
        }
        Ok(())
    }
}
