//! Rotors from matrices against the planar model (issue 28 item 6, issue 29 item 2; the design
//! note's §11 limits): the planar `Propagator` is code independent of `rotor_rub::matrix` (its
//! own generated fields, its own solvers), so agreement checks the matrix methods end to end.
//!
//! - The paper's Jeffcott written as matrices (n = 2, M = I, C = 2ν I, K = I, K_c = K_s, the
//!   stator fixed) is the planar model: every method's switches within 1e-10 of the planar
//!   Taylor method's, frictionless, slipping with reversals and rolling.
//! - The ring held fixed (m̂ → ∞) is the planar model with K_s = k̂_c I: differences shrink
//!   like 1/m̂.
//! - An isotropic support K_s = k_s I with a massless ring (m̂ → 0, the contact mode critically
//!   damped) is the planar model with the series stiffness k_s k̂_c / (k_s + k̂_c): differences
//!   shrink like √m̂ (the damping ĉ = 2√(m̂ (k_s + k̂_c)) vanishes like √m̂); then k̂_c → ∞ is
//!   the paper's K_s.
//! - An anisotropic massless limit exists (the runs converge as m̂ → 0) but it is the
//!   normal-force law — the contact force on the rotor stays normal, N n — not the paper's
//!   K_s g(d), which is not normal when K_s is not isotropic: the difference to the planar model
//!   with the series stiffness k̂_c K_s (k̂_c I + K_s)⁻¹ does not shrink.

mod matrix_common;

use matrix_common::{
    difference, grid, jeffcott, jeffcott_start, matrix, matrix_samples, planar, planar_samples,
    sample_distance,
};
use rotor_rub::matrix::{ring_model, ring_start};
use rotor_rub::method::Method;
use rotor_rub::{Parameter, Preset, Problem};

const METHODS: [Method; 5] = [
    Method::Dop853,
    Method::Rk45,
    Method::Hybrid,
    Method::Taylor,
    Method::Analytic,
];

/// The tightest tolerance each method takes for the comparisons.
fn tight(method: Method) -> Option<f64> {
    Some(if method == Method::Rk45 { 1e-14 } else { 1e-13 })
}

fn with(preset: Preset, set: &[(Parameter, f64)]) -> Problem {
    let mut problem = preset.problem();
    if preset == Preset::Paper {
        // The limits are compared on the sparse rub (ε̂ = 0): the heavy rub amplifies
        // differences along a run.
        Parameter::OffsetX.set(&mut problem, 0.0);
        Parameter::OffsetY.set(&mut problem, 0.0);
    }
    for &(p, v) in set {
        p.set(&mut problem, v);
    }
    problem.validate().expect("a valid problem");
    problem
}

fn all(y: &[f64]) -> Vec<f64> {
    y.to_vec()
}

/// The rotor's entries of a ring state (x, y, x', y').
fn rotor_of_ring(y: &[f64]) -> Vec<f64> {
    vec![y[0], y[1], y[4], y[5]]
}

#[test]
fn the_jeffcott_as_matrices_is_the_planar_model_for_every_method() {
    for (name, preset, periods) in [
        ("paper", Preset::Paper, 10.0),
        ("friction (reversals)", Preset::Friction, 10.0),
        ("dry whip (rolling)", Preset::DryWhip, 5.0),
    ] {
        let problem = preset.problem();
        let end = periods * problem.params.forcing_period();
        let want = planar(&problem, Method::Taylor, Some(1e-13), end);
        let model = jeffcott(&problem.params);
        for method in METHODS {
            let got = matrix(&model, jeffcott_start(&problem), method, tight(method), end);
            let (dt, dy) = difference(
                &format!("{name}, {method:?}"),
                &got,
                &want,
                usize::MAX,
                &all,
            );
            println!(
                "{name} {method:?}: {} switches, worst time {dt:.1e}, state {dy:.1e}",
                got.len()
            );
            assert!(
                dt <= 1e-10 && dy <= 1e-9,
                "{name}, {method:?}: {dt:e} in time, {dy:e} in state"
            );
        }
    }
}

/// The ring model of the paper's rotor with `set` applied: rotor states (x, y, x', y') at
/// `times` (taylor at 1e-13).
fn ring_samples(set: &[(Parameter, f64)], times: &[f64]) -> Vec<Vec<f64>> {
    let problem = with(Preset::Paper, set);
    let model = ring_model(&problem.params).expect("the ring states");
    matrix_samples(&model, ring_start(&problem), times)
        .iter()
        .map(|y| rotor_of_ring(y))
        .collect()
}

fn isotropic(k: f64) -> Problem {
    with(
        Preset::Paper,
        &[
            (Parameter::KXx, k),
            (Parameter::KXy, 0.0),
            (Parameter::KYx, 0.0),
            (Parameter::KYy, k),
        ],
    )
}

/// Sample times: 200 over `periods` forcing periods of the paper's rotor.
fn times(periods: f64) -> Vec<f64> {
    grid(
        periods * Preset::Paper.problem().params.forcing_period(),
        200,
    )
}

