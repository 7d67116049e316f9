//! μ = 0 is the paper, bit for bit (issue 12, `docs/MODEL.md` §10): with friction_coefficient = 0
//! every method's events and samples are identical (`==`, compared as bits) to what the code
//! produced before friction existed, on every preset's stator, whatever the radius ratio.

mod identity {
    pub mod fingerprint;
}

use identity::fingerprint::{problems, record, run, variants};
use rotor_rub::{Preset, Problem};

/// The record made by the code before friction (commit c4bc988 with
/// `identity/before-friction.patch` applied), see `identity/fingerprint.rs`.
const BEFORE: &str = include_str!("data/frictionless.txt");

#[test]
fn frictionless_output_is_bit_identical_to_before_friction() {
    if let Some(path) = std::env::var_os("RECORD") {
        std::fs::write(path, record()).unwrap();
        return;
    }
    let now = record();
    let mut differing = Vec::new();
    for (a, b) in now.lines().zip(BEFORE.lines()) {
        if a != b {
            differing.push(format!("now: {a}\nwas: {b}"));
        }
    }
    assert_eq!(now.lines().count(), BEFORE.lines().count());
    assert!(differing.is_empty(), "{}", differing.join("\n"));
}

/// At μ = 0 the radius ratio is not used: no slip velocity is tracked.
#[test]
fn radius_ratio_changes_nothing_without_friction() {
    for (name, problem) in problems().into_iter().step_by(3) {
        for (variant, options) in variants() {
            let base = run(&problem, options.as_ref());
            for rho in [1e-3, 0.5, 1e5] {
                let mut other = problem;
                other.params.radius_ratio = rho;
                assert!(
                    run(&other, options.as_ref()) == base,
                    "{name} {variant}: radius_ratio = {rho} changed the output"
                );
            }
        }
    }
}

/// Every planar preset's stator (with μ set to 0) is among the recorded problems (the ring
/// presets are matrix models, outside this record).
#[test]
fn every_preset_is_covered() {
    let recorded: Vec<Problem> = problems().into_iter().map(|(_, p)| p).collect();
    for preset in Preset::PLANAR {
        let mut p = preset.problem();
        p.params.friction_coefficient = 0.0;
        p.params.radius_ratio = rotor_rub::Params::DEFAULT.radius_ratio;
        assert!(
            recorded
                .iter()
                .any(|r| r.params == p.params && r.initial == p.initial),
            "preset {} is not in the identity record",
            preset.name()
        );
    }
}
