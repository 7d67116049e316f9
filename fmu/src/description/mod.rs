//! `modelDescription.xml` for FMI 2.0 and FMI 3.0 and either unit system, written from the
//! variable table (`variables.rs`, itself read off the parameter table): names, descriptions,
//! start values, ranges, units and display units cannot drift from the code.
//!
//! The GUID / instantiation token is a hash of the unit system, the variable table and the crate
//! version, so an FMU built from changed variables refuses a description of the old ones, and
//! the one binary knows from the token which unit system an instance speaks
//! ([`units_of_token`]).
//!
//! `ModelStructure` states each output's dependencies on the inputs at a communication point:
//! the state outputs (x, y, vx, vy), the normal force and the contact count depend on none (the
//! inputs are held over the next step and act only through it: no direct feedthrough, so a
//! controller closing a loop over them has no algebraic loop); `in_contact` and `slip_regime`
//! depend on the speed input, which re-decides the contact regime and the slip direction at the
//! current state at once (`Stepper::set_speed_ratio`).

mod elements;

use std::fmt::Write;

pub use elements::attributes;
use elements::{fmi2_variable, fmi3_variable, model_structure, unit_definitions};

use crate::instance::CATEGORIES;
use crate::units::{SI_DEFAULT, Units};
use crate::variables::{self, Output, Role, Variable};

/// The model identifier: the binary's file name without its extension.
pub const MODEL_IDENTIFIER: &str = "rotor_rub_fmu";

/// Which FMI version a description is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Version {
    /// FMI 2.0.
    Fmi2,
    /// FMI 3.0.
    Fmi3,
}

/// The model name of `units`.
pub fn model_name(units: Units) -> &'static str {
    match units {
        Units::Dimensionless => "rotor_rub",
        Units::Si => "rotor_rub_si",
    }
}

/// The GUID (FMI 2.0) and instantiation token (FMI 3.0) of `units`: FNV-1a of the version, the
/// unit system and every variable's reference, name, type, role, bounds and unit, as
/// `{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}`.
pub fn guid(units: Units) -> String {
    let mut text = format!("{}|{:?}", env!("CARGO_PKG_VERSION"), units);
    for v in variables::all(units) {
        let _ = write!(
            text,
            "|{}:{}:{:?}:{:?}:{:?}:{:?}:{:?}:{}",
            v.vr,
            v.name,
            v.kind,
            v.role,
            v.start,
            v.min,
            v.max,
            v.dimension.unit(units)
        );
    }
    let hash = |seed: u64| {
        text.bytes().fold(seed, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
        })
    };
    let (a, b) = (hash(0xcbf2_9ce4_8422_2325), hash(0x8422_2325_cbf2_9ce4));
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

/// The unit system whose token is `token`, if any.
pub fn units_of_token(token: &str) -> Option<Units> {
    [Units::Dimensionless, Units::Si]
        .into_iter()
        .find(|&u| guid(u) == token)
}

/// XML text with `&`, `<`, `>` and `"` escaped.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A number as XML: shortest round-trip form.
fn number(x: f64) -> String {
    format!("{x:?}")
}

/// One line on the model, per unit system.
pub fn summary(units: Units) -> &'static str {
    match units {
        Units::Dimensionless => {
            "Jeffcott rotor rubbing on an anisotropically supported stator (rotor-rub): exact piecewise-analytical co-simulation with contact events, an external input force and a speed input; all quantities dimensionless"
        }
        Units::Si => {
            "Jeffcott rotor rubbing on an anisotropically supported stator (rotor-rub): exact piecewise-analytical co-simulation with contact events, an external input force and a speed input; SI units (s, m, m/s, N, rad/s) scaled by the natural frequency, the radial clearance and the rotor mass"
        }
    }
}

/// The inputs an output depends on at a communication point (see the module docs).
pub fn dependencies(output: Output) -> &'static [u32] {
    const SPEED: u32 = 12;
    match output {
        Output::InContact | Output::SlipRegime => &[SPEED],
        _ => &[],
    }
}

