//! The model-file FMU's model: its variables (named after the model's DOFs), the matrix stepper
//! and the communication step.
//!
//! # Variables (value references)
//! | vr | name | causality | unit |
//! |---|---|---|---|
//! | 0 | `time` | independent | s |
//! | 1 | `internal_step` | parameter (fixed) | s |
//! | 2 | `in_contact` | output (Boolean) | |
//! | 3 | `contact_count` | output (UInt64 / Integer) | |
//! | 4, 5 | `rub_x`, `rub_y` | output: P = q_rotor − q_stator at the station | m |
//! | 100 + i | DOF i's name (`x1`, …) | output | m (rad on tilts) |
//! | 200 + i | `v` + its name (`vx1`, …) | output | m/s |
//! | 300 + i | `f_` + its name (`f_x1`, …) | input: force on DOF i, held over a step | N |
//!
//! The names are those of `rotor-rub simulate --model`'s columns (docs/MODEL_FILES.md).
//!
//! # Communication step
//! (t, t + h] in k = ⌈h / internal_step⌉ equal stepper steps (at most [`MAX_INTERNAL_STEPS`]);
//! every switch inside is located by the stepper's method (taylor by default: exact free
//! flight), so the result does not depend on h beyond rounding. A force input that changed
//! since the last step is applied at the step's start (`MatrixStepper::set_input`). A failed
//! step leaves the model at the step's start.

use rotor_rub::EventKind;
use rotor_rub::matrix::MatrixState;
use rotor_rub::propagate::Regime;
use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub::stepper::{MatrixStepper, OwnedModel};

use super::{CAPACITY, FileModel};
use crate::message::Message;
use crate::msg;
use crate::variables::Kind;

/// The default longest internal step, s.
pub const INTERNAL_STEP: f64 = 1e-3;
/// Most stepper steps in one communication step.
pub const MAX_INTERNAL_STEPS: u64 = 1_000_000;
/// Value reference of the first DOF's position.
pub const POSITION_BASE: u32 = 100;
/// Value reference of the first DOF's velocity.
pub const VELOCITY_BASE: u32 = 200;
/// Value reference of the first DOF's force input.
pub const FORCE_BASE: u32 = 300;

/// The FMI type of a model-file FMU variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// Float64 / Real.
    Float,
    /// Boolean.
    Boolean,
    /// UInt64 (FMI 3) / Integer (FMI 2).
    Count,
}

/// What a value reference is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileVariable {
    /// The time, s.
    Time,
    /// The longest internal step, s.
    InternalStep,
    /// Whether the station is in contact.
    InContact,
    /// Contact entries so far.
    ContactCount,
    /// The station's relative displacement, x (m).
    RubX,
    /// Its y (m).
    RubY,
    /// DOF i's position.
    Position(usize),
    /// DOF i's velocity.
    Velocity(usize),
    /// The force input on DOF i.
    Force(usize),
}

impl FileVariable {
    /// The variable's FMI type.
    pub fn kind(self) -> FileKind {
        match self {
            FileVariable::InContact => FileKind::Boolean,
            FileVariable::ContactCount => FileKind::Count,
            _ => FileKind::Float,
        }
    }
}

/// The model of a model-file FMU instance.
#[derive(Clone)]
pub struct FileRun {
    /// The statement in SI, as read from the resource.
    pub file: FileModel,
    /// The longest internal step, s.
    pub internal_step: f64,
    /// The force inputs, N.
    pub force: Vec<f64>,
    /// The forces the stepper runs with (N): differs from `force` until the next step.
    applied: Vec<f64>,
    /// The stepper, from the end of initialization on.
    pub stepper: Option<MatrixStepper<OwnedModel<CAPACITY>, CAPACITY>>,
    /// Contact entries so far.
    pub contact_count: u64,
    /// The start time, s (the experiment's; the file's initial state holds there).
    pub start_time: f64,
}

impl core::fmt::Debug for FileRun {
    /// The model and where it is (the stepper is not `Debug`).
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FileRun")
            .field("model", &self.file.name)
            .field("time", &self.time())
            .field("internal_step", &self.internal_step)
            .field("force", &self.force)
            .field("contact_count", &self.contact_count)
            .finish_non_exhaustive()
    }
}

