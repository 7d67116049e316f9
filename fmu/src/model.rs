//! The FMU's model, shared by the FMI 2.0 and 3.0 layers: parameters and inputs staged before
//! initialization, the stepper after it, the communication step covered by internal steps, and
//! the outputs. Plain data (`Copy`): a saved FMU state is a copy; no call after instantiation
//! allocates.
//!
//! # A communication step
//! [`Model::do_step`] covers (t, t + h] with stepper steps of at most `internal_step`, so the
//! accuracy does not depend on h. A step whose exprb43 error estimate exceeds `tolerance` is
//! undone (the stepper is `Copy`) and retried at half the length (at most
//! [`MAX_HALVINGS`] times; the length grows back by doubling when the estimate is 64× below the
//! tolerance). Every contact switch inside is located exactly by the stepper; with early return
//! the step ends at the first one ([`Stepper::step_to_switch`]) and reports its time.

use rotor_rub::stepper::{OnCap, Stepper, StepperConfig};
use rotor_rub::{Parameter, Problem, Regime, field};

use crate::message::Message;
use crate::msg;
use crate::variables::{self, Output, Setting, Target};

/// Most halvings of one internal step (2⁻¹² of `internal_step`).
pub const MAX_HALVINGS: u32 = 12;

/// The FMU's settings (`variables::SETTINGS`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Longest internal step.
    pub internal_step: f64,
    /// Accepted error estimate.
    pub tolerance: f64,
}

/// How a communication step ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepped {
    /// At t + h.
    Completed,
    /// Early, at a switch at this time (early return only).
    EarlyReturn(f64),
}

/// The model of one FMU instance.
#[derive(Clone, Copy, Debug)]
pub struct Model {
    /// Parameters, input force and speed, initial state; the stepper's own after initialization.
    pub problem: Problem,
    /// The settings.
    pub settings: Settings,
    /// The stepper, from the end of initialization on.
    pub stepper: Option<Stepper>,
    /// Contact entries so far.
    pub contact_count: u64,
    /// The next internal step length (step control).
    pub next_step: f64,
}

impl Default for Model {
    fn default() -> Self {
        Model {
            problem: Problem::DEFAULT,
            settings: Settings {
                internal_step: variables::INTERNAL_STEP,
                tolerance: variables::TOLERANCE,
            },
            stepper: None,
            contact_count: 0,
            next_step: variables::INTERNAL_STEP,
        }
    }
}

impl Model {
    /// Build the stepper at `start_time` (end of initialization).
    pub fn initialize(&mut self, start_time: f64) -> Result<(), Message> {
        let mut problem = self.problem;
        problem.start_time = start_time;
        let config = StepperConfig {
            on_cap: OnCap::Degrade,
            ..StepperConfig::with_dt(self.settings.internal_step)
        };
        let stepper = Stepper::new(&problem, config)
            .map_err(|e| msg!("cannot initialize at start time {start_time}: {e}"))?;
        self.problem = problem;
        self.stepper = Some(stepper);
        self.next_step = self.settings.internal_step;
        self.contact_count = 0;
        Ok(())
    }

    /// The value of variable `vr` as f64 (booleans 0/1, counts as f64 exactly up to 2⁵³).
    pub fn get(&self, vr: u32) -> Result<f64, Message> {
        let var = variables::find(vr).ok_or_else(|| unknown(vr))?;
        Ok(match var.target {
            Target::Table(p) => p.get(&self.current_problem()),
            Target::Setting(Setting::InternalStep) => self.settings.internal_step,
            Target::Setting(Setting::Tolerance) => self.settings.tolerance,
            Target::Output(o) => self.output(o),
        })
    }

    /// The problem in force: the staged one before initialization, the stepper's after.
    fn current_problem(&self) -> Problem {
        let mut p = self.problem;
        if let Some(s) = &self.stepper {
            p.params = *s.params();
        }
        p
    }

    fn output(&self, o: Output) -> f64 {
        let (state, regime, sigma) = match &self.stepper {
            Some(s) => (s.state(), s.regime(), s.slip_direction()),
            None => {
                let p = &self.problem;
                let regime = field::regime_of(&p.params, p.start_time, &p.initial);
                (p.initial, regime, 0.0)
            }
        };
        let in_contact = regime != Regime::Free;
        match o {
            Output::Time => self
                .stepper
                .as_ref()
                .map_or(self.problem.start_time, Stepper::time),
            Output::X => state.x,
            Output::Y => state.y,
            Output::Vx => state.vx,
            Output::Vy => state.vy,
            Output::InContact => f64::from(u8::from(in_contact)),
            Output::NormalForce if in_contact => {
                let p = self.current_problem();
                let t = self.stepper.as_ref().map_or(p.start_time, Stepper::time);
                field::friction_at(&p.params, t, &state).normal
            }
            Output::NormalForce => 0.0,
            Output::ContactCount => self.contact_count as f64,
            Output::SlipRegime => match regime {
                Regime::Free => 0.0,
                Regime::Rolling => 4.0,
                Regime::Contact if sigma > 0.0 => 2.0,
                Regime::Contact if sigma < 0.0 => 3.0,
                Regime::Contact => 1.0,
            },
        }
    }

