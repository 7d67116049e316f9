//! The run-up of the paper's rotor with rub jumps off its rub branch, and the coast-down comes
//! back on it only at a lower speed: both jump speeds are the same for every method, and the
//! hysteresis loop is there. A smooth resonance is not taken for a jump.

use rotor_rub::speed::RunupPreset;
use rotor_rub::variable_speed::{Jump, JumpSearch, Revolution, SpeedDirection, find_jumps};
use rotor_rub::{Method, Options, Preset};

use super::support::{options, ramp, revolutions};

fn one_way(revs: &[Revolution], direction: SpeedDirection) -> Vec<Revolution> {
    revs.iter()
        .copied()
        .filter(|r| r.direction() == direction)
        .collect()
}

/// The largest jump of a branch in the given sense (down: the radius falls).
fn jump(revs: &[Revolution], direction: SpeedDirection, falls: bool) -> Jump {
    let part = one_way(revs, direction);
    let jumps = find_jumps(&part, &JumpSearch::default());
    jumps
        .as_slice()
        .iter()
        .copied()
        .filter(|j| (j.after < j.before) == falls)
        .max_by(|a, b| {
            (a.after - a.before)
                .abs()
                .total_cmp(&(b.after - b.before).abs())
        })
        .unwrap_or_else(|| panic!("{direction:?}: no jump in {jumps:?}"))
}

/// The `paper-hysteresis` program (η 0.5 → 3.5 → 0.5 at dη/dτ = 1e-3): the run-up falls off
/// the rub branch near η = 2.47, the coast-down climbs back on near 1.40, and every method puts
/// both jumps at one speed. Measured: dop853 (tol 1e-10 and 1e-13), hybrid, analytic and rk45
/// all find η = 2.4736 and 1.4035 (spread 0).
#[test]
fn the_jumps_are_found_at_one_speed_by_every_method() {
    let preset = RunupPreset::PaperHysteresis;
    let problem = preset.rotor().problem();
    let points = preset.ramp().points().unwrap();
    let profile = points.profile().unwrap();
    let mut speeds = Vec::new();
    for (method, tol) in [
        (Method::Dop853, Some(1e-10)),
        (Method::Hybrid, None),
        (Method::Analytic, None),
        (Method::Rk45, Some(1e-10)),
    ] {
        let revs = revolutions(
            &problem,
            profile,
            &options(Options::with_method(method), tol),
        );
        let fall = jump(&revs, SpeedDirection::Up, true);
        let rise = jump(&revs, SpeedDirection::Down, false);
        eprintln!(
            "{}: run-up falls at η = {:.4} ({:.3} -> {:.3}), coast-down rises at η = {:.4} ({:.3} -> {:.3})",
            method.name(),
            fall.speed_ratio,
            fall.before,
            fall.after,
            rise.speed_ratio,
            rise.before,
            rise.after
        );
        // Off the rub branch (above 3 clearances) to the free orbit (below 1), and back.
        assert!(fall.before > 3.0 && fall.after < 1.0, "{fall:?}");
        assert!(rise.before < 1.0 && rise.after > 1.5, "{rise:?}");
        speeds.push((fall.speed_ratio, rise.speed_ratio));
        // The hysteresis loop: between the jumps the run-up rides the rub branch, the
        // coast-down the free orbit.
        let up = one_way(&revs, SpeedDirection::Up);
        let down = one_way(&revs, SpeedDirection::Down);
        for speed in [1.6, 2.0, 2.4] {
            let near = |rs: &[Revolution]| {
                rs.iter()
                    .min_by(|a, b| {
                        (a.speed_ratio - speed)
                            .abs()
                            .total_cmp(&(b.speed_ratio - speed).abs())
                    })
                    .unwrap()
                    .max_radius
            };
            assert!(near(&up) > near(&down) + 1.0, "η = {speed}");
        }
    }
    for (k, name) in [(0, "run-up"), (1, "coast-down")] {
        let of = |s: &(f64, f64)| if k == 0 { s.0 } else { s.1 };
        let spread = speeds.iter().map(of).fold(f64::NEG_INFINITY, f64::max)
            - speeds.iter().map(of).fold(f64::INFINITY, f64::min);
        // Allowed: two forcing periods' change of speed, 2 · 1e-3 · 2π/1.4 ≈ 0.01.
        assert!(
            spread <= JUMP_SPEED_TOLERANCE,
            "{name} jump speeds {speeds:?}"
        );
    }
}

/// How far the methods' jump speeds may be apart.
const JUMP_SPEED_TOLERANCE: f64 = 0.01;

#[test]
fn a_smooth_resonance_is_not_a_jump() {
    let mut problem = Preset::Paper.problem();
    problem.params.mass_ratio = 5e-4;
    let points = ramp(0.6, 1.6, 1e-3, 20.0, false).points().unwrap();
    let profile = points.profile().unwrap();
    let revs = revolutions(
        &problem,
        profile,
        &options(Options::with_method(Method::Hybrid), None),
    );
    for direction in [SpeedDirection::Up, SpeedDirection::Down] {
        let part = one_way(&revs, direction);
        assert!(part.len() > 100);
        let jumps = find_jumps(&part, &JumpSearch::default());
        assert!(jumps.as_slice().is_empty(), "{direction:?}: {jumps:?}");
    }
}
