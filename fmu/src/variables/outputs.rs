//! The outputs (value references 1–8, the stator ring's 20–23) and the independent variable
//! (0), per unit system.

use super::{Kind, Output, Role, Target, Variable};
use crate::units::{Dimension, Units};

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

/// The outputs, value references 1–8 and 20–23 (the ring's centre and its velocity: at rest,
/// 0, for the massless ring, `stator_mass_ratio` = 0).
pub fn outputs(units: Units) -> [Variable; 12] {
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
        output(
            20,
            "xs",
            Kind::Float,
            Output::Xs,
            Dimension::Length,
            pick(
                "stator ring centre x_s, clearances (0 for the massless ring)",
                "stator ring centre x_s, m (0 for the massless ring)",
            ),
        ),
        output(
            21,
            "ys",
            Kind::Float,
            Output::Ys,
            Dimension::Length,
            pick(
                "stator ring centre y_s, clearances (0 for the massless ring)",
                "stator ring centre y_s, m (0 for the massless ring)",
            ),
        ),
        output(
            22,
            "vxs",
            Kind::Float,
            Output::Vxs,
            Dimension::Velocity,
            pick(
                "stator ring velocity x_s', clearances per unit time",
                "stator ring velocity x_s', m/s",
            ),
        ),
        output(
            23,
            "vys",
            Kind::Float,
            Output::Vys,
            Dimension::Velocity,
            pick(
                "stator ring velocity y_s', clearances per unit time",
                "stator ring velocity y_s', m/s",
            ),
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
