//! The declaration table: every symbol declared once, generated functions typed by it, and an
//! undeclared symbol failing the build with a message naming it and the formula.

use std::collections::HashSet;

use rotor_rub_codegen::emit::{Formula, Output, emit_formula};
use rotor_rub_codegen::expr::Graph;
use rotor_rub_codegen::model::symbols::{GROUPS, INTERNAL};

#[test]
fn every_symbol_is_declared_once() {
    let mut seen = HashSet::new();
    for g in GROUPS {
        for &(name, _, _) in g.fields {
            assert!(seen.insert(name), "symbol `{name}` declared twice");
        }
    }
    for &(name, _) in INTERNAL {
        assert!(seen.insert(name), "symbol `{name}` declared twice");
    }
    let types: HashSet<_> = GROUPS.iter().map(|g| g.ty).collect();
    assert_eq!(types.len(), GROUPS.len(), "a struct declared twice");
}

fn formula_using(name: &str) -> (Graph, Formula) {
    let mut g = Graph::new();
    let nu = g.input("nu");
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
    let _ = emit_formula(&g, &f, GROUPS);
}

#[test]
#[should_panic(expected = "formula `probe` uses the symbol `lam`")]
fn a_derivation_internal_symbol_cannot_be_an_input() {
    let (g, f) = formula_using("lam");
    let _ = emit_formula(&g, &f, GROUPS);
}

#[test]
fn declared_symbols_become_struct_arguments() {
    let (g, f) = formula_using("eta");
    let e = emit_formula(&g, &f, GROUPS);
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
