//! The model-file FMU's `modelDescription.xml` (FMI 3.0 or 2.0) and its instantiation token;
//! the instance's reading of its resource at instantiation is in `resource.rs`.

use std::fmt::Write;

use super::FileModel;
use super::run::{FORCE_BASE, FileKind, FileVariable, INTERNAL_STEP, POSITION_BASE, VELOCITY_BASE};
use crate::description::{Capabilities, Version, escape, header};

/// The instantiation token (FMI 3.0) and GUID (FMI 2.0) of the FMU built for `resource` (the
/// resource's text): FNV-1a of the crate version and the text, as `{xxxxxxxx-…}` with a
/// `5` in the third group's first digit's place, apart from the planar FMUs' tokens.
pub fn file_token(resource: &str) -> String {
    let text = format!("{}|model-file|{resource}", env!("CARGO_PKG_VERSION"));
    let hash = |seed: u64| {
        text.bytes().fold(seed, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
        })
    };
    let (a, b) = (hash(0xcbf2_9ce4_8422_2325), hash(0x8422_2325_cbf2_9ce4));
    format!(
        "{{{:08x}-{:04x}-5{:03x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xfff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

/// The model name of the FMU built for `file`: `rotor_rub_` and the file's name, letters,
/// digits and `_` kept.
pub fn file_model_name(file: &FileModel) -> String {
    let base: String = file
        .name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    let base = base.trim_matches('_');
    if base.is_empty() {
        "rotor_rub_model".to_owned()
    } else {
        format!("rotor_rub_{base}")
    }
}

/// One variable's name, description, unit and causality.
fn about(file: &FileModel, v: FileVariable) -> (String, String, &'static str, &'static str) {
    let dof = |i: usize| file.dofs.get(i).map_or("?", String::as_str);
    // Lateral DOFs (named x…, y…) are in m, the others (tilts a…, b…) in rad.
    let lateral = |i: usize| dof(i).starts_with(['x', 'y']);
    match v {
        FileVariable::Time => ("time".into(), "time".into(), "s", "independent"),
        FileVariable::InternalStep => (
            "internal_step".into(),
            "longest internal step of the matrix stepper (every switch inside is located exactly)"
                .into(),
            "s",
            "parameter",
        ),
        FileVariable::InContact => (
            "in_contact".into(),
            "the rub station is in contact".into(),
            "",
            "output",
        ),
        FileVariable::ContactCount => (
            "contact_count".into(),
            "contact entries so far".into(),
            "",
            "output",
        ),
        FileVariable::RubX => (
            "rub_x".into(),
            "the rub station's relative displacement P = q_rotor - q_stator, x".into(),
            "m",
            "output",
        ),
        FileVariable::RubY => (
            "rub_y".into(),
            "the rub station's relative displacement P = q_rotor - q_stator, y".into(),
            "m",
            "output",
        ),
        FileVariable::Position(i) => (
            dof(i).to_owned(),
            format!("DOF {} ({})", i, dof(i)),
            if lateral(i) { "m" } else { "rad" },
            "output",
        ),
        FileVariable::Velocity(i) => (
            format!("v{}", dof(i)),
            format!("velocity of DOF {} ({})", i, dof(i)),
            if lateral(i) { "m/s" } else { "rad/s" },
            "output",
        ),
        FileVariable::Force(i) => (
            format!("f_{}", dof(i)),
            format!(
                "external force on DOF {} ({}), held over a communication step",
                i,
                dof(i)
            ),
            if lateral(i) { "N" } else { "N.m" },
            "input",
        ),
    }
}

/// Every variable of the FMU built for `file`, in value-reference order.
pub fn file_variables(file: &FileModel) -> Vec<(u32, FileVariable)> {
    let n = file.n() as u32;
    let mut out = vec![
        (0, FileVariable::Time),
        (1, FileVariable::InternalStep),
        (2, FileVariable::InContact),
        (3, FileVariable::ContactCount),
        (4, FileVariable::RubX),
        (5, FileVariable::RubY),
    ];
    for (base, make) in [
        (
            POSITION_BASE,
            FileVariable::Position as fn(usize) -> FileVariable,
        ),
        (VELOCITY_BASE, FileVariable::Velocity),
        (FORCE_BASE, FileVariable::Force),
    ] {
        out.extend((0..n).map(|i| (base + i, make(i as usize))));
    }
    out
}

pub use super::resource::{read_resource, resource_dir};

/// The model description of the FMU built for `file` (`resource`: its resource text).
pub fn file_model_description(version: Version, file: &FileModel, resource: &str) -> String {
    let mut x = String::new();
    let name = file_model_name(file);
    let token = file_token(resource);
    let description = escape(&format!(
        "{}: a rotor from matrices ({} DOFs) rubbing at ({}, {}), stated at {} rad/s, in SI; exact free flight, every contact switch located",
        file.name,
        file.n(),
        file.dofs.get(file.rub.0).map_or("?", String::as_str),
        file.dofs.get(file.rub.1).map_or("?", String::as_str),
        file.speed
    ));
    let tool = format!(
        "rotor-rub {} (cargo xtask fmu --model)",
        env!("CARGO_PKG_VERSION")
    );
    header(
        &mut x,
        version,
        [&name, &token, &description, &tool],
        Capabilities {
            serialize: false,
            early_return: false,
        },
    );
    let _ = writeln!(x, r#"  <UnitDefinitions>"#);
    for (unit, base) in [
        ("s", r#"s="1""#),
        ("m", r#"m="1""#),
        ("m/s", r#"m="1" s="-1""#),
        ("N", r#"kg="1" m="1" s="-2""#),
        ("rad", r#"rad="1""#),
        ("rad/s", r#"rad="1" s="-1""#),
        ("N.m", r#"kg="1" m="2" s="-2""#),
    ] {
        let _ = writeln!(
            x,
            r#"    <Unit name="{}"><BaseUnit {base}/></Unit>"#,
            escape(unit)
        );
    }
    let _ = writeln!(x, r#"  </UnitDefinitions>"#);
    let period = core::f64::consts::TAU / file.speed;
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0.0" stopTime="{:?}" stepSize="{:?}"/>"#,
        20.0 * period,
        INTERNAL_STEP
    );
    let vars: Vec<(u32, FileVariable)> = file_variables(file)
        .into_iter()
        .filter(|(_, v)| version == Version::Fmi3 || *v != FileVariable::Time)
        .collect();
    let _ = writeln!(x, r#"  <ModelVariables>"#);
    for &(vr, v) in &vars {
        let (vname, text, unit, causality) = about(file, v);
        let (vname, text) = (escape(&vname), escape(&text));
        let unit_attr = if unit.is_empty() {
            String::new()
        } else {
            format!(r#" unit="{}""#, escape(unit))
        };
        let variability = match v {
            FileVariable::InternalStep => "fixed",
            FileVariable::InContact | FileVariable::ContactCount => "discrete",
            _ => "continuous",
        };
        // Start values: the parameter's and the inputs' (outputs are calculated).
        let start = match v {
            FileVariable::InternalStep => format!(r#" start="{INTERNAL_STEP:?}""#),
            FileVariable::Force(i) => {
                format!(
                    r#" start="{:?}""#,
                    file.force.get(i).copied().unwrap_or(0.0)
                )
            }
            _ => String::new(),
        };
        let unit_attr = if v.kind() == FileKind::Float {
            unit_attr
        } else {
            String::new()
        };
        match version {
            Version::Fmi3 => {
                let element = match v.kind() {
                    FileKind::Float => "Float64",
                    FileKind::Boolean => "Boolean",
                    FileKind::Count => "Int64",
                };
                let _ = writeln!(
                    x,
                    r#"    <{element} name="{vname}" valueReference="{vr}" description="{text}" causality="{causality}" variability="{variability}"{unit_attr}{start}/>"#
                );
            }
            Version::Fmi2 => {
                let element = match v.kind() {
                    FileKind::Float => "Real",
                    FileKind::Boolean => "Boolean",
                    FileKind::Count => "Integer",
                };
                let _ = writeln!(
                    x,
                    r#"    <ScalarVariable name="{vname}" valueReference="{vr}" description="{text}" causality="{causality}" variability="{variability}"><{element}{unit_attr}{start}/></ScalarVariable>"#
                );
            }
        }
    }
    let _ = writeln!(x, r#"  </ModelVariables>"#);
    let _ = writeln!(x, r#"  <ModelStructure>"#);
    match version {
        Version::Fmi2 => {
            let _ = writeln!(x, r#"    <Outputs>"#);
            for (k, (_, v)) in vars.iter().enumerate() {
                if about(file, *v).3 == "output" {
                    let _ = writeln!(x, r#"      <Unknown index="{}"/>"#, k + 1);
                }
            }
            let _ = writeln!(x, r#"    </Outputs>"#);
            let _ = writeln!(x, r#"    <InitialUnknowns>"#);
            for (k, (_, v)) in vars.iter().enumerate() {
                if about(file, *v).3 == "output" {
                    let _ = writeln!(x, r#"      <Unknown index="{}" dependencies=""/>"#, k + 1);
                }
            }
            let _ = writeln!(x, r#"    </InitialUnknowns>"#);
        }
        Version::Fmi3 => {
            for (vr, v) in &vars {
                if about(file, *v).3 == "output" {
                    let _ = writeln!(x, r#"    <Output valueReference="{vr}"/>"#);
                }
            }
            for (vr, v) in &vars {
                if about(file, *v).3 == "output" {
                    let _ = writeln!(
                        x,
                        r#"    <InitialUnknown valueReference="{vr}" dependencies=""/>"#
                    );
                }
            }
        }
    }
    let _ = writeln!(x, r#"  </ModelStructure>"#);
    let _ = writeln!(x, r#"</fmiModelDescription>"#);
    x
}
