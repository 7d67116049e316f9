//! Setting a variable.
//!
//! * Before initialization every value is staged; the parameter set is validated as a whole
//!   (ranges in the importer's units, cross-parameter rules) when initialization ends.
//! * After it, an input (fx, fy, the speed) takes effect at once: it is checked against its
//!   range and applied to the stepper (inputs enter no cross-parameter rule).
//! * A tunable parameter is checked against its own range when set, and staged; the staged set
//!   is validated as a whole, and applied as one, by the next communication step
//!   ([`Model::apply_pending`]). So the outcome does not depend on the order of the sets (μ > 0,
//!   then k_xy = 50, then k_yx = −50 is the same as the reverse order), and a refused set
//!   changes nothing: the stepper never runs on a mix of old and new values.

use rotor_rub::params::Number;
use rotor_rub::{ParamError, Parameter, Params, Problem};

use super::Model;
use crate::message::Message;
use crate::msg;
use crate::units::{Dimension, Units};
use crate::variables::{self, Role, Setting, Target, Variable, dimension};

impl Model {
    /// Set variable `vr` to `value` (importer units), checked against its range and causality
    /// (see the module docs for when it takes effect); on error nothing changes.
    pub fn set(&mut self, vr: u32, value: f64) -> Result<(), Message> {
        if let Some(f) = &mut self.file {
            return f.set(vr, value).map_err(|e| msg!("{e}"));
        }
        let var = self.variable(vr)?;
        let initialized = self.stepper.is_some();
        match var.role {
            Role::ContinuousOutput | Role::DiscreteOutput | Role::Independent => {
                return Err(msg!(
                    "variable {} (vr {vr}) is computed by the FMU: it cannot be set",
                    var.name
                ));
            }
            Role::Fixed if initialized => {
                return Err(msg!(
                    "{} is fixed: it cannot change after initialization (tried {value})",
                    var.name
                ));
            }
            _ => {}
        }
        if !value.is_finite() {
            return Err(msg!("{} = {value} is not a finite number", var.name));
        }
        match var.target {
            Target::Table(p) => self.set_table(p, &var, value),
            Target::Setting(s) => self.set_setting(s, &var, value),
            Target::Output(_) => Err(msg!("{} is an output: it cannot be set", var.name)),
        }
    }

    fn set_table(&mut self, p: Parameter, var: &Variable, value: f64) -> Result<(), Message> {
        let model_value = self.scales().to_model(var.dimension, value);
        let scale_free = matches!(var.dimension, Dimension::One | Dimension::Angle);
        if self.stepper.is_none() && self.units == Units::Si && !scale_free {
            // Before initialization the SI scales may still change: an SI value is checked for
            // its sign here and against its whole range when initialization ends.
            let range = p.range();
            let below = if range.min_open {
                value <= 0.0
            } else {
                value < 0.0
            };
            if range.min >= 0.0 && below {
                let bound = if range.min_open { "> 0" } else { ">= 0" };
                return Err(msg!(
                    "{} = {} {} is out of range: it must be {bound}",
                    var.name,
                    Number(value),
                    var.dimension.unit(self.units)
                ));
            }
        } else if let Err(e) = p.check(model_value) {
            let params = self
                .stepper
                .as_ref()
                .map_or(Params::DEFAULT, |s| *s.params());
            return Err(self.refusal("refused", e, &params));
        }
        if let Some(stepper) = self.stepper.as_mut() {
            let applied = match p {
                Parameter::ForceX => stepper.set_input_force(model_value, stepper.input_force().1),
                Parameter::ForceY => stepper.set_input_force(stepper.input_force().0, model_value),
                Parameter::SpeedRatio => stepper.set_speed_ratio(model_value),
                _ => {
                    self.pending = true;
                    Ok(())
                }
            };
            applied.map_err(|e| msg!("{} = {value} refused: {e}", var.name))?;
        }
        p.set(&mut self.requested, value);
        Ok(())
    }

    fn set_setting(&mut self, s: Setting, var: &Variable, value: f64) -> Result<(), Message> {
        let (lo, hi) = (var.min.unwrap_or(f64::MIN), var.max.unwrap_or(f64::MAX));
        let integral = var.kind != variables::Kind::Float;
        if !(lo..=hi).contains(&value) || (integral && value.fract() != 0.0) {
            return Err(msg!(
                "{} = {} is out of range: it must be {}in [{}, {}]",
                var.name,
                Number(value),
                if integral { "an integer " } else { "" },
                Number(lo),
                Number(hi)
            ));
        }
        let st = &mut self.settings;
        match s {
            Setting::InternalStep => st.internal_step = value,
            Setting::Tolerance => st.tolerance = value,
            // In range [1, 2³¹ − 1] and integral: exact.
            Setting::MaxInternalSteps => st.max_internal_steps = value as u32,
            Setting::NaturalFrequency => st.scales.natural_frequency = value,
            Setting::Clearance => st.scales.clearance = value,
            Setting::Mass => st.scales.mass = value,
        }
        Ok(())
    }

