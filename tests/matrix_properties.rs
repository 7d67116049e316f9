//! Properties of the stator ring's runs (issue 28 item 6), over random rings, supports,
//! offsets, speeds and friction (proptest), by the taylor method at tol 1e-12:
//!
//! - Continuity: no body's position or velocity jumps at an event (the contact is a force, not
//!   an impact): the states 1e-9 before and after each event, and the event's own state, agree
//!   to 1e-6.
//! - Work–energy: the change of the energy of rotor + ring + contact spring,
//!   E = ½|q'|² + ½|q|² + ½m̂|p'|² + ½pᵀK_s p + ½k̂_c(z − 1)₊², equals the integral of the
//!   power of what is not in it — unbalance and input force on the rotor, −2ν|q'|², −ĉ|p'|²,
//!   the support's circulatory part −p'ᵀ((K_s − K_sᵀ)/2) p, and friction −f (d'·t) (f = μσN
//!   slipping, λ rolling, from the oracle's hand-written law, `matrix_oracle/ring.rs`) —
//!   integrated by Simpson's rule between events (spacing ≤ 2e-3), to 1e-7 of the energy.

#[allow(
    dead_code,
    reason = "the properties use the oracle's law, not its runs"
)]
mod matrix_oracle {
    pub mod ring;
}
mod matrix_common;

use matrix_common::options;
use matrix_oracle::ring::Ring;
use proptest::prelude::*;
use rotor_rub::matrix::{MatrixPropagator, RingModel, ring_model, ring_start};
use rotor_rub::method::Method;
use rotor_rub::propagate::{EventKind, Regime};
use rotor_rub::{Parameter, Preset, Problem, Propagate, events};

/// A random ring problem.
fn problems() -> impl Strategy<Value = Problem> {
    (
        (0.2f64..5.0, 30.0f64..300.0, 0.0f64..1.0),
        (10.0f64..60.0, -10.0f64..10.0, -10.0f64..10.0, 10.0f64..60.0),
        (-0.3f64..0.3, -0.3f64..0.3, 0.9f64..2.5),
        (prop_oneof![Just(0.0), 0.05f64..0.6], 0.5f64..5.0),
    )
        .prop_map(
            |((m, kc, c), (kxx, kxy, kyx, kyy), (ex, ey, eta), (mu, rho))| {
                let mut problem = Preset::Paper.problem();
                for (p, v) in [
                    (Parameter::StatorMassRatio, m),
                    (Parameter::ContactStiffness, kc),
                    (Parameter::StatorDamping, c),
                    (Parameter::KXx, kxx),
                    (Parameter::KXy, kxy),
                    (Parameter::KYx, kyx),
                    (Parameter::KYy, kyy),
                    (Parameter::OffsetX, ex),
                    (Parameter::OffsetY, ey),
                    (Parameter::SpeedRatio, eta),
                    (Parameter::FrictionCoefficient, mu),
                    (Parameter::RadiusRatio, rho),
                ] {
                    p.set(&mut problem, v);
                }
                problem
            },
        )
}

fn propagator<'a>(model: &'a RingModel, problem: &Problem) -> MatrixPropagator<&'a RingModel, 8> {
    MatrixPropagator::new(
        model,
        0.0,
        ring_start(problem),
        &options(Method::Taylor, Some(1e-12)),
    )
    .expect("the run starts")
}

fn state_at(p: &mut MatrixPropagator<&RingModel, 8>, t: f64) -> [f64; 8] {
    while p.advance(t).expect("the run goes on").is_some() {}
    p.state().as_slice().try_into().expect("eight states")
}