#[test]
fn a_ring_held_fixed_is_the_planar_model() {
    let kc = 100.0;
    let times = times(5.0);
    let want = planar_samples(&isotropic(kc), &times);
    // Beyond the table's range of m̂ (≤ 1e3): the matrix model itself takes any mass.
    let errors: Vec<f64> = [1e6, 1e8]
        .iter()
        .map(|&mass| {
            let mut problem = with(
                Preset::Paper,
                &[
                    (Parameter::StatorMassRatio, 1.0),
                    (Parameter::ContactStiffness, kc),
                    (Parameter::StatorDamping, 0.5),
                ],
            );
            problem.params.stator_mass_ratio = mass;
            let model = ring_model(&problem.params).expect("the ring states");
            let got: Vec<Vec<f64>> = matrix_samples(&model, ring_start(&problem), &times)
                .iter()
                .map(|y| rotor_of_ring(y))
                .collect();
            sample_distance(&got, &want)
        })
        .collect();
    println!("held ring: m̂ = 1e6, 1e8: {errors:?}");
    let ratio = errors[0] / errors[1];
    assert!(errors[1] < 1e-6, "{errors:?}");
    assert!(
        (30.0..=300.0).contains(&ratio),
        "1/m̂ convergence: ratio {ratio} of {errors:?}"
    );
}

/// The ring with support `ks` (rows), contact stiffness `kc`, mass `mass` and its contact mode
/// critically damped.
fn light_ring(ks: [[f64; 2]; 2], kc: f64, mass: f64) -> Vec<(Parameter, f64)> {
    let stiffest = kc + ks[0][0].max(ks[1][1]);
    vec![
        (Parameter::KXx, ks[0][0]),
        (Parameter::KXy, ks[0][1]),
        (Parameter::KYx, ks[1][0]),
        (Parameter::KYy, ks[1][1]),
        (Parameter::StatorMassRatio, mass),
        (Parameter::ContactStiffness, kc),
        (Parameter::StatorDamping, 2.0 * (mass * stiffest).sqrt()),
    ]
}

#[test]
fn an_isotropic_massless_ring_is_the_series_stiffness_then_the_paper_model() {
    let (ks, kc) = (20.0, 100.0);
    let times = times(3.0);
    let want = planar_samples(&isotropic(ks * kc / (ks + kc)), &times);
    let errors: Vec<f64> = [1e-2, 1e-3, 1e-4]
        .iter()
        .map(|&mass| {
            let got = ring_samples(&light_ring([[ks, 0.0], [0.0, ks]], kc, mass), &times);
            sample_distance(&got, &want)
        })
        .collect();
    println!("light isotropic ring: m̂ = 1e-2, 1e-3, 1e-4: {errors:?}");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!(
            (10f64.sqrt() / 1.6..=10f64.sqrt() * 1.6).contains(&ratio),
            "√m̂ convergence: ratio {ratio} of {errors:?}"
        );
    }
    // The series stiffness tends to k_s as k̂_c → ∞: the paper's model (planar runs, errors
    // like 1/k̂_c).
    let paper = planar_samples(&isotropic(ks), &times);
    let errors: Vec<f64> = [1e3, 1e5]
        .iter()
        .map(|&kc| {
            sample_distance(
                &planar_samples(&isotropic(ks * kc / (ks + kc)), &times),
                &paper,
            )
        })
        .collect();
    println!("series stiffness: k̂_c = 1e3, 1e5: {errors:?}");
    let ratio = errors[0] / errors[1];
    assert!(
        (30.0..=300.0).contains(&ratio),
        "1/k̂_c: ratio {ratio} of {errors:?}"
    );
}

#[test]
fn the_anisotropic_massless_limit_is_the_normal_force_law_not_the_paper_law() {
    let (ks, kc) = ([[10.0, 0.0], [0.0, 60.0]], 100.0);
    // The paper's offset: deep contacts, where the two laws' directions part.
    let heavy = [(Parameter::OffsetX, 0.3), (Parameter::OffsetY, -0.2)];
    let times = times(1.0);
    let runs: Vec<Vec<Vec<f64>>> = [1e-3, 1e-4, 1e-5, 1e-6]
        .iter()
        .map(|&mass| ring_samples(&[light_ring(ks, kc, mass), heavy.to_vec()].concat(), &times))
        .collect();
    // The massless limit exists: successive runs (m̂ down by 10 each) draw closer.
    let steps: Vec<f64> = runs
        .windows(2)
        .map(|w| sample_distance(&w[0], &w[1]))
        .collect();
    println!("anisotropic light ring: successive differences {steps:?}");
    assert!(steps.windows(2).all(|w| w[1] < w[0]), "{steps:?}");
    let b = steps[steps.len() - 1];
    // … and it is not the planar K g(d) law with the series stiffness k̂_c K_s (k̂_c I + K_s)⁻¹
    // (diagonal here: k̂_c k_i / (k̂_c + k_i)), whose force is not normal.
    let series = |k: f64| kc * k / (kc + k);
    let want = planar_samples(
        &with(
            Preset::Paper,
            &[
                (Parameter::KXx, series(ks[0][0])),
                (Parameter::KXy, 0.0),
                (Parameter::KYx, 0.0),
                (Parameter::KYy, series(ks[1][1])),
                heavy[0],
                heavy[1],
            ],
        ),
        &times,
    );
    let distance = sample_distance(&runs[3], &want);
    println!("anisotropic: the limit against the planar series law {distance:.2e}");
    // The last run is within about b of the limit (the steps shrink): the planar law is 10
    // times farther.
    assert!(distance > 10.0 * b, "{distance:e} against {b:e}");
}
