//! The declaration table: every symbol declared once, generated functions typed by it, and an
//! undeclared symbol failing the build with a message naming it and the formula.

use std::collections::HashSet;

use rotor_rub_codegen::emit::emit_formula;
use rotor_rub_codegen::expr::Graph;
use rotor_rub_codegen::ir::{Formula, Output};
use rotor_rub_codegen::model::parameters;
use rotor_rub_codegen::model::symbols::{DERIVED, INTERNAL, TABLE_PREFIX, all_groups};

#[test]
fn every_symbol_is_declared_once() {
    let mut seen = HashSet::new();
    for g in all_groups() {
        for &(name, _, _) in g.fields {
            assert!(seen.insert(name), "symbol `{name}` declared twice");
        }
    }
    for &(name, _) in INTERNAL {
        assert!(seen.insert(name), "symbol `{name}` declared twice");
    }
    let types: HashSet<_> = all_groups().iter().map(|g| g.ty).collect();
    assert_eq!(types.len(), all_groups().len(), "a struct declared twice");
}

fn formula_using(name: &str) -> (Graph, Formula) {
    let mut g = Graph::new();
    let nu = g.input("damping_ratio");
    let x = g.input(name);
    let e = g.mul(nu, x);
    let f = Formula {
        name: "probe".into(),
        summary: "test".into(),
        source: "test".into(),
        derivation: "test".into(),
        test_only: false,
        output_type: "Probe".into(),
        outputs: vec![Output {
            name: "o".into(),
            doc: String::new(),
            expr: e,
        }],
    };
    (g, f)
}

#[test]
#[should_panic(expected = "formula `probe` uses the symbol `nuu`")]
fn an_undeclared_symbol_fails_naming_symbol_and_formula() {
    let (g, f) = formula_using("nuu");
    let _ = emit_formula(&g, &f, all_groups());
}

#[test]
#[should_panic(expected = "formula `probe` uses the symbol `lam`")]
fn a_derivation_internal_symbol_cannot_be_an_input() {
    let (g, f) = formula_using("lam");
    let _ = emit_formula(&g, &f, all_groups());
}

#[test]
fn declared_symbols_become_struct_arguments() {
    let (g, f) = formula_using("speed_ratio");
    let e = emit_formula(&g, &f, all_groups());
    let text = e.tokens.to_string();
    assert!(text.contains("model : & ModelParams"), "{text}");
    assert!(
        !text.contains(": f64 ,") || text.contains("pub o : f64"),
        "{text}"
    );
}

#[test]
fn no_generated_function_takes_a_positional_f64() {
    let source = rotor_rub_codegen::generate().source;
    for line in source.lines().filter(|l| l.starts_with("pub fn")) {
        assert!(!line.contains("f64"), "positional f64 argument in `{line}`");
    }
    // Multi-line signatures: no parameter line of the form `name: f64,` outside structs.
    let mut in_sig = false;
    for line in source.lines() {
        if line.starts_with("pub fn") && !line.ends_with('{') {
            in_sig = true;
        } else if in_sig {
            assert!(
                !line.trim_end().ends_with(": f64,"),
                "positional f64: `{line}`"
            );
            if line.contains(") ->") {
                in_sig = false;
            }
        }
    }
}

/// The model's parameters are the parameter table's entries by name: every table entry is a
/// `ModelParams` symbol of its own name and a `Params` input `params.<name>`, and the derived
/// quantities are declared once beside them.
#[test]
fn model_parameters_are_the_table_entries_by_name() {
    let model = all_groups().iter().find(|g| g.ty == "ModelParams").unwrap();
    let table = all_groups().iter().find(|g| g.ty == "Params").unwrap();
    assert_eq!(table.external, Some("crate::params::Params"));
    for (k, entry) in parameters::MODEL.iter().enumerate() {
        assert_eq!(model.fields[k].0, entry.name);
        assert_eq!(model.fields[k].1, entry.name);
        assert_eq!(table.fields[k].0, format!("{TABLE_PREFIX}{}", entry.name));
        assert_eq!(table.fields[k].1, entry.name);
    }
    let derived: Vec<&str> = model.fields[parameters::MODEL.len()..]
        .iter()
        .map(|f| f.0)
        .collect();
    assert_eq!(derived, DERIVED.iter().map(|d| d.0).collect::<Vec<_>>());
}

/// `model_params` copies each table field into the `ModelParams` field of the same name: the
/// emitted constructor never assigns one name from another (a swapped pair cannot compile).
#[test]
fn model_params_copies_each_field_by_its_own_name() {
    let source = rotor_rub_codegen::generate().source;
    let start = source.find("pub fn model_params(").unwrap();
    let body = &source[start..source[start..].find("\n}\n").unwrap() + start];
    for line in body.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("let ") {
            let (local, value) = rest.trim_end_matches(';').split_once(" = ").unwrap();
            assert_eq!(value, format!("params.{local}"), "{line}");
        } else if let Some((field, value)) = line.trim_end_matches(',').split_once(": ")
            && parameters::MODEL.iter().any(|e| e.name == field)
        {
            assert_eq!(value, field, "{line}");
        }
    }
}