impl FileRun {
    /// The model of `file`, every value at its start.
    pub fn new(file: FileModel) -> FileRun {
        let force = file.force.clone();
        FileRun {
            applied: force.clone(),
            force,
            file,
            internal_step: INTERNAL_STEP,
            stepper: None,
            contact_count: 0,
            start_time: 0.0,
        }
    }

    /// The variable behind `vr`, if any.
    pub fn variable(&self, vr: u32) -> Option<FileVariable> {
        let n = self.file.n();
        let index = |base: u32| vr.checked_sub(base).map(|i| i as usize).filter(|&i| i < n);
        Some(match vr {
            0 => FileVariable::Time,
            1 => FileVariable::InternalStep,
            2 => FileVariable::InContact,
            3 => FileVariable::ContactCount,
            4 => FileVariable::RubX,
            5 => FileVariable::RubY,
            _ => {
                if let Some(i) = index(POSITION_BASE) {
                    FileVariable::Position(i)
                } else if let Some(i) = index(VELOCITY_BASE) {
                    FileVariable::Velocity(i)
                } else if let Some(i) = index(FORCE_BASE) {
                    FileVariable::Force(i)
                } else {
                    return None;
                }
            }
        })
    }

    /// Check that `vr` is a variable of one of the FMI `kinds` (a get or set of that type):
    /// Float64/Real for the floats, Boolean for `in_contact`, Int64/Integer for
    /// `contact_count`.
    ///
    /// # Errors
    /// An unknown value reference, or a variable of another type.
    pub fn check_kind(&self, vr: u32, kinds: &[Kind]) -> Result<(), Message> {
        let var = self
            .variable(vr)
            .ok_or_else(|| msg!("unknown value reference {vr} (see modelDescription.xml)"))?;
        let kind = match var.kind() {
            FileKind::Float => Kind::Float,
            FileKind::Boolean => Kind::Bool,
            FileKind::Count => Kind::Int64,
        };
        if kinds.contains(&kind) {
            Ok(())
        } else {
            Err(msg!(
                "value reference {vr} ({var:?}) is of type {kind:?}, not {kinds:?}"
            ))
        }
    }

    /// Build the stepper at the start time (end of initialization).
    ///
    /// # Errors
    /// The internal step out of range, or what the runtime refuses in the statement.
    pub fn initialize(&mut self) -> Result<(), String> {
        let dt = self.internal_step;
        if !(dt.is_finite() && dt > 0.0 && dt <= rotor_rub::stepper::MAX_STEP) {
            return Err(format!(
                "internal_step = {dt} is out of range: it must be in (0, {}] s",
                rotor_rub::stepper::MAX_STEP
            ));
        }
        let mut file = self.file.clone();
        file.force.clone_from(&self.force);
        let model = file.state()?;
        let start = file.start()?;
        let stepper = MatrixStepper::new(
            model,
            self.start_time,
            start,
            MatrixStepperConfig::with_dt(dt),
        )
        .map_err(|e| format!("cannot initialize: {e}"))?;
        self.stepper = Some(stepper);
        self.applied.clone_from(&self.force);
        self.contact_count = 0;
        Ok(())
    }

    /// Set a parameter (before initialization) or an input.
    ///
    /// # Errors
    /// A variable that cannot be set now, or a value out of range.
    pub fn set(&mut self, vr: u32, value: f64) -> Result<(), String> {
        match self.variable(vr) {
            Some(FileVariable::InternalStep) if self.stepper.is_none() => {
                self.internal_step = value;
                Ok(())
            }
            Some(FileVariable::Force(i)) => {
                if !value.is_finite() {
                    return Err(format!(
                        "f_{} = {value} is not a force: it must be finite (N)",
                        self.file.dofs.get(i).map_or("?", String::as_str)
                    ));
                }
                if let Some(f) = self.force.get_mut(i) {
                    *f = value;
                }
                Ok(())
            }
            Some(v) => Err(format!("{v:?} (value reference {vr}) cannot be set now")),
            None => Err(format!("unknown value reference {vr}")),
        }
    }

