//! Speed profiles and ramps: bad input is refused with a typed error naming the value and its
//! valid range; the pieces keep the phase θ = ∫η continuous, and the phase is found back in time.

use rotor_rub::speed::{
    Quantity, Ramp, RampError, RampPace, SpeedPoint, SpeedProfile, SpeedProfileError,
};
use rotor_rub::variable_speed::{
    VariableSpeedError, VariableSpeedOptions, VariableSpeedPropagator,
};
use rotor_rub::{Method, Options, Preset, Problem};

use super::support::ramp;

fn p(time: f64, speed: f64) -> SpeedPoint {
    SpeedPoint::new(time, speed)
}

#[test]
fn bad_profiles_are_refused_naming_the_point_and_the_range() {
    let cases: Vec<(Vec<SpeedPoint>, SpeedProfileError, &str)> = vec![
        (
            vec![p(0.0, 1.0)],
            SpeedProfileError::TooFewPoints { count: 1 },
            "at least 2",
        ),
        (
            vec![p(0.0, 1.0), p(f64::NAN, 1.0)],
            SpeedProfileError::NonFinite {
                index: 1,
                quantity: Quantity::Time,
                value: f64::NAN,
            },
            "time = NaN",
        ),
        (
            vec![p(0.0, 1.0), p(1.0, f64::INFINITY)],
            SpeedProfileError::NonFinite {
                index: 1,
                quantity: Quantity::SpeedRatio,
                value: f64::INFINITY,
            },
            "speed_ratio = inf",
        ),
        (
            vec![p(0.0, 1.0), p(5.0, 1e-4)],
            SpeedProfileError::OutOfRange {
                index: 1,
                quantity: Quantity::SpeedRatio,
                value: 1e-4,
                range: rotor_rub::speed::speed_range(),
            },
            "speed_ratio = 1e-4 is out of range: it must be in [0.001, 100]",
        ),
        (
            vec![p(0.0, 1.0), p(2e6, 1.0)],
            SpeedProfileError::OutOfRange {
                index: 1,
                quantity: Quantity::Time,
                value: 2e6,
                range: rotor_rub::speed::time_range(),
            },
            "time = 2e6 is out of range: it must be in [-1e6, 1e6]",
        ),
        (
            vec![p(0.0, 1.0), p(3.0, 1.2), p(3.0, 1.4)],
            SpeedProfileError::NotIncreasing {
                index: 2,
                time: 3.0,
                previous: 3.0,
            },
            "times must increase",
        ),
        (
            vec![p(0.0, 1.0), p(3.0, 1.2), p(2.0, 1.4)],
            SpeedProfileError::NotIncreasing {
                index: 2,
                time: 2.0,
                previous: 3.0,
            },
            "time = 2 is not after the previous point's time 3",
        ),
        (
            vec![p(0.0, 1.0), p(1.0, 3.0)],
            SpeedProfileError::RateTooHigh {
                index: 0,
                rate: 2.0,
            },
            "dη/dτ = 2 up to the next point: |dη/dτ| must be at most 1",
        ),
    ];
    for (points, expected, text) in cases {
        let e = SpeedProfile::new(&points).unwrap_err();
        match (e, expected) {
            // NaN != NaN: compare the rest.
            (
                SpeedProfileError::NonFinite {
                    index,
                    quantity,
                    value,
                },
                SpeedProfileError::NonFinite {
                    index: i,
                    quantity: q,
                    value: v,
                },
            ) => {
                assert!(index == i && quantity == q && (value.is_nan() && v.is_nan() || value == v))
            }
            (e, expected) => assert_eq!(e, expected),
        }
        assert!(e.to_string().contains(text), "{e} lacks {text:?}");
    }
}

#[test]
fn bad_ramps_are_refused_naming_the_value_and_the_range() {
    let ok = ramp(0.5, 2.0, 1e-3, 0.0, false);
    assert!(ok.points().is_ok());
    let cases: Vec<(Ramp, &str)> = vec![
        (
            Ramp { from: 0.0, ..ok },
            "from = 0 is out of range: it must be in [0.001, 100]",
        ),
        (Ramp { to: f64::NAN, ..ok }, "to = NaN is out of range"),
        (Ramp { to: 0.5, ..ok }, "same speed ratio 0.5"),
        (
            Ramp {
                pace: RampPace::Rate(0.0),
                ..ok
            },
            "dη/dτ = 0 is out of range: it must be in (0, 1]",
        ),
        (
            Ramp {
                pace: RampPace::Rate(-1e-3),
                ..ok
            },
            "dη/dτ = -0.001 is out of range",
        ),
        (
            Ramp {
                pace: RampPace::Rate(f64::NAN),
                ..ok
            },
            "dη/dτ = NaN",
        ),
        (
            Ramp {
                pace: RampPace::Rate(3.0),
                ..ok
            },
            "dη/dτ = 3 is out of range: it must be in (0, 1]",
        ),
        (
            Ramp {
                pace: RampPace::Periods(0.1),
                ..ok
            },
            "a ramp over 0.1 periods changes the speed at",
        ),
        (
            Ramp {
                pace: RampPace::Periods(-5.0),
                ..ok
            },
            "periods = -5 forcing periods is out of range",
        ),
        (
            Ramp {
                settle_periods: -1.0,
                ..ok
            },
            "settle = -1 forcing periods is out of range: it must be in [0, 1e7]",
        ),
        (
            Ramp {
                dwell_periods: f64::INFINITY,
                ..ok
            },
            "dwell = inf forcing periods",
        ),
        (
            Ramp {
                pace: RampPace::Rate(1e-9),
                ..ok
            },
            "would end at τ = 3e9, past the valid times [-1e6, 1e6]",
        ),
    ];
    for (ramp, text) in cases {
        let e: RampError = ramp.points().unwrap_err();
        assert!(e.to_string().contains(text), "{e} lacks {text:?}");
    }
}