fn distance(a: &[f64; 8], b: &[f64; 8]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// E of the module docs.
fn energy(problem: &Problem, y: &[f64; 8]) -> f64 {
    let p = &problem.params;
    let sq = |a: f64, b: f64| a * a + b * b;
    let (xs, ys) = (y[2], y[3]);
    let support = 0.5 * (p.k_xx * xs * xs + (p.k_xy + p.k_yx) * xs * ys + p.k_yy * ys * ys);
    let z = sq(y[0] - y[2] - p.offset_x, y[1] - y[3] - p.offset_y).sqrt();
    let spring = 0.5 * p.contact_stiffness * (z - 1.0).max(0.0).powi(2);
    0.5 * (sq(y[4], y[5]) + sq(y[0], y[1]))
        + 0.5 * p.stator_mass_ratio * sq(y[6], y[7])
        + support
        + spring
}

/// The power of the module docs at (t, y) in `regime` (σ: the slip direction there).
fn power(problem: &Problem, ring: &Ring, regime: Regime, sigma: f64, t: f64, y: &[f64; 8]) -> f64 {
    let p = &problem.params;
    let f = p.mass_ratio * p.eccentricity_ratio * p.speed_ratio * p.speed_ratio;
    let th = p.speed_ratio * t + p.phase;
    let drive = (f * th.cos() + p.force_x) * y[4] + (f * th.sin() + p.force_y) * y[5];
    let rotor_damping = 2.0 * p.damping_ratio * (y[4] * y[4] + y[5] * y[5]);
    let ring_damping = p.stator_damping * (y[6] * y[6] + y[7] * y[7]);
    let a = 0.5 * (p.k_xy - p.k_yx);
    // p'ᵀ K_a p with K_a = [[0, a], [−a, 0]].
    let circulatory = y[6] * a * y[3] - y[7] * a * y[2];
    let friction = match regime {
        Regime::Free => 0.0,
        _ if p.friction_coefficient == 0.0 => 0.0,
        _ => {
            let (normal, _, lambda) = ring.friction(t, y);
            let force = if regime == Regime::Rolling {
                lambda
            } else {
                p.friction_coefficient * sigma * normal
            };
            let (dx, dy) = (y[0] - y[2] - p.offset_x, y[1] - y[3] - p.offset_y);
            let z = dx.hypot(dy);
            let tangent = (-dy / z, dx / z);
            force * ((y[4] - y[6]) * tangent.0 + (y[5] - y[7]) * tangent.1)
        }
    };
    drive - rotor_damping - ring_damping - circulatory - friction
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn both_bodies_are_continuous_at_every_event(problem in problems()) {
        let model = ring_model(&problem.params).expect("the ring states");
        let end = 3.0 * problem.params.forcing_period();
        let found: Vec<_> = events(&mut propagator(&model, &problem), end)
            .collect::<Result<_, _>>()
            .expect("the run goes on");
        let delta = 1e-9;
        let mut p = propagator(&model, &problem);
        let mut last = 0.0;
        for (k, e) in found.iter().enumerate() {
            let next = found.get(k + 1).map_or(end, |n| n.time);
            if e.time - delta <= last || e.time + delta >= next {
                continue;
            }
            let before = state_at(&mut p, e.time - delta);
            let after = state_at(&mut p, e.time + delta);
            let at: [f64; 8] = e.state.as_slice().try_into().expect("eight states");
            let jump = distance(&before, &after).max(distance(&before, &at));
            prop_assert!(jump <= 1e-6, "{:?} at {}: jump {jump:e}", e.kind, e.time);
            last = e.time + delta;
        }
    }

    #[test]
    fn the_work_energy_balance_holds_along_the_run(problem in problems()) {
        let model = ring_model(&problem.params).expect("the ring states");
        let ring = Ring::of(&problem.params);
        let end = 3.0 * problem.params.forcing_period();
        let found: Vec<_> = events(&mut propagator(&model, &problem), end)
            .collect::<Result<_, _>>()
            .expect("the run goes on");
        let mut p = propagator(&model, &problem);
        // Each stretch between events: (start, end, regime).
        let mut stretches = Vec::new();
        let (mut from, mut regime) = (0.0, p.regime());
        for e in &found {
            stretches.push((from, e.time, regime));
            from = e.time;
            regime = match e.kind {
                EventKind::Exit => Regime::Free,
                EventKind::Roll => Regime::Rolling,
                EventKind::Enter | EventKind::Reverse | EventKind::Slip => Regime::Contact,
            };
        }
        stretches.push((from, end, regime));
        let y0 = state_at(&mut p, 0.0);
        let (e0, mut work, mut scale) = (energy(&problem, &y0), 0.0, energy(&problem, &y0).abs());
        for (a, b, regime) in stretches {
            if b <= a {
                continue;
            }
            let halves = ((b - a) / 2e-3).ceil().max(1.0) as usize;
            let (count, h) = (2 * halves, (b - a) / (2 * halves) as f64);
            // Σ weight·P with P = P_σ=0 − σ Q: σ, the slip direction, read at the middle (at
            // the ends w may be 0).
            let (mut sum, mut slip_sum, mut sigma) = (0.0, 0.0, 0.0);
            for i in 0..=count {
                let t = if i == count { b } else { a + h * i as f64 };
                let y = state_at(&mut p, t);
                let weight = if i == 0 || i == count { 1.0 } else if i % 2 == 1 { 4.0 } else { 2.0 };
                sum += weight * power(&problem, &ring, regime, 0.0, t, &y);
                slip_sum += weight * (power(&problem, &ring, regime, 1.0, t, &y)
                    - power(&problem, &ring, regime, 0.0, t, &y));
                if i == halves {
                    sigma = ring.friction(t, &y).1.signum();
                }
                scale = scale.max(energy(&problem, &y).abs());
            }
            work += (sum + sigma * slip_sum) * h / 3.0;
        }
        let y_end = state_at(&mut propagator(&model, &problem), end);
        let change = energy(&problem, &y_end) - e0;
        prop_assert!(
            (change - work).abs() <= 1e-7 * (1.0 + scale),
            "energy change {change} against work {work} (scale {scale})"
        );
    }
}
