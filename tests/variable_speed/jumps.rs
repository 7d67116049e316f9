//! The run-up of the paper's rotor with rub jumps off its upper branch, and the coast-down does
//! not come back on it: the jump speed is the same for every method, and the hysteresis loop is
//! there.

use rotor_rub::variable_speed::{JumpSearch, Revolution, SpeedDirection, find_jumps};
use rotor_rub::{Method, Options, Preset};

use super::support::{options, ramp, revolutions};

fn one_way(revs: &[Revolution], direction: SpeedDirection) -> Vec<Revolution> {
    revs.iter()
        .copied()
        .filter(|r| r.direction() == direction)
        .collect()
}

#[test]
fn the_run_up_jump_is_found_at_one_speed_by_every_method() {
    let problem = Preset::Paper.problem();
    let points = ramp(0.5, 3.5, 2e-3, 20.0, false).points().unwrap();
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
        let up = one_way(&revs, SpeedDirection::Up);
        let jump = find_jumps(&up, &JumpSearch::default()).largest().unwrap();
        eprintln!(
            "{}: run-up jump at η = {:.4} ({:.3} -> {:.3})",
            method.name(),
            jump.speed_ratio,
            jump.before,
            jump.after
        );
        // Off the upper branch (above 2.5 clearances) down to the lower rub (about 1.5).
        assert!(jump.before - jump.after > 1.0, "{jump:?}");
        speeds.push(jump.speed_ratio);
        // The hysteresis loop: at η = 2.0 … 2.4 the run-up rides the upper branch, the
        // coast-down the lower one.
        let down = one_way(&revs, SpeedDirection::Down);
        for speed in [2.0, 2.2, 2.4] {
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
    let spread = speeds.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
        - speeds.iter().fold(f64::INFINITY, |a, &b| a.min(b));
    // Measured: every method finds η = 2.5013 (spread 0). Allowed: two revolutions' change of
    // speed, 2 · 2e-3 · 2π/2.5 = 0.01.
    assert!(spread <= JUMP_SPEED_TOLERANCE, "jump speeds {speeds:?}");
}

/// How far the methods' run-up jump speeds may be apart.
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
