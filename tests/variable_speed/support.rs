//! Helpers of the variable-speed tests: runs on a ramp, revolutions, state comparisons.

use rotor_rub::speed::{Ramp, RampPace, SpeedPoint, SpeedProfile};
use rotor_rub::variable_speed::{
    Revolution, Revolutions, VariableSpeedOptions, VariableSpeedPropagator,
};
use rotor_rub::{Options, Problem, State};

/// A ramp from `from` to `to` at `rate` starting at τ = 0, one way or there and back.
pub fn ramp(from: f64, to: f64, rate: f64, settle: f64, one_way: bool) -> Ramp {
    Ramp {
        start_time: 0.0,
        from,
        to,
        pace: RampPace::Rate(rate),
        settle_periods: settle,
        dwell_periods: 0.0,
        one_way,
    }
}

/// The revolutions of `problem` on `profile` with `options` (64 samples per revolution).
pub fn revolutions(
    problem: &Problem,
    profile: SpeedProfile<'_>,
    options: &VariableSpeedOptions,
) -> Vec<Revolution> {
    let mut p = VariableSpeedPropagator::new(problem, profile, options).unwrap();
    Revolutions::new(&mut p, profile, problem.params.phase, 64)
        .collect::<Result<_, _>>()
        .unwrap()
}

/// Options for `method` at `tol`.
pub fn options(options: Options, tol: Option<f64>) -> VariableSpeedOptions {
    VariableSpeedOptions::new(Options { tol, ..options })
}

/// The states of a run on `profile` at `times`.
pub fn states_at(
    problem: &Problem,
    profile: SpeedProfile<'_>,
    options: &VariableSpeedOptions,
    times: &[f64],
) -> Vec<State> {
    let mut p = VariableSpeedPropagator::new(problem, profile, options).unwrap();
    times
        .iter()
        .map(|&t| rotor_rub::advance_to(&mut p, t, |_| {}).unwrap().state)
        .collect()
}

/// Largest component difference of two states.
pub fn distance(a: &State, b: &State) -> f64 {
    let (a, b) = (a.to_array(), b.to_array());
    (0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// A profile holding `speed` from τ = 0 to `end`.
pub fn constant_points(speed: f64, end: f64) -> [SpeedPoint; 2] {
    [SpeedPoint::new(0.0, speed), SpeedPoint::new(end, speed)]
}
