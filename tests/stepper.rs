//! The fixed-step stepper against the event-driven propagators: switch times, states at step
//! ends, every switch inside a step reported, event-list overflow, caps, parameter and step
//! changes between steps, typed errors, and no panic on random problems.

use proptest::prelude::*;
use rotor_rub::stepper::{EVENT_CAPACITY, MAX_STEP};
use rotor_rub::{
    ContactScheme, Event, EventKind, Options, ParamError, Parameter, Params, Preset, Problem,
    Propagate, PropagationError, Propagator, Regime, State, Stepper, StepperConfig, StepperError,
    advance_to,
};

/// The analytic propagator at tol 1e-11 (switch times within ~1e-10 over 20 periods).
fn tight(problem: &Problem) -> Propagator {
    let options = Options {
        tol: Some(1e-11),
        ..Options::default()
    };
    Propagator::new(problem, &options).expect("valid problem")
}

fn max_abs_diff(a: State, b: State) -> f64 {
    let (a, b) = (a.to_array(), b.to_array());
    (0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// Runs `steps` steps of `dt`, checking each step's events against `reference` advanced to the
/// step end; returns the worst switch-time and step-end state differences.
fn compare(stepper: &mut Stepper, reference: &mut Propagator, dt: f64, steps: usize) -> (f64, f64) {
    let (mut worst_time, mut worst_state) = (0.0f64, 0.0f64);
    for _ in 0..steps {
        let t0 = stepper.time();
        let r = stepper.step(dt).expect("step");
        let mut expected = Vec::new();
        let sample = advance_to(reference, r.time, |e| expected.push(*e)).expect("reference");
        assert_eq!(r.events.dropped(), 0);
        assert_eq!(
            r.events.len(),
            expected.len(),
            "switches in ({t0}, {}]: {:?} vs {expected:?}",
            r.time,
            r.events.as_slice()
        );
        for (e, x) in r.events.iter().zip(&expected) {
            assert_eq!(e.kind, x.kind);
            assert!(e.time > t0 && e.time <= r.time, "event outside its step");
            worst_time = worst_time.max((e.time - x.time).abs());
        }
        assert_eq!(r.regime, sample.regime, "regime at {}", r.time);
        worst_state = worst_state.max(max_abs_diff(r.state, sample.state));
    }
    (worst_time, worst_state)
}

#[test]
fn paper_preset_agrees_with_the_event_driven_analytic_method() {
    let problem = Preset::Paper.problem();
    let end = 20.0 * problem.params.forcing_period();
    // dt = 1e-3: exprb43 sub-steps of 1e-3 (local error ~1e-16) and exact free flight: the
    // stepper is as accurate as the tight reference (measured ~1e-10 over 20 periods).
    // dt = 1e-2: local error ~1e-12 per sub-step (measured: switch times 5.3e-7, states
    // 2.9e-6 after chaotic growth over 20 periods; the bounds leave a factor 10).
    for (dt, tol_time, tol_state) in [(1e-3, 1e-8, 1e-8), (1e-2, 1e-5, 3e-5)] {
        let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(dt)).unwrap();
        let mut reference = tight(&problem);
        let steps = (end / dt) as usize;
        let (t, s) = compare(&mut stepper, &mut reference, dt, steps);
        assert!(t <= tol_time, "dt {dt}: switch times differ by {t:e}");
        assert!(s <= tol_state, "dt {dt}: step-end states differ by {s:e}");
    }
}

#[test]
fn every_switch_inside_long_steps_is_reported() {
    // Steps of 0.25 hold up to three switches; sub-steps stay 2.5e-3 long.
    let problem = Preset::Paper.problem();
    let config = StepperConfig {
        dt: 0.25,
        contact_substeps: 100,
        max_substeps: 400,
        ..StepperConfig::default()
    };
    let mut stepper = Stepper::new(&problem, config).unwrap();
    let mut reference = tight(&problem);
    let (t, s) = compare(&mut stepper, &mut reference, 0.25, 80);
    assert!(t <= 1e-7 && s <= 1e-7, "switch {t:e}, state {s:e}");
}

/// A fast rotor (η = 20) whorling on its synchronous orbit (radius ≈ 0.35) around a stator
/// offset by 0.8: it touches the stator once per revolution, ≈ 6 switches per time unit.
fn fast_rubbing() -> Problem {
    let params = Params {
        speed_ratio: 20.0,
        offset_x: 0.8,
        offset_y: 0.0,
        ..Preset::Paper.problem().params
    };
    Problem {
        params,
        initial: State::new(-0.351, 0.0, 0.0, -7.02),
        start_time: 0.0,
    }
}

#[test]
fn event_list_overflow_is_reported_not_silent() {
    let problem = fast_rubbing();
    let config = StepperConfig {
        dt: MAX_STEP,
        contact_substeps: 400,
        max_substeps: 1024,
        ..StepperConfig::default()
    };
    let mut stepper = Stepper::new(&problem, config).unwrap();
    let r = stepper.step(MAX_STEP).unwrap();
    let mut reference = tight(&problem);
    let mut expected: Vec<Event> = Vec::new();
    advance_to(&mut reference, r.time, |e| expected.push(*e)).unwrap();
    assert!(
        expected.len() > EVENT_CAPACITY,
        "{} switches",
        expected.len()
    );
    assert_eq!(r.events.total(), expected.len());
    assert_eq!(r.events.len(), EVENT_CAPACITY);
    assert!(r.events.overflowed());
    assert_eq!(r.events.dropped() as usize, expected.len() - EVENT_CAPACITY);
    for (e, x) in r.events.iter().zip(&expected) {
        assert_eq!(e.kind, x.kind);
        assert!((e.time - x.time).abs() <= 1e-6, "{} vs {}", e.time, x.time);
    }
    assert!(!r.capped);
    assert!(max_abs_diff(r.state, reference.state()) <= 1e-5);
}

#[test]
fn the_substep_cap_is_reported() {
    let problem = fast_rubbing();
    let config = StepperConfig {
        dt: MAX_STEP,
        contact_substeps: 1,
        max_substeps: 1,
        ..StepperConfig::default()
    };
    let mut stepper = Stepper::new(&problem, config).unwrap();
    let r = stepper.step(MAX_STEP).unwrap();
    assert!(r.capped, "one sub-step cannot cover several contacts");
    assert!(r.substeps <= 2);
    assert!(r.state.is_finite());
    let field = rotor_rub::field::regime_of(&problem.params, r.time, &r.state);
    assert_eq!(
        r.regime, field,
        "after a cap the regime is read from the state"
    );
    // The next step starts from a consistent state and goes on.
    stepper.step(0.01).unwrap();
}

#[test]
fn parameter_and_step_changes_between_steps() {
    // A speed ramp η = 1.5 → 2.4 in ten increments, each held 2 time units, with the step length
    // alternating between 1e-3 and 2e-3; the reference is the analytic method restarted from its
    // own state at every change.
    let problem = Preset::Paper.problem();
    let mut stepper = Stepper::new(&problem, StepperConfig::default()).unwrap();
    let mut reference = tight(&problem);
    let mut params = problem.params;
    let (mut worst_time, mut worst_state) = (0.0f64, 0.0f64);
    for k in 0..10 {
        if k > 0 {
            params.speed_ratio = 1.5 + 0.1 * k as f64;
            stepper.set_params(&params).unwrap();
            assert_eq!(stepper.params(), &params);
            let restart = Problem {
                params,
                initial: reference.state(),
                start_time: reference.time(),
            };
            reference = tight(&restart);
        }
        let dt = if k % 2 == 0 { 1e-3 } else { 2e-3 };
        let (t, s) = compare(&mut stepper, &mut reference, dt, (2.0 / dt) as usize);
        assert_eq!(stepper.precomputed_dt(), dt);
        (worst_time, worst_state) = (worst_time.max(t), worst_state.max(s));
    }
    assert!(
        worst_time <= 1e-8 && worst_state <= 1e-8,
        "{worst_time:e} {worst_state:e}"
    );
}

#[test]
fn invalid_inputs_give_typed_errors() {
    let problem = Preset::Paper.problem();
    let mut bad = problem;
    bad.params.speed_ratio = -1.0;
    assert!(matches!(
        Stepper::new(&bad, StepperConfig::default()),
        Err(StepperError::Propagation(PropagationError::InvalidProblem(
            ParamError::OutOfRange {
                parameter: Parameter::SpeedRatio,
                ..
            }
        )))
    ));
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY, 1.5] {
        let r = Stepper::new(&problem, StepperConfig::with_dt(dt));
        assert!(
            matches!(r, Err(StepperError::InvalidStep { .. })),
            "dt {dt}"
        );
    }
    for (substeps, max) in [(0, 8), (4, 2), (2000, 2000)] {
        let config = StepperConfig {
            contact_substeps: substeps,
            max_substeps: max,
            ..StepperConfig::default()
        };
        let r = Stepper::new(&problem, config);
        assert!(matches!(r, Err(StepperError::InvalidConfig { .. })));
    }
    let mut stepper = Stepper::new(&problem, StepperConfig::default()).unwrap();
    stepper.step(1e-3).unwrap();
    let before = (stepper.time(), stepper.state(), *stepper.params());
    for dt in [0.0, -1.0, f64::NAN, 2.0] {
        let e = stepper.step(dt).unwrap_err();
        assert!(matches!(e, StepperError::InvalidStep { .. }));
        assert!(e.to_string().contains("invalid"), "{e}");
    }
    let mut params = problem.params;
    params.damping_ratio = f64::NAN;
    assert!(matches!(
        stepper.set_params(&params),
        Err(StepperError::Propagation(PropagationError::InvalidProblem(
            ParamError::NonFinite { .. }
        )))
    ));
    assert_eq!(before, (stepper.time(), stepper.state(), *stepper.params()));
    // A flutter case diverges with a typed error (docs/MODEL.md §6 case 3).
    let mut flutter = problem;
    (flutter.params.k_xy, flutter.params.k_yx) = (15.0, -10.0);
    flutter.params.offset_x = 0.0;
    flutter.params.offset_y = 0.0;
    flutter.initial = State::new(1.2, 0.0, 0.0, 0.5);
    let mut s = Stepper::new(&flutter, StepperConfig::with_dt(1e-2)).unwrap();
    let err = (0..10_000).find_map(|_| s.step(1e-2).err());
    assert!(
        matches!(
            err,
            Some(StepperError::Propagation(PropagationError::Diverged { .. }))
        ),
        "{err:?}"
    );
}