    /// Apply the tunable parameters set since the last step, validated as one set (ranges and
    /// cross-parameter rules). On error nothing changes and the set stays staged: the importer
    /// sets consistent values and steps again.
    pub fn apply_pending(&mut self) -> Result<(), Message> {
        let Some(current) = self.stepper.as_ref().map(|s| *s.params()) else {
            return Err(msg!("doStep before the end of initialization"));
        };
        if !self.pending {
            return Ok(());
        }
        let mut candidate = Problem {
            params: current,
            ..Problem::DEFAULT
        };
        let tunable = Parameter::ALL.into_iter().filter(|&p| {
            variables::of_parameter(p, self.units).is_some_and(|v| v.role == Role::Tunable)
        });
        for p in tunable {
            p.set(&mut candidate, self.model_value(p));
        }
        let params = candidate.params;
        let Some(stepper) = self.stepper.as_mut() else {
            return Err(msg!("doStep before the end of initialization"));
        };
        let checked = params.validate().map_err(Into::into);
        match checked.and_then(|()| stepper.set_params(&params)) {
            Ok(()) => {
                self.pending = false;
                Ok(())
            }
            Err(rotor_rub::StepperError::Propagation(
                rotor_rub::PropagationError::InvalidProblem(e),
            )) => Err(self.refusal(
                "the parameters set since the last step are refused as a set, nothing changed",
                e,
                &params,
            )),
            Err(e) => Err(msg!(
                "the parameters set since the last step are refused: {e}"
            )),
        }
    }

    /// A refused parameter value or set, in the importer's names and units.
    pub fn refusal(&self, context: &str, e: ParamError, params: &Params) -> Message {
        let scales = self.scales();
        let units = self.units;
        let name =
            |p: Parameter| variables::of_parameter(p, units).map_or_else(|| p.name(), |v| v.name);
        match e {
            ParamError::NonFinite { parameter, value } => {
                msg!(
                    "{context}: {} = {value} is not a finite number",
                    name(parameter)
                )
            }
            ParamError::OutOfRange {
                parameter: Parameter::StartTime,
                value,
                range,
            } => msg!(
                "{context}: the start time {} gives τ0 = {} out of range: it must be in {range}",
                Number(self.start_time),
                Number(value)
            ),
            ParamError::OutOfRange {
                parameter,
                value,
                range,
            } => {
                let d = dimension(parameter);
                let to = |x| scales.to_importer(d, x);
                let open = if range.min_open { '(' } else { '[' };
                let unit = match d.unit(units) {
                    "1" => "",
                    u => u,
                };
                msg!(
                    "{context}: {} = {}{}{unit} is out of range: it must be in {open}{}, {}]{}{unit}{}",
                    name(parameter),
                    Number(to(value)),
                    if unit.is_empty() { "" } else { " " },
                    Number(to(range.min)),
                    Number(to(range.max)),
                    if unit.is_empty() { "" } else { " " },
                    if unit.is_empty() || matches!(d, Dimension::Angle) {
                        ""
                    } else {
                        " (the model's range scaled by ω_n, δ and M)"
                    }
                )
            }
            ParamError::FrictionNeedsDefiniteStator {
                friction_coefficient,
                ..
            } => {
                let k = |x| Number(scales.to_importer(Dimension::Stiffness, x));
                let unit = Dimension::Stiffness.unit(units);
                msg!(
                    "{context}: friction_coefficient = {} needs a stator stiffness with a positive definite symmetric part (k_xx > 0, k_yy > 0, k_xx·k_yy > ((k_xy + k_yx)/2)²); the set has k_xx = {}, k_xy = {}, k_yx = {}, k_yy = {} ({unit})",
                    Number(friction_coefficient),
                    k(params.k_xx),
                    k(params.k_xy),
                    k(params.k_yx),
                    k(params.k_yy)
                )
            }
            ParamError::RingNeedsMatrixModel { stator_mass_ratio } => {
                msg!(
                    "{context}: stator_mass_ratio = {} states a stator ring with mass, which this FMU does not run (it runs the massless ring only)",
                    Number(stator_mass_ratio)
                )
            }
            ParamError::RingWithoutMass { parameter, value } => {
                let d = dimension(parameter);
                msg!(
                    "{context}: {} = {} has no effect while stator_mass_ratio = 0 (the massless ring's support is the contact spring): set stator_mass_ratio > 0 or leave {} at its start value",
                    name(parameter),
                    Number(scales.to_importer(d, value)),
                    name(parameter)
                )
            }
        }
    }
}
