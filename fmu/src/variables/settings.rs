//! The FMU's own settings (value references 200–202) and the SI FMU's scales (210–212).

use super::{
    INTERNAL_STEP, INTERNAL_STEP_RANGE, Kind, MAX_INTERNAL_STEPS, MAX_INTERNAL_STEPS_RANGE, Role,
    Setting, TOLERANCE, TOLERANCE_RANGE, Target, Variable,
};
use crate::units::{
    CLEARANCE_RANGE, Dimension, MASS_RANGE, NATURAL_FREQUENCY_RANGE, SI_DEFAULT, Scales, Units,
};

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
