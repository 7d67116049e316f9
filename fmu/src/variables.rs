//! The FMU's variables, stated once per unit system (`units.rs`): the outputs and inputs of the
//! issue's contract, every entry of the parameter table (`rotor_rub::Parameter`) as a parameter
//! (or as an input where the FMU drives it), and the FMU's own settings. The model description
//! (`description.rs`), the documentation (`documentation.rs`) and the value-reference dispatch
//! of `model.rs` all read this table.
//!
//! Value references (the same in both unit systems): time 0, outputs 1–8, inputs 10–12, table
//! entries 100 + table index, settings 200–202, the SI FMU's scales 210–212. `start_time` is
//! not a variable: the FMU starts at the importer's start time.

use rotor_rub::Parameter;

use crate::units::{
    CLEARANCE_RANGE, Dimension, MASS_RANGE, NATURAL_FREQUENCY_RANGE, SI_DEFAULT, Scales, Units,
};

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

const fn output(
    vr: u32,
    name: &'static str,
    kind: Kind,
    out: Output,
    dimension: Dimension,
    d: &'static str,
) -> Variable {
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
        dimension,
        target: Target::Output(out),
    }
}

/// The outputs, value references 1–8.
pub fn outputs(units: Units) -> [Variable; 8] {
    let si = units == Units::Si;
    let pick = |dimensionless, si_text| if si { si_text } else { dimensionless };
    [
        output(
            1,
            "x",
            Kind::Float,
            Output::X,
            Dimension::Length,
            pick("rotor centre x, clearances", "rotor centre x, m"),
        ),
        output(
            2,
            "y",
            Kind::Float,
            Output::Y,
            Dimension::Length,
            pick("rotor centre y, clearances", "rotor centre y, m"),
        ),
        output(
            3,
            "vx",
            Kind::Float,
            Output::Vx,
            Dimension::Velocity,
            pick(
                "velocity x', clearances per unit time",
                "rotor centre velocity x, m/s",
            ),
        ),
        output(
            4,
            "vy",
            Kind::Float,
            Output::Vy,
            Dimension::Velocity,
            pick(
                "velocity y', clearances per unit time",
                "rotor centre velocity y, m/s",
            ),
        ),
        output(
            5,
            "in_contact",
            Kind::Bool,
            Output::InContact,
            Dimension::One,
            "the rotor touches the stator",
        ),
        output(
            6,
            "normal_force",
            Kind::Float,
            Output::NormalForce,
            Dimension::Force,
            pick(
                "normal contact force N = n'K_s g (0 when free), per unit mass",
                "normal contact force, N (0 when free)",
            ),
        ),
        output(
            7,
            "contact_count",
            Kind::Int64,
            Output::ContactCount,
            Dimension::One,
            "contact entries since the start (FMI 2: saturates at 2147483647)",
        ),
        output(
            8,
            "slip_regime",
            Kind::Int32,
            Output::SlipRegime,
            Dimension::One,
            "0 free, 1 contact without friction, 2 slipping forward (w > 0), 3 slipping backward (w < 0), 4 rolling",
        ),
    ]
}

/// The independent variable, value reference 0.
pub fn time(units: Units) -> Variable {
    Variable {
        vr: 0,
        name: "time",
        kind: Kind::Float,
        role: Role::Independent,
        description: match units {
            Units::Dimensionless => "dimensionless time τ = ω_n t",
            Units::Si => "time, s",
        },
        start: None,
        min: None,
        max: None,
        dimension: Dimension::Time,
        target: Target::Output(Output::Time),
    }
}

/// The inputs: table entries the importer drives, with their value references.
const INPUTS: [(Parameter, u32); 3] = [
    (Parameter::ForceX, 10),
    (Parameter::ForceY, 11),
    (Parameter::SpeedRatio, 12),
];

/// What a table entry measures.
pub fn dimension(p: Parameter) -> Dimension {
    use Parameter as P;
    match p {
        P::SpeedRatio => Dimension::AngularSpeed,
        P::DampingRatio | P::MassRatio | P::FrictionCoefficient => Dimension::One,
        P::Phase => Dimension::Angle,
        P::KXx | P::KXy | P::KYx | P::KYy => Dimension::Stiffness,
        P::EccentricityRatio | P::OffsetX | P::OffsetY | P::RadiusRatio | P::X0 | P::Y0 => {
            Dimension::Length
        }
        P::ForceX | P::ForceY => Dimension::Force,
        P::Vx0 | P::Vy0 => Dimension::Velocity,
        P::StartTime => Dimension::Time,
    }
}

