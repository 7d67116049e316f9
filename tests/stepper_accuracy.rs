//! The stepper's accuracy with its default fourth-order contact step (exprb43) at dt = 1e-3 over
//! 10 forcing periods against DOP853 at tol 1e-12 (issue 31 item 2): the largest state error at
//! the step ends, and the switch times, on the paper preset and on the friction cases (slip
//! reversal, rolling, dry whip). The bounds are the errors measured before the exit and entry
//! searches moved to the pieces' Taylor polynomials (`runtime/stepper/polynomial.rs`), with a
//! margin of about 1.5 for the reference's own error: the new searches must not lose accuracy.

use rotor_rub::{
    Event, Method, Options, Preset, Problem, Propagator, State, Stepper, StepperConfig, advance_to,
};

const DT: f64 = 1e-3;

/// The DOP853 (tol 1e-12) states at the step ends k·dt, and its switches, over `steps` steps.
fn reference(problem: &Problem, steps: usize) -> (Vec<State>, Vec<Event>) {
    let options = Options {
        tol: Some(1e-12),
        ..Options::with_method(Method::Dop853)
    };
    let mut p = Propagator::new(problem, &options).unwrap();
    let mut events = Vec::new();
    let states = (1..=steps)
        .map(|k| {
            advance_to(&mut p, problem.start_time + k as f64 * DT, |e| {
                events.push(*e)
            })
            .unwrap()
            .state
        })
        .collect();
    (states, events)
}

/// The largest state error at the step ends and the largest switch-time difference of the
/// default stepper at dt = 1e-3 over 10 forcing periods.
fn errors(problem: &Problem) -> (f64, f64, usize) {
    let steps = (10.0 * problem.params.forcing_period() / DT) as usize;
    let (want, want_events) = reference(problem, steps);
    let mut stepper = Stepper::new(problem, StepperConfig::with_dt(DT)).unwrap();
    let mut state_error: f64 = 0.0;
    let mut events = Vec::new();
    for w in &want {
        let r = stepper.step(DT).unwrap();
        assert!(!r.capped && !r.search_capped, "a cap at {}", r.time);
        events.extend(r.events.iter().copied());
        let (a, b) = (r.state.to_array(), w.to_array());
        for (x, y) in a.iter().zip(&b) {
            state_error = state_error.max((x - y).abs());
        }
    }
    let kinds = |e: &[Event]| e.iter().map(|e| e.kind.name()).collect::<Vec<_>>();
    assert_eq!(kinds(&events), kinds(&want_events), "switch kinds");
    let time_error = events
        .iter()
        .zip(&want_events)
        .map(|(a, b)| (a.time - b.time).abs())
        .fold(0.0, f64::max);
    (state_error, time_error, events.len())
}

fn check(name: &str, problem: &Problem, state_bound: f64, time_bound: f64) {
    let (state, time, n) = errors(problem);
    eprintln!("{name:14}: {n} switches, state error {state:.2e}, switch times {time:.2e}");
    assert!(n > 0, "{name}: no switch to test");
    assert!(
        state <= state_bound,
        "{name}: state error {state:e} > {state_bound:e}"
    );
    assert!(
        time <= time_bound,
        "{name}: switch time error {time:e} > {time_bound:e}"
    );
}

/// The paper preset: 2.0e-10 before (`BENCHMARKS.md`, "Embedded stepper").
#[test]
fn paper_preset_at_fourth_order_within_today_s_accuracy() {
    // Measured: 1.46e-10 in the state, 1.64e-11 in switch times before; 1.54e-10, 1.66e-11 now.
    check("paper", &Preset::Paper.problem(), 3e-10, 2.5e-11);
}

/// Friction: slip reversal, rolling (as in `tests/friction_stepper.rs`) and the dry-whip preset.
#[test]
fn friction_cases_at_fourth_order_within_today_s_accuracy() {
    let mut reversal = Preset::Paper.problem();
    reversal.params.speed_ratio = 2.0;
    reversal.params.friction_coefficient = 0.2;
    reversal.params.radius_ratio = 1.0;
    let mut rolling = Preset::Paper.problem();
    let p = &mut rolling.params;
    (p.k_xx, p.k_xy, p.k_yx, p.k_yy) = (100.0, 0.0, 0.0, 100.0);
    p.friction_coefficient = 0.6;
    p.radius_ratio = 0.5;
    // Measured before (state, switch times): reversal 1.62e-10, 1.19e-11; rolling 6.62e-11,
    // 3.99e-12; dry whip 3.65e-10, 1.84e-11. Now: 1.62e-10, 1.18e-11; 6.85e-11, 4.15e-12;
    // 3.66e-10, 1.85e-11.
    for (name, problem, state_bound, time_bound) in [
        ("slip reversal", reversal, 2.5e-10, 1.8e-11),
        ("rolling", rolling, 1e-10, 6e-12),
        ("dry whip", Preset::DryWhip.problem(), 5.5e-10, 2.8e-11),
    ] {
        check(name, &problem, state_bound, time_bound);
    }
}
