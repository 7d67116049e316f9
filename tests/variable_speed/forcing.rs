//! The speed-change force is the unbalance's reaction: the unbalance sits at η_m ρ̂ (cos θ, sin θ)
//! from the rotor centre and pulls on it with minus its acceleration. Checked here by central
//! differences of that position along θ(τ) = θ0 + η0 s + ½ η' s², independently of the
//! generated formulas: the field on a ramp piece (generated forcing + speed-change force) and
//! the held forcing A (cos(θ − δ), sin(θ − δ)).

use rotor_rub::coefficients::{self as coef, ModelParams, Phasor, SpeedChange};
use rotor_rub::field::{self, Field};
use rotor_rub::reference::OdeSystem;
use rotor_rub::speed::{HeldSpeed, SpeedPiece};
use rotor_rub::variable_speed::RampSystem;
use rotor_rub::{Params, Preset, Regime, State};

/// −η_m ρ̂ d²/dτ² (cos θ, sin θ) at τ by fourth-order central differences (step 1e-3:
/// truncation ~1e-12, rounding of θ ≈ 30 rad ~1e-9).
fn reaction(params: &Params, piece: &SpeedPiece, tau: f64) -> (f64, f64) {
    let unbalance = params.mass_ratio * params.eccentricity_ratio;
    let h = 1e-3;
    let pos = |k: f64| {
        let theta = piece.phase_at(tau + k * h);
        (unbalance * theta.cos(), unbalance * theta.sin())
    };
    let second = |f: &dyn Fn(f64) -> f64| {
        (-f(2.0) + 16.0 * f(1.0) - 30.0 * f(0.0) + 16.0 * f(-1.0) - f(-2.0)) / (12.0 * h * h)
    };
    (-second(&|k| pos(k).0), -second(&|k| pos(k).1))
}

fn piece(rate: f64) -> SpeedPiece {
    SpeedPiece {
        index: 0,
        end_index: 1,
        start: 3.0,
        end: 50.0,
        speed_ratio: 1.3,
        rate,
        phase_constant: 0.4,
    }
}

#[test]
fn the_field_on_a_ramp_carries_the_unbalance_reaction() {
    let params = Preset::Paper.problem().params;
    // The speed stays positive over the times checked (1.3 − 0.05·17 = 0.45 at τ = 20).
    for rate in [-0.05, -1e-3, 0.0, 1e-3, 0.3] {
        let piece = piece(rate);
        for tau in [3.0, 7.5, 20.0] {
            // Free flight at rest at the origin: the acceleration is the forcing alone.
            let system = RampSystem {
                params,
                regime: Regime::Free,
                slip: 0.0,
                piece,
            };
            let [_, _, ax, ay] = system.rhs(tau, &[0.0; 4]);
            let (fx, fy) = reaction(&params, &piece, tau);
            let scale = params.mass_ratio * params.eccentricity_ratio * 4.0;
            assert!(
                (ax - fx).abs() < 1e-8 * scale && (ay - fy).abs() < 1e-8 * scale,
                "rate {rate} τ {tau}: field ({ax}, {ay}), reaction ({fx}, {fy})"
            );
            // The sign matters: speeding up, the force has a component against the spin.
            let (s, c) = piece.phase_at(tau).sin_cos();
            let tangential = -s * ax + c * ay;
            let expected = -params.mass_ratio * params.eccentricity_ratio * rate;
            assert!(
                (tangential - expected).abs() < 1e-12,
                "{tangential} vs {expected}"
            );
        }
    }
}

#[test]
fn the_field_in_contact_adds_the_same_force_to_the_constant_speed_field() {
    let params = Preset::Paper.problem().params;
    let piece = piece(0.05);
    let state = State::new(1.1, -0.4, 0.3, 0.8);
    let tau = 9.0;
    let system = RampSystem {
        params,
        regime: Regime::Contact,
        slip: 0.0,
        piece,
    };
    let [_, _, ax, ay] = system.rhs(tau, &state.to_array());
    let at_speed = Params {
        speed_ratio: piece.speed_at(tau),
        ..params
    };
    let theta = piece.phase_at(tau);
    let (bx, by) = field::acceleration(
        &ModelParams::of(&at_speed),
        Field::Contact,
        &Phasor {
            ct: theta.cos(),
            st: theta.sin(),
        },
        &state,
    );
    let unbalance = params.mass_ratio * params.eccentricity_ratio;
    // The η' part by hand: −η_m ρ̂ η' (−sin θ, cos θ).
    let (ex, ey) = (
        unbalance * piece.rate * theta.sin(),
        -unbalance * piece.rate * theta.cos(),
    );
    assert!((ax - bx - ex).abs() < 1e-15 && (ay - by - ey).abs() < 1e-15);
}

#[test]
fn a_held_step_is_one_harmonic_with_the_held_rate() {
    let params = Preset::Paper.problem().params;
    let unbalance = params.mass_ratio * params.eccentricity_ratio;
    for (speed, rate) in [(1.3, 0.0), (1.3, 0.01), (0.2, -0.05), (2.0, 0.5)] {
        let held = HeldSpeed {
            speed_ratio: speed,
            rate,
            phase_constant: 0.25,
        };
        let equivalent = held.params(&params);
        for tau in [0.0, 1.0, 4.2] {
            // The held forcing as the constant-speed model sees it: F (cos θ', sin θ').
            let f = equivalent.mass_ratio
                * equivalent.eccentricity_ratio
                * equivalent.speed_ratio
                * equivalent.speed_ratio;
            let phase = equivalent.speed_ratio * tau + equivalent.phase;
            let (gx, gy) = (f * phase.cos(), f * phase.sin());
            // The varying-speed unbalance with η, η' frozen, by hand.
            let theta = speed * tau + 0.25;
            let hx = unbalance * (speed * speed * theta.cos() + rate * theta.sin());
            let hy = unbalance * (speed * speed * theta.sin() - rate * theta.cos());
            assert!(
                (gx - hx).abs() < 1e-12 && (gy - hy).abs() < 1e-12,
                "η {speed} η' {rate}: ({gx}, {gy}) vs ({hx}, {hy})"
            );
            // The generated whole forcing agrees too.
            let g = coef::varying_speed_unbalance(
                &ModelParams::of(&Params {
                    speed_ratio: speed,
                    ..params
                }),
                &coef::Phasor {
                    ct: theta.cos(),
                    st: theta.sin(),
                },
                &SpeedChange { speed_rate: rate },
            );
            assert!((g.fx - hx).abs() < 1e-12 && (g.fy - hy).abs() < 1e-12);
        }
    }
}