/// A table entry's name and description in `units`.
fn name_and_doc(p: Parameter, units: Units) -> (&'static str, &'static str) {
    use Parameter as P;
    let info = p.info();
    match (units, p) {
        (Units::Dimensionless, P::ForceX) => ("fx", info.doc),
        (Units::Dimensionless, P::ForceY) => ("fy", info.doc),
        (Units::Dimensionless, _) => (info.name, info.doc),
        (Units::Si, P::SpeedRatio) => (
            "speed",
            "rotor running speed Ω, rad/s (the model's η = Ω/ω_n; the forcing phase stays continuous when it changes)",
        ),
        (Units::Si, P::MassRatio) => ("mass_ratio", "unbalance mass over the rotor mass M"),
        (Units::Si, P::EccentricityRatio) => (
            "eccentricity",
            "radius of the unbalance mass from the rotor axis, m (ρ̂ = e/δ in (0, 1e3])",
        ),
        (Units::Si, P::Phase) => ("phase", "phase of the unbalance at t = 0, rad"),
        (Units::Si, P::KXx) => (
            "k_xx",
            "stator stiffness, x force per x displacement, N/m (k/(M ω_n²) in [0, 1e5])",
        ),
        (Units::Si, P::KXy) => (
            "k_xy",
            "stator stiffness, x force per y displacement (cross-coupling), N/m (k/(M ω_n²) in [-1e5, 1e5])",
        ),
        (Units::Si, P::KYx) => (
            "k_yx",
            "stator stiffness, y force per x displacement (cross-coupling), N/m (k/(M ω_n²) in [-1e5, 1e5])",
        ),
        (Units::Si, P::KYy) => (
            "k_yy",
            "stator stiffness, y force per y displacement, N/m (k/(M ω_n²) in [0, 1e5])",
        ),
        (Units::Si, P::OffsetX) => (
            "offset_x",
            "stator centre offset from the rotor's rest position, x, m (at most 10 clearances)",
        ),
        (Units::Si, P::OffsetY) => (
            "offset_y",
            "stator centre offset from the rotor's rest position, y, m (at most 10 clearances)",
        ),
        (Units::Si, P::RadiusRatio) => (
            "rotor_radius",
            "rotor radius at the contact, m (R/δ in (0, 1e5]; the rotor spins counter-clockwise)",
        ),
        (Units::Si, P::ForceX) => (
            "fx",
            "external force on the rotor, x, N (a magnetic bearing, a controller, a static load; at most 1e3 M ω_n² δ)",
        ),
        (Units::Si, P::ForceY) => (
            "fy",
            "external force on the rotor, y, N (at most 1e3 M ω_n² δ)",
        ),
        (Units::Si, P::X0) => ("x0", "initial position x, m (at most 100 clearances)"),
        (Units::Si, P::Y0) => ("y0", "initial position y, m (at most 100 clearances)"),
        (Units::Si, P::Vx0) => ("vx0", "initial velocity x, m/s (at most 100 δ ω_n)"),
        (Units::Si, P::Vy0) => ("vy0", "initial velocity y, m/s (at most 100 δ ω_n)"),
        (Units::Si, _) => (info.name, info.doc),
    }
}

/// The variable of table entry `p` in `units` (`None` for `start_time`).
pub fn of_parameter(p: Parameter, units: Units) -> Option<Variable> {
    if p == Parameter::StartTime {
        return None;
    }
    let info = p.info();
    let (name, description) = name_and_doc(p, units);
    let dimension = dimension(p);
    let (vr, role) = match INPUTS.iter().find(|(q, _)| *q == p) {
        Some(&(_, vr)) => (vr, Role::Input),
        None => {
            // Start values and the phase (kept continuous by speed changes) are fixed.
            let fixed = !p.is_model() || p == Parameter::Phase;
            let role = if fixed { Role::Fixed } else { Role::Tunable };
            (100 + p as u32, role)
        }
    };
    let scale_free = matches!(dimension, Dimension::One | Dimension::Angle);
    let (start, min, max) = match units {
        Units::Dimensionless => (info.default, Some(info.range.min), Some(info.range.max)),
        Units::Si if scale_free => (info.default, Some(info.range.min), Some(info.range.max)),
        // The SI range scales with ω_n, δ and M (set in any order): its sign is declared, the
        // whole range is checked where the values take effect.
        Units::Si => (
            SI_DEFAULT.to_importer(dimension, info.default),
            (info.range.min >= 0.0).then_some(0.0),
            None,
        ),
    };
    Some(Variable {
        vr,
        name,
        kind: Kind::Float,
        role,
        description,
        start: Some(start),
        min,
        max,
        dimension,
        target: Target::Table(p),
    })
}

