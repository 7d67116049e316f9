//! The parameter table's entries as FMU variables: names, descriptions, units, start values and
//! bounds in either unit system (inputs at value references 10–12, the rest at 100 + index).

use rotor_rub::Parameter;

use super::{Kind, Role, Target, Variable};
use crate::units::{Dimension, SI_DEFAULT, Units};

/// The inputs: table entries the importer drives, with their value references.
pub(super) const INPUTS: [(Parameter, u32); 3] = [
    (Parameter::ForceX, 10),
    (Parameter::ForceY, 11),
    (Parameter::SpeedRatio, 12),
];

/// What a table entry measures.
pub fn dimension(p: Parameter) -> Dimension {
    use Parameter as P;
    match p {
        P::SpeedRatio => Dimension::AngularSpeed,
        P::DampingRatio | P::MassRatio | P::FrictionCoefficient | P::StatorMassRatio => {
            Dimension::One
        }
        P::StatorDamping => Dimension::Damping,
        P::Phase => Dimension::Angle,
        P::KXx | P::KXy | P::KYx | P::KYy | P::ContactStiffness => Dimension::Stiffness,
        P::EccentricityRatio
        | P::OffsetX
        | P::OffsetY
        | P::RadiusRatio
        | P::X0
        | P::Y0
        | P::Xs0
        | P::Ys0 => Dimension::Length,
        P::ForceX | P::ForceY => Dimension::Force,
        P::Vx0 | P::Vy0 | P::Vxs0 | P::Vys0 => Dimension::Velocity,
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
        (Units::Si, P::StatorMassRatio) => (
            "stator_mass_ratio",
            "stator ring mass over the rotor mass M (0: the paper's massless ring; > 0 runs the ring with mass)",
        ),
        (Units::Si, P::ContactStiffness) => (
            "contact_stiffness",
            "contact stiffness between rotor and a ring with mass, N/m (k̂_c = k_c/(M ω_n²) in (0, 1e6]; only with stator_mass_ratio > 0)",
        ),
        (Units::Si, P::StatorDamping) => (
            "stator_damping",
            "damping of the ring with mass on its support, N·s/m (ĉ = c_s/(M ω_n) in [0, 1e3]; only with stator_mass_ratio > 0)",
        ),
        (Units::Si, P::Xs0) => (
            "xs0",
            "ring's initial centre x_s, m (with stator_mass_ratio > 0)",
        ),
        (Units::Si, P::Ys0) => (
            "ys0",
            "ring's initial centre y_s, m (with stator_mass_ratio > 0)",
        ),
        (Units::Si, P::Vxs0) => (
            "vxs0",
            "ring's initial velocity x_s', m/s (with stator_mass_ratio > 0)",
        ),
        (Units::Si, P::Vys0) => (
            "vys0",
            "ring's initial velocity y_s', m/s (with stator_mass_ratio > 0)",
        ),
        (Units::Si, _) => (info.name, info.doc),
    }
}

/// The variable of table entry `p` in `units` (`None` for `start_time`). The stator ring's
/// entries are offered: `stator_mass_ratio` > 0 runs the ring with mass (the stepper decides,
/// `rotor_rub::stepper::AnyStepper`); it is fixed (a running FMU cannot change between the
/// massless and the massive ring), the ring's stiffness and damping are tunable.
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
            let fixed = !p.is_model() || p == Parameter::Phase || p == Parameter::StatorMassRatio;
            let role = if fixed { Role::Fixed } else { Role::Tunable };
            (100 + p as u32, role)
        }
    };
    let scale_free = matches!(dimension, Dimension::One | Dimension::Angle);
    // An SI start value is the model's default converted: converted back where the value
    // takes effect it must be the default again, bit for bit (`Model::requested_problem`
    // keeps an untouched SI default's model value exact).
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
