//! Every output stays bit-identical through a refactoring: every method (and the stepper, and
//! a speed profile) on every preset, friction and the input force included, against the record
//! `tests/data/outputs.txt` (see `identity/outputs.rs` for what it covers and how to make it
//! again when a change moves bits on purpose).

mod identity {
    pub mod outputs;
}

use identity::outputs::{record, runs};

const RECORDED: &str = include_str!("data/outputs.txt");

#[test]
fn every_output_is_bit_identical_to_the_record() {
    let runs = runs();
    if let Some(path) = std::env::var_os("DUMP") {
        let mut text = String::new();
        for (name, run) in &runs {
            text.push_str("run ");
            text.push_str(name);
            text.push('\n');
            text.push_str(run);
        }
        std::fs::write(path, text).unwrap();
    }
    let now = record(&runs);
    if let Some(path) = std::env::var_os("RECORD") {
        std::fs::write(path, &now).unwrap();
        return;
    }
    let differing: Vec<String> = now
        .lines()
        .zip(RECORDED.lines())
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("now: {a}\nwas: {b}"))
        .collect();
    assert_eq!(now.lines().count(), RECORDED.lines().count());
    assert!(
        differing.is_empty(),
        "{} of {} runs differ:\n{}",
        differing.len(),
        now.lines().count(),
        differing.join("\n")
    );
}
