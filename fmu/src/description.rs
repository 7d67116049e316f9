//! `modelDescription.xml` for FMI 2.0 and FMI 3.0, written from the variable table
//! (`variables.rs`, itself read off the parameter table): names, descriptions, start values and
//! ranges cannot drift from the code. Units: everything is dimensionless (unit "1").
//!
//! The GUID / instantiation token is a hash of the variable table and the crate version, so an
//! FMU built from changed variables refuses a description of the old ones.

use std::fmt::Write;

use crate::variables::{self, Kind, Role, Variable};

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

/// The GUID (FMI 2.0) and instantiation token (FMI 3.0): FNV-1a of the version and of every
/// variable's reference, name, type, role and bounds, as `{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}`.
pub fn guid() -> String {
    let mut text = String::from(env!("CARGO_PKG_VERSION"));
    for v in variables::all() {
        let _ = write!(
            text,
            "|{}:{}:{:?}:{:?}:{:?}:{:?}:{:?}",
            v.vr, v.name, v.kind, v.role, v.start, v.min, v.max
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

/// XML text with `&`, `<`, `>` and `"` escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A number as XML: shortest round-trip form.
fn number(x: f64) -> String {
    format!("{x:?}")
}

const DESCRIPTION: &str = "Jeffcott rotor rubbing on an anisotropically supported stator (rotor-rub): exact piecewise-analytical co-simulation with contact events, an external input force and a speed input; all quantities dimensionless";

/// The model description for `version`.
pub fn model_description(version: Version) -> String {
    let mut x = String::new();
    let vars: Vec<Variable> = variables::all().collect();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    match version {
        Version::Fmi2 => {
            let _ = writeln!(
                x,
                r#"<fmiModelDescription fmiVersion="2.0" modelName="rotor_rub" guid="{}" description="{DESCRIPTION}" generationTool="rotor-rub {} (cargo xtask fmu)" variableNamingConvention="flat" numberOfEventIndicators="0">"#,
                guid(),
                env!("CARGO_PKG_VERSION")
            );
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true" canNotUseMemoryManagementFunctions="true"/>"#
            );
        }
        Version::Fmi3 => {
            let _ = writeln!(
                x,
                r#"<fmiModelDescription fmiVersion="3.0" modelName="rotor_rub" instantiationToken="{}" description="{DESCRIPTION}" generationTool="rotor-rub {} (cargo xtask fmu)" variableNamingConvention="flat">"#,
                guid(),
                env!("CARGO_PKG_VERSION")
            );
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUState="true" canSerializeFMUState="true" canReturnEarlyAfterIntermediateUpdate="false" hasEventMode="false" mightReturnEarlyFromDoStep="true"/>"#
            );
        }
    }
    let _ = writeln!(x, r#"  <UnitDefinitions>"#);
    let _ = writeln!(x, r#"    <Unit name="1"/>"#);
    let _ = writeln!(x, r#"  </UnitDefinitions>"#);
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0.0" stopTime="83.77580409572782" stepSize="{}"/>"#,
        number(variables::INTERNAL_STEP)
    );
    let _ = writeln!(x, r#"  <ModelVariables>"#);
    for v in &vars {
        match version {
            Version::Fmi2 => fmi2_variable(&mut x, v),
            Version::Fmi3 => fmi3_variable(&mut x, v),
        }
    }
    let _ = writeln!(x, r#"  </ModelVariables>"#);
    let _ = writeln!(x, r#"  <ModelStructure>"#);
    match version {
        Version::Fmi2 => {
            // Outputs and initial unknowns by index (1-based order in ModelVariables).
            let _ = writeln!(x, r#"    <Outputs>"#);
            for (k, _) in vars.iter().enumerate().filter(|(_, v)| is_output(v)) {
                let _ = writeln!(x, r#"      <Unknown index="{}"/>"#, k + 1);
            }
            let _ = writeln!(x, r#"    </Outputs>"#);
            let _ = writeln!(x, r#"    <InitialUnknowns>"#);
            for (k, _) in vars.iter().enumerate().filter(|(_, v)| is_output(v)) {
                let _ = writeln!(x, r#"      <Unknown index="{}"/>"#, k + 1);
            }
            let _ = writeln!(x, r#"    </InitialUnknowns>"#);
        }
        Version::Fmi3 => {
            for v in vars.iter().filter(|v| is_output(v)) {
                let _ = writeln!(x, r#"    <Output valueReference="{}"/>"#, v.vr);
            }
            for v in vars.iter().filter(|v| is_output(v)) {
                let _ = writeln!(x, r#"    <InitialUnknown valueReference="{}"/>"#, v.vr);
            }
        }
    }
    let _ = writeln!(x, r#"  </ModelStructure>"#);
    let _ = writeln!(x, r#"</fmiModelDescription>"#);
    x
}

fn is_output(v: &Variable) -> bool {
    matches!(v.role, Role::ContinuousOutput | Role::DiscreteOutput)
}

/// causality, variability and initial of a role.
fn attributes(role: Role) -> (&'static str, &'static str, Option<&'static str>) {
    match role {
        Role::Independent => ("independent", "continuous", None),
        Role::ContinuousOutput => ("output", "continuous", Some("calculated")),
        Role::DiscreteOutput => ("output", "discrete", Some("calculated")),
        Role::Input => ("input", "continuous", None),
        Role::Tunable => ("parameter", "tunable", Some("exact")),
        Role::Fixed => ("parameter", "fixed", Some("exact")),
    }
}

fn head(x: &mut String, v: &Variable) -> (Option<&'static str>, String) {
    let (causality, variability, initial) = attributes(v.role);
    let _ = write!(
        x,
        r#"name="{}" valueReference="{}" description="{}" causality="{causality}" variability="{variability}""#,
        escape(v.name),
        v.vr,
        escape(v.description)
    );
    let mut bounds = String::new();
    if v.kind == Kind::Float {
        bounds.push_str(r#" unit="1""#);
        if let Some(min) = v.min {
            let _ = write!(bounds, r#" min="{}""#, number(min));
        }
        if let Some(max) = v.max {
            let _ = write!(bounds, r#" max="{}""#, number(max));
        }
    }
    if let Some(start) = v.start {
        let _ = write!(bounds, r#" start="{}""#, number(start));
    }
    (initial, bounds)
}

fn fmi2_variable(x: &mut String, v: &Variable) {
    x.push_str("    <ScalarVariable ");
    let (initial, bounds) = head(x, v);
    if let Some(i) = initial {
        let _ = write!(x, r#" initial="{i}""#);
    }
    let element = match v.kind {
        Kind::Float => "Real",
        Kind::Int64 | Kind::Int32 => "Integer",
        Kind::Bool => "Boolean",
    };
    let _ = writeln!(x, ">\n      <{element}{bounds}/>\n    </ScalarVariable>");
}

fn fmi3_variable(x: &mut String, v: &Variable) {
    let element = match v.kind {
        Kind::Float => "Float64",
        Kind::Int64 => "Int64",
        Kind::Int32 => "Int32",
        Kind::Bool => "Boolean",
    };
    let _ = write!(x, "    <{element} ");
    let (initial, bounds) = head(x, v);
    if let Some(i) = initial {
        let _ = write!(x, r#" initial="{i}""#);
    }
    let _ = writeln!(x, "{bounds}/>");
}
