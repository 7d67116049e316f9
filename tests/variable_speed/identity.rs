//! η' = 0 reproduces the constant-speed run bit for bit: a profile holding one speed, run with
//! every method (the numerical methods integrate the variable-speed field with η' = 0, the
//! closed-form methods run on the held speed), gives the events and samples of the
//! constant-speed run, compared as bits.

use std::fmt::Write as _;

use rotor_rub::speed::SpeedProfile;
use rotor_rub::variable_speed::{
    SpeedProfileStepper, VariableSpeedOptions, VariableSpeedPropagator,
};
use rotor_rub::{
    ContactScheme, Method, Options, Params, Preset, Problem, Propagate, Propagator, State, Stepper,
    StepperConfig, advance_to,
};

use super::support::constant_points;

fn bits(out: &mut String, values: &[f64]) {
    for v in values {
        let _ = write!(out, " {:016x}", v.to_bits());
    }
}

/// Events and 160 samples over 40 time units, bit for bit.
fn fingerprint(p: &mut dyn Propagate) -> String {
    let mut out = String::new();
    for k in 1..=160 {
        let t = 0.25 * f64::from(k);
        let s = advance_to(p, t, |e| {
            let _ = write!(out, "event {}", e.kind.name());
            bits(
                &mut out,
                &[e.time, e.state.x, e.state.y, e.state.vx, e.state.vy],
            );
            out.push('\n');
        })
        .unwrap();
        out.push_str(s.regime.name());
        bits(
            &mut out,
            &[s.time, s.state.x, s.state.y, s.state.vx, s.state.vy],
        );
        out.push('\n');
    }
    out
}

/// The paper's stators and the friction presets (a held speed takes friction), at three speeds
/// and two starts.
fn problems() -> Vec<(String, Problem)> {
    let mut out = Vec::new();
    for (name, preset) in [
        ("paper", Preset::Paper),
        ("paper-text", Preset::PaperText),
        ("friction", Preset::Friction),
        ("dry-whip", Preset::DryWhip),
    ] {
        for eta in [1.0, 1.5, 2.5] {
            for (start, initial) in [
                ("start", State::new(0.1, 0.1, 0.0, 0.0)),
                ("in-contact", State::new(1.2, 0.3, -0.5, 1.5)),
            ] {
                let mut p = preset.problem();
                p.params.speed_ratio = eta;
                p.params.phase = 0.7;
                p.initial = initial;
                out.push((format!("{name}/η={eta}/{start}"), p));
            }
        }
    }
    out
}

fn variants() -> Vec<Options> {
    vec![
        Options::with_method(Method::Analytic),
        Options {
            contact_scheme: ContactScheme::Exprb2,
            ..Options::with_method(Method::Analytic)
        },
        Options::with_method(Method::Hybrid),
        Options::with_method(Method::Dop853),
        Options::with_method(Method::Rk45),
    ]
}

#[test]
fn a_held_speed_reproduces_the_constant_speed_run_bit_for_bit() {
    let mut compared = 0;
    let mut kinds = std::collections::BTreeSet::new();
    for (name, problem) in problems() {
        let eta = problem.params.speed_ratio;
        // The profile's own speed; the problem's is not used on a profile.
        let points = constant_points(eta, 25.0);
        let profile = SpeedProfile::new(&points).unwrap();
        let on_profile = Problem {
            params: Params {
                speed_ratio: 7.0,
                ..problem.params
            },
            ..problem
        };
        for options in variants() {
            let mut constant = Propagator::new(&problem, &options).unwrap();
            let mut variable = VariableSpeedPropagator::new(
                &on_profile,
                profile,
                &VariableSpeedOptions::new(options),
            )
            .unwrap();
            let a = fingerprint(&mut constant);
            let b = fingerprint(&mut variable);
            kinds.extend(
                a.lines()
                    .filter_map(|l| l.strip_prefix("event "))
                    .filter_map(|l| l.split(' ').next())
                    .map(String::from),
            );
            assert!(a.contains("event"), "{name}: no switch to compare");
            assert!(
                a == b,
                "{name} η = {eta} {options:?}: the held speed differs from the constant speed"
            );
            // One segment: the speed held across both points and after the last.
            assert_eq!(variable.segments(), 1);
            compared += 1;
        }
    }
    assert_eq!(compared, 24 * 5);
    // Friction's switches were compared too.
    eprintln!("switches compared: {kinds:?}");
    assert!(
        kinds.contains("roll") && kinds.contains("slip"),
        "{kinds:?}"
    );
}

#[test]
fn the_stepper_on_a_held_speed_is_the_constant_speed_stepper() {
    for (name, problem) in problems() {
        let points = constant_points(problem.params.speed_ratio, 10.0);
        let profile = SpeedProfile::new(&points).unwrap();
        let config = StepperConfig::with_dt(0.01);
        let mut constant = Stepper::new(&problem, config).unwrap();
        let mut variable = SpeedProfileStepper::new(&problem, profile, config).unwrap();
        for _ in 0..3000 {
            let a = constant.step(0.01).unwrap();
            let b = variable.step(0.01).unwrap();
            assert!(a == b, "{name}: step at τ = {} differs", a.time);
            assert_eq!(a.state.x.to_bits(), b.state.x.to_bits());
        }
    }
}

/// The comparison can fail: a phase moved by one ulp, or the speed-change force switched on
/// at a rate of 1e-300, changes the bits.
#[test]
fn the_comparison_sees_a_one_ulp_change() {
    let (_, problem) = problems()[2].clone();
    let eta = problem.params.speed_ratio;
    let options = Options::with_method(Method::Dop853);
    let mut constant = Propagator::new(&problem, &options).unwrap();
    let reference = fingerprint(&mut constant);
    let nudged = Problem {
        params: Params {
            phase: f64::from_bits(problem.params.phase.to_bits() + 1),
            ..problem.params
        },
        ..problem
    };
    let points = constant_points(eta, 25.0);
    let profile = SpeedProfile::new(&points).unwrap();
    let mut variable =
        VariableSpeedPropagator::new(&nudged, profile, &VariableSpeedOptions::new(options))
            .unwrap();
    assert!(fingerprint(&mut variable) != reference);
    let ramped = [
        rotor_rub::speed::SpeedPoint::new(0.0, eta),
        rotor_rub::speed::SpeedPoint::new(25.0, eta + 1e-13),
    ];
    let profile = SpeedProfile::new(&ramped).unwrap();
    let mut variable =
        VariableSpeedPropagator::new(&problem, profile, &VariableSpeedOptions::new(options))
            .unwrap();
    assert!(fingerprint(&mut variable) != reference);
}
