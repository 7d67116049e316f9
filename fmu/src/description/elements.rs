//! The elements of a model description: unit definitions, one variable (FMI 2.0's
//! `ScalarVariable` or FMI 3.0's typed element) and the model structure.

use std::fmt::Write;

use super::{Version, dependencies, escape, number};
use crate::units::{SI_UNITS, Units};
use crate::variables::{Kind, Role, Target, Variable};

pub(super) fn unit_definitions(x: &mut String, units: Units) {
    let _ = writeln!(x, r#"  <UnitDefinitions>"#);
    match units {
        Units::Dimensionless => {
            let _ = writeln!(x, r#"    <Unit name="1"/>"#);
        }
        Units::Si => {
            for u in &SI_UNITS {
                let _ = write!(x, r#"    <Unit name="{}">"#, escape(u.name));
                let exponents: Vec<String> = u
                    .base
                    .iter()
                    .filter(|(_, e)| *e != 0)
                    .map(|(b, e)| format!(r#"{b}="{e}""#))
                    .collect();
                if !exponents.is_empty() {
                    let _ = write!(x, "<BaseUnit {}/>", exponents.join(" "));
                }
                for (name, factor) in u.display {
                    let _ = write!(
                        x,
                        r#"<DisplayUnit name="{}" factor="{}"/>"#,
                        escape(name),
                        number(*factor)
                    );
                }
                let _ = writeln!(x, "</Unit>");
            }
        }
    }
    let _ = writeln!(x, r#"  </UnitDefinitions>"#);
}

pub(super) fn model_structure(x: &mut String, version: Version, vars: &[Variable]) {
    let outputs: Vec<(usize, &Variable)> = vars
        .iter()
        .enumerate()
        .filter(|(_, v)| is_output(v))
        .collect();
    let depends = |v: &Variable| match v.target {
        Target::Output(o) => dependencies(o),
        _ => &[],
    };
    let _ = writeln!(x, r#"  <ModelStructure>"#);
    match version {
        Version::Fmi2 => {
            // By index: the 1-based position in ModelVariables.
            let index = |vr: u32| vars.iter().position(|v| v.vr == vr).map_or(0, |k| k + 1);
            let _ = writeln!(x, r#"    <Outputs>"#);
            for (k, v) in &outputs {
                let deps: Vec<String> = depends(v).iter().map(|&r| index(r).to_string()).collect();
                let kinds = vec!["dependent"; deps.len()].join(" ");
                let kinds = if deps.is_empty() {
                    String::new()
                } else {
                    format!(r#" dependenciesKind="{kinds}""#)
                };
                let _ = writeln!(
                    x,
                    r#"      <Unknown index="{}" dependencies="{}"{kinds}/>"#,
                    k + 1,
                    deps.join(" ")
                );
            }
            let _ = writeln!(x, r#"    </Outputs>"#);
            let _ = writeln!(x, r#"    <InitialUnknowns>"#);
            for (k, _) in &outputs {
                let _ = writeln!(x, r#"      <Unknown index="{}"/>"#, k + 1);
            }
            let _ = writeln!(x, r#"    </InitialUnknowns>"#);
        }
        Version::Fmi3 => {
            for (_, v) in &outputs {
                let deps: Vec<String> = depends(v).iter().map(u32::to_string).collect();
                let kinds = if deps.is_empty() {
                    String::new()
                } else {
                    format!(
                        r#" dependenciesKind="{}""#,
                        vec!["dependent"; deps.len()].join(" ")
                    )
                };
                let _ = writeln!(
                    x,
                    r#"    <Output valueReference="{}" dependencies="{}"{kinds}/>"#,
                    v.vr,
                    deps.join(" ")
                );
            }
            for (_, v) in &outputs {
                let _ = writeln!(x, r#"    <InitialUnknown valueReference="{}"/>"#, v.vr);
            }
        }
    }
    let _ = writeln!(x, r#"  </ModelStructure>"#);
}

fn is_output(v: &Variable) -> bool {
    matches!(v.role, Role::ContinuousOutput | Role::DiscreteOutput)
}

/// causality, variability and initial of a role.
pub fn attributes(role: Role) -> (&'static str, &'static str, Option<&'static str>) {
    match role {
        Role::Independent => ("independent", "continuous", None),
        Role::ContinuousOutput => ("output", "continuous", Some("calculated")),
        Role::DiscreteOutput => ("output", "discrete", Some("calculated")),
        Role::Input => ("input", "continuous", None),
        Role::Tunable => ("parameter", "tunable", Some("exact")),
        Role::Fixed => ("parameter", "fixed", Some("exact")),
    }
}

fn head(x: &mut String, v: &Variable, units: Units) -> (Option<&'static str>, String) {
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
        let _ = write!(bounds, r#" unit="{}""#, escape(v.dimension.unit(units)));
        if let Some(shown) = v.dimension.display_unit(units) {
            let _ = write!(bounds, r#" displayUnit="{}""#, escape(shown));
        }
    }
    if v.kind != Kind::Bool {
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

pub(super) fn fmi2_variable(x: &mut String, v: &Variable, units: Units) {
    x.push_str("    <ScalarVariable ");
    let (initial, bounds) = head(x, v, units);
    if let Some(i) = initial {
        let _ = write!(x, r#" initial="{i}""#);
    }
    let element = match v.kind {
        Kind::Float => "Real",
        Kind::Int64 | Kind::Int32 => "Integer",
        Kind::Bool => "Boolean",
    };
    // FMI 2.0's Integer min/max and start are integers.
    let bounds = if element == "Integer" {
        bounds.replace(".0\"", "\"")
    } else {
        bounds
    };
    let _ = writeln!(x, ">\n      <{element}{bounds}/>\n    </ScalarVariable>");
}

pub(super) fn fmi3_variable(x: &mut String, v: &Variable, units: Units) {
    let element = match v.kind {
        Kind::Float => "Float64",
        Kind::Int64 => "Int64",
        Kind::Int32 => "Int32",
        Kind::Bool => "Boolean",
    };
    let _ = write!(x, "    <{element} ");
    let (initial, bounds) = head(x, v, units);
    if let Some(i) = initial {
        let _ = write!(x, r#" initial="{i}""#);
    }
    let bounds = if matches!(v.kind, Kind::Int64 | Kind::Int32) {
        bounds.replace(".0\"", "\"")
    } else {
        bounds
    };
    let _ = writeln!(x, "{bounds}/>");
}
