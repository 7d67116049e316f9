//! The FMU's variables, stated once per unit system (`units.rs`): the outputs and inputs of the
//! issue's contract (`outputs.rs`), every entry of the parameter table (`rotor_rub::Parameter`)
//! as a parameter, or as an input where the FMU drives it (`table.rs`), and the FMU's own
//! settings (`settings.rs`). The model description
//! (`description.rs`), the documentation (`documentation.rs`) and the value-reference dispatch
//! of `model.rs` all read this table.
//!
//! Value references (the same in both unit systems): time 0, outputs 1–8 and the stator ring's
//! 20–23, inputs 10–12, table
//! entries 100 + table index, settings 200–202, the SI FMU's scales 210–212. `start_time` is
//! not a variable: the FMU starts at the importer's start time.

mod outputs;
mod settings;
mod table;

pub use outputs::{outputs, time};
pub use settings::{default_scales, settings};
pub use table::{dimension, of_parameter};

use rotor_rub::Parameter;

use crate::units::{Dimension, Units};

/// The FMI type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Float64 (FMI 3) / Real (FMI 2).
    Float,
    /// Int64 (FMI 3) / Integer (FMI 2, saturating at 2³¹ − 1).
    Int64,
    /// Int32 (FMI 3) / Integer (FMI 2).
    Int32,
    /// Boolean.
    Bool,
}

/// A variable's causality and variability.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// The independent variable, time.
    Independent,
    /// An output that varies continuously (Float64).
    ContinuousOutput,
    /// An output that changes at switches only (counts, flags).
    DiscreteOutput,
    /// A continuous input, held constant over a communication step.
    Input,
    /// A parameter that may change between steps.
    Tunable,
    /// A parameter fixed at initialization.
    Fixed,
}

/// What a value reference reads or writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// An output of the model.
    Output(Output),
    /// An entry of the parameter table (an input or a parameter).
    Table(Parameter),
    /// One of the FMU's own settings.
    Setting(Setting),
}

/// The outputs (and the independent variable).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// Time (τ, or seconds in the SI FMU), the independent variable.
    Time,
    /// x.
    X,
    /// y.
    Y,
    /// x'.
    Vx,
    /// y'.
    Vy,
    /// In contact (slipping or rolling).
    InContact,
    /// The normal contact force N = nᵀK_s g (0 when free).
    NormalForce,
    /// Contact entries so far.
    ContactCount,
    /// 0 free, 1 frictionless contact, 2 slipping forward (w > 0), 3 slipping backward, 4 rolling.
    SlipRegime,
    /// The stator ring's centre x_s (0 for the massless ring).
    Xs,
    /// y_s.
    Ys,
    /// x_s'.
    Vxs,
    /// y_s'.
    Vys,
}

/// The FMU's own settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// The longest internal step (the stepper's dt).
    InternalStep,
    /// Largest accepted exprb43 error estimate of a contact sub-step.
    Tolerance,
    /// Most internal steps in one communication step (the work cap).
    MaxInternalSteps,
    /// ω_n (SI FMU).
    NaturalFrequency,
    /// δ (SI FMU).
    Clearance,
    /// M (SI FMU).
    Mass,
}

/// One variable of the model description.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variable {
    /// Value reference.
    pub vr: u32,
    /// Name (the contract's names for inputs and outputs).
    pub name: &'static str,
    /// Type.
    pub kind: Kind,
    /// Causality and variability.
    pub role: Role,
    /// One line.
    pub description: &'static str,
    /// Start value (inputs and parameters).
    pub start: Option<f64>,
    /// Closed lower bound (the table's range, or its sign where the SI range depends on the
    /// scales; an open end or a scaled range is stated in the description).
    pub min: Option<f64>,
    /// Upper bound.
    pub max: Option<f64>,
    /// What it measures (its unit and scale factor).
    pub dimension: Dimension,
    /// What it reads or writes.
    pub target: Target,
}

/// Default longest internal step (model time).
pub const INTERNAL_STEP: f64 = 1e-3;
/// Default tolerance of the contact sub-steps' error estimate.
pub const TOLERANCE: f64 = 1e-8;
/// Valid internal steps (model time).
pub const INTERNAL_STEP_RANGE: (f64, f64) = (1e-6, 0.1);
/// Valid tolerances.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-2);
/// Default cap on internal steps per communication step: 1000 time units (about 160 natural
/// periods) at the default internal step, a fraction of a second to a few seconds of work.
pub const MAX_INTERNAL_STEPS: u32 = 1_000_000;
/// Valid caps on internal steps (FMI 2.0's Integer is 32-bit).
pub const MAX_INTERNAL_STEPS_RANGE: (f64, f64) = (1.0, i32::MAX as f64);

/// Every variable of `units`, in value-reference order.
pub fn all(units: Units) -> Vec<Variable> {
    let table: Vec<Variable> = Parameter::ALL
        .into_iter()
        .filter_map(|p| of_parameter(p, units))
        .collect();
    let (mut inputs, params): (Vec<_>, Vec<_>) =
        table.into_iter().partition(|v| v.role == Role::Input);
    inputs.sort_by_key(|v| v.vr);
    [time(units)]
        .into_iter()
        .chain(outputs(units))
        .chain(inputs)
        .chain(params)
        .chain(settings(units))
        .collect()
}

/// The variable with value reference `vr` in `units`.
pub fn find(vr: u32, units: Units) -> Option<Variable> {
    match vr {
        0 => Some(time(units)),
        1..=8 | 20..=23 => outputs(units).into_iter().find(|v| v.vr == vr),
        10..=12 => table::INPUTS
            .iter()
            .find(|(_, r)| *r == vr)
            .and_then(|(p, _)| of_parameter(*p, units)),
        100..=199 => Parameter::ALL
            .get((vr - 100) as usize)
            .copied()
            .and_then(|p| of_parameter(p, units))
            .filter(|v| v.vr == vr),
        200..=212 => settings(units).find(|v| v.vr == vr),
        _ => None,
    }
}