    /// The state in clearances: the stepper's, or the start before initialization.
    fn state(&self) -> MatrixState<CAPACITY> {
        match &self.stepper {
            Some(s) => s.state(),
            None => self
                .file
                .start()
                .unwrap_or_else(|_| MatrixState::full([0.0; CAPACITY])),
        }
    }

    /// The time, s.
    pub fn time(&self) -> f64 {
        self.stepper
            .as_ref()
            .map_or(self.start_time, MatrixStepper::time)
    }

    /// The value of `vr` in SI (booleans 0/1, counts exact up to 2⁵³).
    ///
    /// # Errors
    /// An unknown value reference.
    pub fn get(&self, vr: u32) -> Result<f64, String> {
        let var = self
            .variable(vr)
            .ok_or_else(|| format!("unknown value reference {vr}"))?;
        let delta = self.file.clearance;
        let n = self.file.n();
        let y = self.state();
        let rub = |k: usize| {
            let (r, s) = (self.file.rub, self.file.stator);
            let (ri, si) = if k == 0 {
                (r.0, s.map(|s| s.0))
            } else {
                (r.1, s.map(|s| s.1))
            };
            (y.get(ri) - si.map_or(0.0, |i| y.get(i))) * delta
        };
        Ok(match var {
            FileVariable::Time => self.time(),
            FileVariable::InternalStep => self.internal_step,
            FileVariable::InContact => {
                let regime = self
                    .stepper
                    .as_ref()
                    .map_or(Regime::Free, MatrixStepper::regime);
                f64::from(u8::from(regime != Regime::Free))
            }
            FileVariable::ContactCount => self.contact_count as f64,
            FileVariable::RubX => rub(0),
            FileVariable::RubY => rub(1),
            FileVariable::Position(i) => y.get(i) * delta,
            FileVariable::Velocity(i) => y.get(n + i) * delta,
            FileVariable::Force(i) => self.force.get(i).copied().unwrap_or(0.0),
        })
    }

    /// Cover (t, t + h] (see the module docs). On error the model is back at the step's start.
    ///
    /// # Errors
    /// Not initialized, h not positive and finite, more than [`MAX_INTERNAL_STEPS`] needed, or
    /// the stepper's refusal.
    pub fn do_step(&mut self, h: f64) -> Result<(), String> {
        let Some(stepper) = self.stepper.as_mut() else {
            return Err("doStep before the end of initialization".to_owned());
        };
        if !(h.is_finite() && h > 0.0) {
            return Err(format!(
                "the communication step h = {h} must be positive and finite (s)"
            ));
        }
        // A step of whole internal steps within rounding takes that many.
        let steps = (h / self.internal_step * (1.0 - 1e-12)).ceil().max(1.0);
        if steps > MAX_INTERNAL_STEPS as f64 {
            return Err(format!(
                "h = {h} s needs {steps} internal steps of at most {} s: at most {MAX_INTERNAL_STEPS} are taken in one step",
                self.internal_step
            ));
        }
        let backup = stepper.snapshot();
        let dt = h / steps;
        let delta = self.file.clearance;
        let result = (|| {
            if self.force != self.applied {
                let scaled: Vec<f64> = self.force.iter().map(|f| f / delta).collect();
                stepper
                    .set_input(&scaled)
                    .map_err(|e| format!("cannot apply the force: {e}"))?;
            }
            let mut entries = 0;
            for _ in 0..steps as u64 {
                let r = stepper.step(dt).map_err(|e| format!("step refused: {e}"))?;
                entries += r
                    .events
                    .iter()
                    .filter(|e| e.kind == EventKind::Enter)
                    .count() as u64;
            }
            Ok(entries)
        })();
        match result {
            Ok(entries) => {
                self.contact_count += entries;
                self.applied.clone_from(&self.force);
                Ok(())
            }
            Err(e) => {
                stepper.restore(&backup);
                Err(e)
            }
        }
    }
}