    /// Set variable `vr` to `value`: checked against its range and causality; on error nothing
    /// changes. Before initialization every parameter and input may be set; after it the inputs
    /// (cheap for fx, fy; the free map's forcing columns recomputed for speed_ratio) and the
    /// tunable parameters (the free map recomputed, Φ kept unless the damping changes).
    pub fn set(&mut self, vr: u32, value: f64) -> Result<(), Message> {
        let var = variables::find(vr).ok_or_else(|| unknown(vr))?;
        if matches!(
            var.role,
            variables::Role::ContinuousOutput
                | variables::Role::DiscreteOutput
                | variables::Role::Independent
        ) {
            return Err(msg!(
                "variable {} (vr {vr}) is computed by the FMU: it cannot be set",
                var.name
            ));
        }
        let Some(stepper) = self.stepper.as_mut() else {
            return self.stage(var.target, var.name, value);
        };
        let p = match var.target {
            Target::Table(p) => p,
            Target::Setting(_) | Target::Output(_) => {
                return Err(msg!(
                    "{} is fixed after initialization (tried to set it to {value})",
                    var.name
                ));
            }
        };
        p.check(value).map_err(|e| msg!("{}: {e}", var.name))?;
        let result = match p {
            Parameter::ForceX => stepper.set_input_force(value, stepper.input_force().1),
            Parameter::ForceY => stepper.set_input_force(stepper.input_force().0, value),
            Parameter::SpeedRatio => stepper.set_speed_ratio(value),
            _ if var.role == variables::Role::Tunable => {
                let mut problem = Problem {
                    params: *stepper.params(),
                    ..self.problem
                };
                p.set(&mut problem, value);
                stepper.set_params(&problem.params)
            }
            _ => {
                return Err(msg!(
                    "{} is a fixed parameter: it cannot change after initialization (tried {value})",
                    var.name
                ));
            }
        };
        result.map_err(|e| msg!("{} = {value} refused: {e}", var.name))
    }

    fn stage(&mut self, target: Target, name: &str, value: f64) -> Result<(), Message> {
        match target {
            Target::Table(p) => {
                p.check(value).map_err(|e| msg!("{name}: {e}"))?;
                p.set(&mut self.problem, value);
            }
            Target::Setting(s) => {
                let (lo, hi) = match s {
                    Setting::InternalStep => variables::INTERNAL_STEP_RANGE,
                    Setting::Tolerance => variables::TOLERANCE_RANGE,
                };
                if !(value.is_finite() && (lo..=hi).contains(&value)) {
                    return Err(msg!(
                        "{name} = {value} is out of range: it must be in [{lo}, {hi}]"
                    ));
                }
                match s {
                    Setting::InternalStep => self.settings.internal_step = value,
                    Setting::Tolerance => self.settings.tolerance = value,
                }
            }
            Target::Output(_) => return Err(msg!("{name} is an output: it cannot be set")),
        }
        Ok(())
    }

    /// Cover the communication step (`t`, `t` + `h`] (see the module docs); with
    /// `early_return` end at the first switch. On error the model is left at its last
    /// completed internal step.
    pub fn do_step(&mut self, t: f64, h: f64, early_return: bool) -> Result<Stepped, Message> {
        let settings = self.settings;
        let Some(stepper) = self.stepper.as_mut() else {
            return Err(msg!("doStep before the end of initialization"));
        };
        let now = stepper.time();
        let scale = 1.0 + t.abs().max(now.abs());
        if !t.is_finite() || (t - now).abs() > 1e-9 * scale {
            return Err(msg!(
                "communication point t = {t} does not match the FMU's time {now} (set the FMU state, or step from {now})"
            ));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(msg!(
                "communication step size h = {h} is invalid: it must be finite and > 0"
            ));
        }
        let end = t + h;
        let mut halvings = 0;
        loop {
            let remaining = end - stepper.time();
            if remaining <= 1e-12 * scale {
                return Ok(Stepped::Completed);
            }
            // A remainder within rounding of the step length takes the step length itself, so
            // that communication steps of whole internal steps keep one precomputed map.
            let dt = if remaining - self.next_step >= -1e-9 * self.next_step {
                self.next_step
            } else {
                remaining
            };
            let before = *stepper;
            let report = if early_return {
                stepper.step_to_switch(dt)
            } else {
                stepper.step(dt)
            }
            .map_err(|e| msg!("step of {dt} from t = {}: {e}", before.time()))?;
            if report.error_estimate > settings.tolerance && halvings < MAX_HALVINGS {
                *stepper = before;
                self.next_step = dt * 0.5;
                halvings += 1;
                continue;
            }
            halvings = 0;
            if report.events.overflowed() {
                // More switches than a report holds: redo the step switch by switch.
                *stepper = before;
                let stop = before.time() + dt;
                while stop - stepper.time() > 1e-12 * scale {
                    let r = stepper
                        .step_to_switch(stop - stepper.time())
                        .map_err(|e| msg!("step from t = {}: {e}", stepper.time()))?;
                    self.contact_count += entries(&r.events);
                }
            } else {
                self.contact_count += entries(&report.events);
            }
            if report.error_estimate * 64.0 < settings.tolerance {
                self.next_step = (self.next_step * 2.0).min(settings.internal_step);
            }
            if early_return && !report.events.is_empty() {
                return Ok(Stepped::EarlyReturn(stepper.time()));
            }
        }
    }
}

fn entries(events: &rotor_rub::EventList) -> u64 {
    events
        .iter()
        .filter(|e| e.kind == rotor_rub::EventKind::Enter)
        .count() as u64
}

fn unknown(vr: u32) -> Message {
    msg!("unknown value reference {vr} (see modelDescription.xml)")
}