/// The settings in `units`, value references 200–202 (and 210–212 in the SI FMU).
pub fn settings(units: Units) -> impl Iterator<Item = Variable> {
    let setting =
        |vr, name, kind, role, description, start, (min, max): (f64, f64), dimension, s| Variable {
            vr,
            name,
            kind,
            role,
            description,
            start: Some(start),
            min: Some(min),
            max: Some(max),
            dimension,
            target: Target::Setting(s),
        };
    let step = match units {
        Units::Dimensionless => setting(
            200,
            "internal_step",
            Kind::Float,
            Role::Fixed,
            "longest internal step: a communication step is covered by steps of at most this length (shortened where the error estimate exceeds the tolerance)",
            INTERNAL_STEP,
            INTERNAL_STEP_RANGE,
            Dimension::Time,
            Setting::InternalStep,
        ),
        Units::Si => setting(
            200,
            "internal_step",
            Kind::Float,
            Role::Fixed,
            "longest internal step, s; 0: 1e-3/ω_n (the dimensionless FMU's default); else ω_n·internal_step must lie in [1e-6, 0.1]",
            0.0,
            (0.0, INTERNAL_STEP_RANGE.1 / NATURAL_FREQUENCY_RANGE.0),
            Dimension::Time,
            Setting::InternalStep,
        ),
    };
    let common = [
        step,
        setting(
            201,
            "tolerance",
            Kind::Float,
            Role::Fixed,
            "largest accepted error estimate of a contact sub-step (max norm relative to 1 + |state|); the importer's tolerance replaces it when given",
            TOLERANCE,
            TOLERANCE_RANGE,
            Dimension::One,
            Setting::Tolerance,
        ),
        setting(
            202,
            "max_internal_steps",
            Kind::Int32,
            Role::Tunable,
            "work cap: most internal steps in one communication step; reaching it ends the step early (FMI 3 with early return) or with Discard, never blocks",
            f64::from(MAX_INTERNAL_STEPS),
            MAX_INTERNAL_STEPS_RANGE,
            Dimension::One,
            Setting::MaxInternalSteps,
        ),
    ];
    let scales = [
        setting(
            210,
            "natural_frequency",
            Kind::Float,
            Role::Fixed,
            "the rotor's natural frequency ω_n = √(k/M), rad/s (its first critical speed)",
            SI_DEFAULT.natural_frequency,
            NATURAL_FREQUENCY_RANGE,
            Dimension::AngularSpeed,
            Setting::NaturalFrequency,
        ),
        setting(
            211,
            "clearance",
            Kind::Float,
            Role::Fixed,
            "radial clearance δ between rotor and stator, m",
            SI_DEFAULT.clearance,
            CLEARANCE_RANGE,
            Dimension::Length,
            Setting::Clearance,
        ),
        setting(
            212,
            "mass",
            Kind::Float,
            Role::Fixed,
            "rotor (disk) mass M, kg",
            SI_DEFAULT.mass,
            MASS_RANGE,
            Dimension::Mass,
            Setting::Mass,
        ),
    ];
    let si = units == Units::Si;
    common
        .into_iter()
        .chain(scales.into_iter().filter(move |_| si))
}

/// The default scales of `units`.
pub fn default_scales(units: Units) -> Scales {
    match units {
        Units::Dimensionless => Scales::ONE,
        Units::Si => SI_DEFAULT,
    }
}

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
        1..=8 => outputs(units).into_iter().find(|v| v.vr == vr),
        10..=12 => INPUTS
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

/// The value reference of table entry `p` (an input's, or 100 + its table index).
pub fn vr_of(p: Parameter) -> u32 {
    INPUTS
        .iter()
        .find(|(q, _)| *q == p)
        .map_or(100 + p as u32, |&(_, vr)| vr)
}
