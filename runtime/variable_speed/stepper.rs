//! The fixed-step stepper on a speed profile (`docs/MODEL.md` §14): each step of length dt
//! holds the speed and its rate at their values over the step ([`HeldSpeed::between`] its two
//! ends: the phase exact at every step end) and takes one [`Stepper`] step with that held
//! forcing. The parameters change only when the held speed does, so a profile that holds its
//! speed runs the constant-speed stepper, bit for bit.
//!
//! Cost: where the speed changes every step re-parametrizes the stepper
//! ([`Stepper::set_params`]: Φ(dt) kept, the forcing's columns G(dt) recomputed, about
//! 0.08 µs), about doubling a free step's cost.

use super::options::VariableSpeedError;
use super::segment::{check_held_unbalance, check_profile_fits};
use crate::params::{Params, Problem};
use crate::speed::{HeldSpeed, SpeedPiece, SpeedProfile};
use crate::stepper::{StepReport, Stepper, StepperConfig, StepperError};

/// A [`Stepper`] following a speed profile. No heap: the profile's points are borrowed.
#[derive(Clone, Copy, Debug)]
pub struct SpeedProfileStepper<'a> {
    stepper: Stepper,
    profile: SpeedProfile<'a>,
    params: Params,
    cursor: SpeedPiece,
}

impl<'a> SpeedProfileStepper<'a> {
    /// Start on `profile` from `problem`'s initial state at the profile's first time (the
    /// problem's start time; its speed ratio is not used, its phase is φ0 as at a constant
    /// speed), with the stepper configured by `config`.
    pub fn new(
        problem: &Problem,
        profile: SpeedProfile<'a>,
        config: StepperConfig,
    ) -> Result<Self, VariableSpeedError> {
        let cursor = profile.first_piece(problem.params.phase);
        check_profile_fits(problem, &profile)?;
        check_held_unbalance(&profile, &problem.params)?;
        let start = Problem {
            params: HeldSpeed::of_piece(&cursor).params(&problem.params),
            ..*problem
        };
        let stepper = Stepper::new(&start, config).map_err(VariableSpeedError::Stepper)?;
        Ok(SpeedProfileStepper {
            stepper,
            profile,
            params: problem.params,
            cursor,
        })
    }

    /// Advance exactly `dt` with the speed held over the step (see the module documentation).
    /// On error the stepper is left as it was before the step's parameters were set (a failed
    /// parameter change leaves it unchanged; a failed step after it keeps the new
    /// parameters, which the next step sets again).
    pub fn step(&mut self, dt: f64) -> Result<StepReport, StepperError> {
        let t0 = self.stepper.time();
        let t1 = t0 + dt;
        let first = self.profile.piece_holding(self.cursor, t0);
        let last = self.profile.piece_holding(first, t1);
        let held = if first == last && first.rate == 0.0 {
            HeldSpeed::of_piece(&first)
        } else {
            HeldSpeed::between((&first, t0), (&last, t1))
        };
        let params = held.params(&self.params);
        if params != *self.stepper.params() {
            self.stepper.set_params(&params)?;
        }
        self.cursor = first;
        self.stepper.step(dt)
    }

    /// The stepper (time, state, regime, parameters in force).
    pub fn stepper(&self) -> &Stepper {
        &self.stepper
    }

    /// The speed profile.
    pub fn profile(&self) -> &SpeedProfile<'a> {
        &self.profile
    }
}