#[test]
fn a_ramp_over_n_periods_turns_the_unbalance_n_times() {
    for (from, to, n) in [(0.5, 2.0, 300.0), (3.0, 1.0, 40.0), (0.9, 1.1, 7.0)] {
        let r = Ramp {
            pace: RampPace::Periods(n),
            ..ramp(from, to, 1.0, 0.0, true)
        };
        let points = r.points().unwrap();
        let profile = points.profile().unwrap();
        let first = profile.first_piece(0.0);
        let turns = (first.phase_at(profile.end()) - first.phase_at(0.0)) / std::f64::consts::TAU;
        assert!((turns - n).abs() < 1e-9 * n, "{turns} turns for {n}");
    }
}

#[test]
fn the_phase_is_continuous_and_found_back_in_time() {
    let points = [
        p(0.0, 0.5),
        p(40.0, 0.5),
        p(1540.0, 2.0),
        p(1600.0, 2.0),
        p(3100.0, 0.5),
    ];
    let profile = SpeedProfile::new(&points).unwrap();
    let mut piece = profile.first_piece(0.3);
    let mut pieces = vec![piece];
    while let Some(next) = profile.next_piece(&piece) {
        let jump = next.phase_at(next.start) - piece.phase_at(piece.end);
        assert!(
            jump.abs() < 1e-12 * next.start.max(1.0),
            "phase jumps by {jump} at {}",
            next.start
        );
        assert!((next.speed_at(next.start) - piece.speed_at(piece.end)).abs() < 1e-12);
        piece = next;
        pieces.push(next);
    }
    // Held speeds are single pieces; the last (held at 0.5 after 3100) has no end.
    assert_eq!(pieces.len(), 5);
    assert!(pieces.last().unwrap().end.is_infinite());
    for t in [0.0, 17.0, 40.0, 900.0, 1570.0, 3000.0, 5000.0] {
        let piece = profile.piece_holding(profile.first_piece(0.3), t);
        let theta = piece.phase_at(t);
        let back = piece.time_of_phase(theta).unwrap();
        assert!((back - t).abs() < 1e-9 * t.max(1.0), "{t} -> {back}");
        // dθ/dτ = η.
        let h = 1e-5;
        let rate = (piece.phase_at(t + h) - piece.phase_at(t - h)) / (2.0 * h);
        assert!(
            (rate - piece.speed_at(t)).abs() < 1e-6,
            "{rate} vs {}",
            piece.speed_at(t)
        );
    }
}

#[test]
fn runs_that_cannot_start_say_why() {
    let points = ramp(0.5, 2.0, 1e-3, 0.0, true).points().unwrap();
    let profile = points.profile().unwrap();
    let options = VariableSpeedOptions::new(Options::with_method(Method::Hybrid));
    let start = |problem: &Problem, options: &VariableSpeedOptions| {
        VariableSpeedPropagator::new(problem, profile, options)
            .err()
            .unwrap()
    };
    let friction = Preset::Friction.problem();
    let e = start(&friction, &options);
    assert!(matches!(e, VariableSpeedError::Friction { .. }));
    assert!(e.to_string().contains("friction_coefficient = 0.2"), "{e}");
    let late = Problem {
        start_time: 5.0,
        ..Preset::Paper.problem()
    };
    let e = start(&late, &options);
    assert!(
        e.to_string().contains("τ0 = 5") && e.to_string().contains("τ = 0"),
        "{e}"
    );
    let holds = VariableSpeedOptions {
        speed_holds: 0,
        ..options
    };
    let e = start(&Preset::Paper.problem(), &holds);
    assert!(
        e.to_string().contains("speed_holds = 0e0 is out of range"),
        "{e}"
    );
    // Very low speed, fast change: the analytic method's held unbalance leaves its range.
    let steep = [p(0.0, 2e-3), p(1.0, 0.5)];
    let steep = SpeedProfile::new(&steep).unwrap();
    let analytic = VariableSpeedOptions::new(Options::with_method(Method::Analytic));
    let e = VariableSpeedPropagator::new(&Preset::Paper.problem(), steep, &analytic)
        .err()
        .unwrap();
    assert!(matches!(e, VariableSpeedError::HeldUnbalance { .. }), "{e}");
    assert!(e.to_string().contains("eccentricity_ratio"), "{e}");
    // The numerical methods take it.
    assert!(VariableSpeedPropagator::new(&Preset::Paper.problem(), steep, &options).is_ok());
}
