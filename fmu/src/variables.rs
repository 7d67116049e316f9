//! The FMU's variables, stated once: the outputs and inputs of the contract, every entry
//! of the parameter table (`rotor_rub::Parameter`) as a parameter (or as an input where the FMU
//! drives it), and the FMU's own settings. The model description (`description.rs`) and the
//! value-reference dispatch of `model.rs` both read this table.
//!
//! Value references: time 0, outputs 1–8, inputs 10–12, table entries 100 + table index, settings
//! 200–201. `start_time` is not a variable: the FMU starts at the importer's start time.

use rotor_rub::Parameter;

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
    /// τ, the independent variable.
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
}

/// The FMU's own settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// The longest internal step (the stepper's dt).
    InternalStep,
    /// Largest accepted exprb43 error estimate of a contact sub-step.
    Tolerance,
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
    /// Closed bounds (the table's range; an open end is stated in the description).
    pub min: Option<f64>,
    /// Upper bound.
    pub max: Option<f64>,
    /// What it reads or writes.
    pub target: Target,
}

/// Default longest internal step.
pub const INTERNAL_STEP: f64 = 1e-3;
/// Default tolerance of the contact sub-steps' error estimate.
pub const TOLERANCE: f64 = 1e-8;
/// Valid internal steps.
pub const INTERNAL_STEP_RANGE: (f64, f64) = (1e-6, 0.1);
/// Valid tolerances.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-2);

const fn output(vr: u32, name: &'static str, kind: Kind, out: Output, d: &'static str) -> Variable {
    let role = match kind {
        Kind::Float => Role::ContinuousOutput,
        _ => Role::DiscreteOutput,
    };
    Variable {
        vr,
        name,
        kind,
        role,
        description: d,
        start: None,
        min: None,
        max: None,
        target: Target::Output(out),
    }
}

/// The outputs, value references 1–8.
pub const OUTPUTS: [Variable; 8] = [
    output(1, "x", Kind::Float, Output::X, "rotor centre x, clearances"),
    output(2, "y", Kind::Float, Output::Y, "rotor centre y, clearances"),
    output(
        3,
        "vx",
        Kind::Float,
        Output::Vx,
        "velocity x', clearances per unit time",
    ),
    output(
        4,
        "vy",
        Kind::Float,
        Output::Vy,
        "velocity y', clearances per unit time",
    ),
    output(
        5,
        "in_contact",
        Kind::Bool,
        Output::InContact,
        "the rotor touches the stator",
    ),
    output(
        6,
        "normal_force",
        Kind::Float,
        Output::NormalForce,
        "normal contact force N = n'K_s g (0 when free), per unit mass",
    ),
    output(
        7,
        "contact_count",
        Kind::Int64,
        Output::ContactCount,
        "contact entries since the start (FMI 2: saturates at 2147483647)",
    ),
    output(
        8,
        "slip_regime",
        Kind::Int32,
        Output::SlipRegime,
        "0 free, 1 contact without friction, 2 slipping forward (w > 0), 3 slipping backward (w < 0), 4 rolling",
    ),
];

/// The independent variable, value reference 0.
pub const TIME: Variable = Variable {
    vr: 0,
    name: "time",
    kind: Kind::Float,
    role: Role::Independent,
    description: "dimensionless time τ = ω_n t",
    start: None,
    min: None,
    max: None,
    target: Target::Output(Output::Time),
};

/// The contract's input names of table entries.
const INPUTS: [(Parameter, u32, &str); 3] = [
    (Parameter::ForceX, 10, "fx"),
    (Parameter::ForceY, 11, "fy"),
    (Parameter::SpeedRatio, 12, "speed_ratio"),
];

/// The settings, value references 200–201.
pub const SETTINGS: [Variable; 2] = [
    Variable {
        vr: 200,
        name: "internal_step",
        kind: Kind::Float,
        role: Role::Fixed,
        description: "longest internal step: a communication step is covered by steps of at most this length (shortened where the error estimate exceeds the tolerance)",
        start: Some(INTERNAL_STEP),
        min: Some(INTERNAL_STEP_RANGE.0),
        max: Some(INTERNAL_STEP_RANGE.1),
        target: Target::Setting(Setting::InternalStep),
    },
    Variable {
        vr: 201,
        name: "tolerance",
        kind: Kind::Float,
        role: Role::Fixed,
        description: "largest accepted error estimate of a contact sub-step (max norm relative to 1 + |state|); the importer's tolerance replaces it when given",
        start: Some(TOLERANCE),
        min: Some(TOLERANCE_RANGE.0),
        max: Some(TOLERANCE_RANGE.1),
        target: Target::Setting(Setting::Tolerance),
    },
];

/// The variable of table entry `p` (`None` for `start_time`).
pub fn of_parameter(p: Parameter) -> Option<Variable> {
    if p == Parameter::StartTime {
        return None;
    }
    let info = p.info();
    let input = INPUTS.iter().find(|(q, _, _)| *q == p);
    let (vr, name, role) = match input {
        Some(&(_, vr, name)) => (vr, name, Role::Input),
        None => {
            // Start values and the phase (kept continuous by speed changes) are fixed.
            let fixed = !p.is_model() || p == Parameter::Phase;
            let role = if fixed { Role::Fixed } else { Role::Tunable };
            (100 + p as u32, info.name, role)
        }
    };
    Some(Variable {
        vr,
        name,
        kind: Kind::Float,
        role,
        description: info.doc,
        start: Some(info.default),
        min: Some(info.range.min),
        max: Some(info.range.max),
        target: Target::Table(p),
    })
}

/// Every variable, in value-reference order.
pub fn all() -> impl Iterator<Item = Variable> {
    let table = Parameter::ALL.into_iter().filter_map(of_parameter);
    let (inputs, params): (Vec<_>, Vec<_>) = table.partition(|v| v.role == Role::Input);
    let mut inputs = inputs;
    inputs.sort_by_key(|v| v.vr);
    [TIME]
        .into_iter()
        .chain(OUTPUTS)
        .chain(inputs)
        .chain(params)
        .chain(SETTINGS)
}

/// The variable with value reference `vr`.
pub fn find(vr: u32) -> Option<Variable> {
    match vr {
        0 => Some(TIME),
        1..=8 => OUTPUTS.iter().find(|v| v.vr == vr).copied(),
        10..=12 => INPUTS
            .iter()
            .find(|(_, r, _)| *r == vr)
            .and_then(|(p, _, _)| of_parameter(*p)),
        100..=199 => Parameter::ALL
            .get((vr - 100) as usize)
            .copied()
            .and_then(of_parameter)
            .filter(|v| v.vr == vr),
        200..=201 => SETTINGS.iter().find(|v| v.vr == vr).copied(),
        _ => None,
    }
}
