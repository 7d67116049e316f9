//! Helpers shared by the integration tests.

use std::fs;
use std::path::Path;

use assert_cmd::Command;
use rotor_rub::{Method, Options, Preset, PropagationError, Propagator};

/// The `rotor-rub` binary.
pub fn bin() -> Command {
    assert_cmd::cargo::cargo_bin_cmd!("rotor-rub")
}

/// Whether `method` is implemented yet in the library (the runtime is built in parallel with the
/// CLI): tests that need a method skip, saying so, while it reports "not built yet".
pub fn available(method: Method) -> bool {
    match Propagator::new(&Preset::Paper.problem(), &Options::with_method(method)) {
        Err(PropagationError::InvalidOption { what, .. }) if what.contains("not built yet") => {
            eprintln!("skipped: method {} is not built yet", method.name());
            false
        }
        _ => true,
    }
}

/// Return from the test early (skipped) unless every listed method is available.
#[macro_export]
macro_rules! require {
    ($($m:expr),+) => {
        if !($($crate::common::available($m))&&+) {
            return;
        }
    };
}

/// Parse a CSV file: its header and rows of fields.
pub fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines
        .next()
        .expect("a header line")
        .split(',')
        .map(String::from)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

/// Parse a field as f64.
pub fn num(field: &str) -> f64 {
    field
        .parse()
        .unwrap_or_else(|_| panic!("'{field}' is not a number"))
}

/// Names of the entries of a directory, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}