#[test]
fn exprb2_and_substeps_converge() {
    // Halving the contact sub-step of exprb2 divides the end error by ≈ 4 (second order).
    let problem = Preset::Paper.problem();
    let end = 3.0;
    let mut reference = tight(&problem);
    let exact = advance_to(&mut reference, end, |_| {}).unwrap().state;
    let error = |substeps: u32| {
        let config = StepperConfig {
            dt: 1e-2,
            scheme: ContactScheme::Exprb2,
            contact_substeps: substeps,
            max_substeps: 4 * substeps,
            ..StepperConfig::default()
        };
        let mut s = Stepper::new(&problem, config).unwrap();
        for _ in 0..300 {
            s.step(1e-2).unwrap();
        }
        max_abs_diff(s.state(), exact)
    };
    let (e1, e2) = (error(1), error(2));
    assert!(e1 / e2 > 3.0 && e1 / e2 < 5.5, "{e1:e} / {e2:e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// No panic on random problems; every step either succeeds with a consistent report or
    /// fails with a typed error that leaves the stepper unchanged.
    #[test]
    fn random_problems_never_panic(
        problem in prop_oneof![
            rotor_rub::strategies::problem(),
            rotor_rub::strategies::degenerate_problem()
        ],
        dt in 1e-3f64..0.5,
        substeps in 1u32..4,
        exprb2 in any::<bool>(),
    ) {
        let config = StepperConfig {
            dt,
            scheme: if exprb2 { ContactScheme::Exprb2 } else { ContactScheme::Exprb43 },
            contact_substeps: substeps,
            max_substeps: 4 * substeps,
            ..StepperConfig::default()
        };
        let Ok(mut stepper) = Stepper::new(&problem, config) else {
            return Ok(());
        };
        let mut regime = stepper.regime();
        for _ in 0..200 {
            let (t0, s0) = (stepper.time(), stepper.state());
            match stepper.step(dt) {
                Ok(r) => {
                    prop_assert!(r.time > t0 && (r.time - t0 - dt).abs() <= 1e-12 * (1.0 + t0));
                    prop_assert!(r.state.is_finite());
                    let mut last = t0;
                    for e in &r.events {
                        prop_assert!(e.time >= last && e.time <= r.time);
                        prop_assert_eq!(e.kind == EventKind::Enter, regime == Regime::Free);
                        regime = e.kind.regime_after();
                        last = e.time;
                    }
                    if !r.capped && !r.events.overflowed() {
                        prop_assert_eq!(regime, r.regime);
                    }
                    regime = r.regime;
                }
                Err(e) => {
                    prop_assert!(matches!(
                        e,
                        StepperError::Propagation(
                            PropagationError::Diverged { .. } | PropagationError::SingularContact { .. }
                        )
                    ), "{}", e);
                    prop_assert_eq!((stepper.time(), stepper.state()), (t0, s0));
                    break;
                }
            }
        }
    }
}
