//! Siblings of issue 32 in runs that continue from a state they reached: the analytic method's
//! held speed over the last sliver of a changing-speed piece (`docs/MODEL.md` §14).
//!
//! A ramp over N forcing periods of its mean speed turns the unbalance exactly N times, so the
//! analytic method's phase grid of held steps (32 per period) ends on the piece's end — in
//! floating point up to ~1e-13 before it. The held step from there to the piece's end had its
//! speed from a phase difference that cancels: η_h = (θ(t1) − θ(t0))/(t1 − t0) came out 0
//! ("invalid problem: speed_ratio = 0") or far from the piece's speed. Now a grid point within
//! a sliver of the piece's end ends the held step at the piece's end instead, and a held speed
//! over an interval too short to resolve its phase difference is the piece's mean speed there.

use rotor_rub::speed::{HeldSpeed, Ramp, RampPace, SpeedPoint, SpeedProfile};
use rotor_rub::variable_speed::{VariableSpeedOptions, VariableSpeedPropagator};
use rotor_rub::{Method, Options, Preset, Propagate};

/// The ramps of the example (`runup --from 1.6 --to 0.8 --ramp-periods 150 --one-way
/// --settle 0`) and more: up and down, short and long, starting at τ = 0 and later.
fn ramps() -> Vec<Ramp> {
    let mut out = Vec::new();
    for (from, to, periods, start_time) in [
        (1.6, 0.8, 150.0, 0.0),
        (0.8, 1.6, 150.0, 0.0),
        (1.6, 0.8, 37.0, 0.0),
        (0.5, 3.5, 11.0, 0.0),
        (3.5, 0.5, 3.0, 1234.5),
        (1.05, 0.95, 7.0, 1e5),
    ] {
        out.push(Ramp {
            start_time,
            from,
            to,
            pace: RampPace::Periods(periods),
            settle_periods: 0.0,
            dwell_periods: 0.0,
            one_way: true,
        });
    }
    out
}

/// The analytic method runs every ramp to its end and beyond (before: "speed_ratio = 0" at the
/// end of the ramp), every held step's speed within the ramp's speeds.
#[test]
fn held_speeds_run_to_the_end_of_every_ramp() {
    for ramp in ramps() {
        let points = ramp.points().unwrap();
        let profile = points.profile().unwrap();
        let mut problem = Preset::Paper.problem();
        problem.start_time = ramp.start_time;
        problem.params.speed_ratio = ramp.from;
        let options = VariableSpeedOptions::new(Options::with_method(Method::Analytic));
        let mut p = VariableSpeedPropagator::new(&problem, profile, &options).unwrap();
        let end = profile.end();
        for target in [end, end + 1.0] {
            loop {
                match p.advance(target) {
                    Ok(Some(_)) => continue,
                    Ok(None) => break,
                    Err(e) => panic!("{ramp:?}: failed at τ = {}: {e}", p.time()),
                }
            }
            assert_eq!(p.time(), target, "{ramp:?}");
        }
    }
}

/// The held speed over an interval too short for its phase difference (a few ulps of the phase)
/// is the speed there, not the cancelled difference over the length.
#[test]
fn a_held_speed_over_a_sliver_is_the_speed_there() {
    let points = [SpeedPoint::new(0.0, 1.6), SpeedPoint::new(600.0, 0.8)];
    let profile = SpeedProfile::new(&points).unwrap();
    let piece = profile.first_piece(0.3);
    for t0 in [100.0f64, 599.9999999999, 600.0 - 1e-12] {
        for length in [1e-13, 1e-12, 1e-10, 1e-6] {
            let t1 = (t0 + length).min(piece.end);
            if t1 <= t0 {
                continue;
            }
            let held = HeldSpeed::between((&piece, t0), (&piece, t1));
            let want = 0.5 * (piece.speed_at(t0) + piece.speed_at(t1));
            assert!(
                (held.speed_ratio - want).abs() <= 1e-6 * want,
                "[{t0}, {t1}]: held {} vs {want}",
                held.speed_ratio
            );
            assert!((held.rate - piece.rate).abs() <= 1e-6 * piece.rate.abs());
        }
    }
}