/// `<DefaultExperiment>`'s stop time and step: 20 forcing periods of the default speed.
fn default_experiment(units: Units) -> (f64, f64) {
    let periods = 20.0 * core::f64::consts::TAU / rotor_rub::Params::DEFAULT.speed_ratio;
    match units {
        Units::Dimensionless => (periods, variables::INTERNAL_STEP),
        Units::Si => (periods / SI_DEFAULT.natural_frequency, 1e-4),
    }
}

/// The model description for `version` and `units`.
pub fn model_description(version: Version, units: Units) -> String {
    let mut x = String::new();
    // FMI 2.0 leaves the independent variable implicit (time); declared, it makes the FMI
    // Library (libcosim's importer) report a missing start value, which it must not have.
    let vars: Vec<Variable> = variables::all(units)
        .into_iter()
        .filter(|v| version == Version::Fmi3 || v.role != Role::Independent)
        .collect();
    let name = model_name(units);
    let token = guid(units);
    let description = escape(summary(units));
    let tool = format!("rotor-rub {} (cargo xtask fmu)", env!("CARGO_PKG_VERSION"));
    header(
        &mut x,
        version,
        [name, &token, &description, &tool],
        Capabilities {
            serialize: true,
            early_return: true,
        },
    );
    unit_definitions(&mut x, units);
    let _ = writeln!(x, r#"  <LogCategories>"#);
    for (category, _, text) in CATEGORIES {
        let _ = writeln!(
            x,
            r#"    <Category name="{category}" description="{}"/>"#,
            escape(text)
        );
    }
    let _ = writeln!(x, r#"  </LogCategories>"#);
    let (stop, step) = default_experiment(units);
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0.0" stopTime="{}" stepSize="{}"/>"#,
        number(stop),
        number(step)
    );
    let _ = writeln!(x, r#"  <ModelVariables>"#);
    for v in &vars {
        match version {
            Version::Fmi2 => fmi2_variable(&mut x, v, units),
            Version::Fmi3 => fmi3_variable(&mut x, v, units),
        }
    }
    let _ = writeln!(x, r#"  </ModelVariables>"#);
    model_structure(&mut x, version, &vars);
    let _ = writeln!(x, r#"</fmiModelDescription>"#);
    x
}

/// What a model description's CoSimulation element offers beyond the common set.
pub(crate) struct Capabilities {
    /// canSerializeFMUstate / canSerializeFMUState.
    pub serialize: bool,
    /// FMI 3's mightReturnEarlyFromDoStep.
    pub early_return: bool,
}

/// The XML declaration, the fmiModelDescription element's opening tag and the CoSimulation
/// element of either FMI version (the planar/ring FMU's and a model file's).
pub(crate) fn header(
    x: &mut String,
    version: Version,
    [name, token, description, tool]: [&str; 4],
    offers: Capabilities,
) {
    let (serialize, early) = (offers.serialize, offers.early_return);
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    match version {
        Version::Fmi2 => {
            let _ = writeln!(
                x,
                r#"<fmiModelDescription fmiVersion="2.0" modelName="{name}" guid="{token}" description="{description}" generationTool="{tool}" variableNamingConvention="flat" numberOfEventIndicators="0">"#
            );
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUstate="true" canSerializeFMUstate="{serialize}" canNotUseMemoryManagementFunctions="true"/>"#
            );
        }
        Version::Fmi3 => {
            let _ = writeln!(
                x,
                r#"<fmiModelDescription fmiVersion="3.0" modelName="{name}" instantiationToken="{token}" description="{description}" generationTool="{tool}" variableNamingConvention="flat">"#
            );
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUState="true" canSerializeFMUState="{serialize}" canReturnEarlyAfterIntermediateUpdate="false" hasEventMode="false" mightReturnEarlyFromDoStep="{early}"/>"#
            );
        }
    }
}
