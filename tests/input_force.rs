//! The external input force and the speed input (`docs/MODEL.md` §15): every method against
//! DOP853 at tol 1e-13 on the nonlinear field with the force (an independent path: the numerical
//! fields carry the force as part of the forcing, while the closed forms move free flight's origin
//! to the static deflection and add Kl⁻¹u to contact's particular solution); a force changed at
//! every step against DOP853 restarted at every step; the speed input's continuous phase;
//! the stepper's early stop at a switch, its budget policy and its snapshot.

use rotor_rub::stepper::{OnCap, Snapshot};
use rotor_rub::{
    ContactScheme, Method, Options, Preset, Problem, Propagator, State, Stepper, StepperConfig,
    StepperError, advance_to, math,
};

fn max_abs_diff(a: State, b: State) -> f64 {
    let (a, b) = (a.to_array(), b.to_array());
    (0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

fn reference(problem: &Problem) -> Propagator {
    let options = Options {
        tol: Some(1e-13),
        ..Options::with_method(Method::Dop853)
    };
    Propagator::new(problem, &options).expect("valid problem")
}

/// The paper preset pushed by a constant force away from the stator centre (a static load that
/// moves the equilibrium 0.45 clearances off-centre), so that contact is frequent.
fn loaded() -> Problem {
    let mut problem = Preset::Paper.problem();
    problem.params.force_x = -0.1;
    problem.params.force_y = 0.15;
    problem
}

#[test]
fn every_method_follows_a_constant_force() {
    let problem = loaded();
    let end = 5.0 * problem.params.forcing_period();
    let mut events_ref = Vec::new();
    let at_end = advance_to(&mut reference(&problem), end, |e| events_ref.push(*e)).unwrap();
    assert!(
        events_ref.len() >= 10,
        "contact happens: {}",
        events_ref.len()
    );
    for (name, options, tol) in [
        // Measured: 8.6e-12 / 2.2e-11, 2.3e-11 / 5.7e-11, 2.1e-10 / 5.4e-10.
        (
            "analytic",
            Options {
                tol: Some(1e-11),
                ..Options::default()
            },
            1e-9,
        ),
        (
            "hybrid",
            Options {
                tol: Some(1e-12),
                ..Options::with_method(Method::Hybrid)
            },
            1e-9,
        ),
        (
            "rk45",
            Options {
                tol: Some(1e-12),
                ..Options::with_method(Method::Rk45)
            },
            1e-8,
        ),
    ] {
        let mut events = Vec::new();
        let mut p = Propagator::new(&problem, &options).unwrap();
        let s = advance_to(&mut p, end, |e| events.push(*e)).unwrap();
        assert_eq!(events.len(), events_ref.len(), "{name}: switch count");
        let worst = events
            .iter()
            .zip(&events_ref)
            .map(|(a, b)| (a.time - b.time).abs())
            .fold(0.0, f64::max);
        let err = max_abs_diff(s.state, at_end.state);
        println!("{name}: switch times within {worst:.1e}, end state within {err:.1e}");
        assert!(worst < tol && err < tol, "{name}: {worst:e}, {err:e}");
    }
    let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(1e-3)).unwrap();
    let mut switches = 0;
    while stepper.time() < end - 1e-9 {
        let dt = (end - stepper.time()).min(1e-3);
        switches += stepper.step(dt).unwrap().events.total();
    }
    let err = max_abs_diff(stepper.state(), at_end.state);
    println!("stepper dt = 1e-3: {switches} switches, end state within {err:.1e}");
    assert_eq!(switches, events_ref.len());
    // Measured 4.7e-11.
    assert!(err < 1e-9, "stepper: {err:e}");
}

#[test]
fn zero_force_set_between_steps_changes_no_bit() {
    let problem = Preset::Paper.problem();
    let mut a = Stepper::new(&problem, StepperConfig::with_dt(1e-3)).unwrap();
    let mut b = a;
    for k in 0..20_000 {
        if k % 7 == 0 {
            b.set_input_force(0.0, 0.0).unwrap();
        }
        let (ra, rb) = (a.step(1e-3).unwrap(), b.step(1e-3).unwrap());
        assert_eq!(ra, rb, "step {k}");
    }
}

#[test]
fn a_force_changed_every_step_matches_dop853_restarted_every_step() {
    // A PD-like force sampled at every step: the closed forms are exact for a force constant
    // over each step, so the stepper must follow the restarted reference closely.
    let problem = Preset::Paper.problem();
    let dt = 1e-2;
    let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(dt)).unwrap();
    let mut state = problem.initial;
    let mut worst = 0.0f64;
    for k in 0..2000 {
        let t = k as f64 * dt;
        let (fx, fy) = (
            -0.8 * state.x - 0.1 * state.vx,
            -0.8 * state.y - 0.1 * state.vy,
        );
        stepper.set_input_force(fx, fy).unwrap();
        let mut piece = problem;
        (piece.params.force_x, piece.params.force_y) = (fx, fy);
        piece.initial = state;
        piece.start_time = t;
        state = advance_to(&mut reference(&piece), t + dt, |_| {})
            .unwrap()
            .state;
        let r = stepper.step(dt).unwrap();
        worst = worst.max(max_abs_diff(r.state, state));
        // Follow the stepper (a chaotic rub would separate two runs over 20 time units).
        state = r.state;
    }
    // Measured 3.6e-10 (exprb43 sub-steps of 1e-2 in contact).
    println!("largest one-step difference from restarted DOP853: {worst:.1e}");
    assert!(worst < 1e-8, "{worst:e}");
}

#[test]
fn out_of_range_or_nan_forces_are_refused_and_change_nothing() {
    let mut s = Stepper::new(&Preset::Paper.problem(), StepperConfig::default()).unwrap();
    let before = s.snapshot();
    for (fx, fy) in [
        (f64::NAN, 0.0),
        (0.0, f64::INFINITY),
        (1e4, 0.0),
        (0.0, -1001.0),
    ] {
        assert!(s.set_input_force(fx, fy).is_err(), "({fx}, {fy})");
        assert_eq!(s.snapshot(), before);
    }
    for eta in [f64::NAN, 0.0, 1e3] {
        assert!(s.set_speed_ratio(eta).is_err(), "{eta}");
        assert_eq!(s.snapshot(), before);
    }
}

#[test]
fn a_speed_change_keeps_the_forcing_phase_continuous() {
    let problem = Preset::Paper.problem();
    let mut s = Stepper::new(&problem, StepperConfig::with_dt(1e-3)).unwrap();
    for k in 0..5000 {
        s.step(1e-3).unwrap();
        if k % 500 == 499 {
            let p = *s.params();
            let before = math::wrap_angle(p.speed_ratio * s.time() + p.phase);
            s.set_speed_ratio(p.speed_ratio * 1.01).unwrap();
            let q = *s.params();
            let after = math::wrap_angle(q.speed_ratio * s.time() + q.phase);
            let jump = (after - before).abs();
            let jump = jump.min(core::f64::consts::TAU - jump);
            assert!(jump < 1e-12, "phase jump {jump:e} at {}", s.time());
            let f = (q.mass_ratio * q.eccentricity_ratio * q.speed_ratio * q.speed_ratio)
                / (p.mass_ratio * p.eccentricity_ratio * p.speed_ratio * p.speed_ratio);
            assert!((f - 1.01 * 1.01).abs() < 1e-12);
        }
    }
}

#[test]
fn step_to_switch_stops_where_step_finds_the_switch() {
    let problem = Preset::Paper.problem();
    let mut s = Stepper::new(&problem, StepperConfig::with_dt(1e-2)).unwrap();
    let mut stops = 0;
    while stops < 20 {
        let copy = s;
        let full = s.step(1e-2).unwrap();
        let Some(first) = full.events.iter().next().copied() else {
            continue;
        };
        let mut early = copy;
        let r = early.step_to_switch(1e-2).unwrap();
        assert_eq!(r.time, first.time);
        assert_eq!(r.state, first.state);
        assert_eq!(r.events.len(), 1);
        assert_eq!(r.regime, first.kind.regime_after());
        assert_eq!(early.time(), first.time);
        // The rest of the step from the switch ends where the whole step ended.
        let rest = early.step(full.time - early.time()).unwrap();
        assert!((rest.time - full.time).abs() < 1e-15);
        assert!(max_abs_diff(rest.state, full.state) < 1e-11);
        stops += 1;
    }
}

#[test]
fn a_step_over_budget_is_refused_under_on_cap_fail() {
    let problem = Preset::Paper.problem();
    let config = StepperConfig {
        dt: 0.5,
        contact_substeps: 1,
        max_substeps: 1,
        ..StepperConfig::default()
    };
    let mut degrade = Stepper::new(&problem, config).unwrap();
    let mut fail = Stepper::new(
        &problem,
        StepperConfig {
            on_cap: OnCap::Fail,
            ..config
        },
    )
    .unwrap();
    let mut refused = 0;
    for _ in 0..400 {
        let r = degrade.step(0.5).unwrap();
        let (before, t_before) = (fail.snapshot(), fail.time());
        match fail.step(0.5) {
            Ok(s) => assert_eq!(s, r),
            Err(StepperError::BudgetExceeded { time, .. }) => {
                assert!(r.capped || r.search_capped);
                assert_eq!(time, t_before);
                assert_eq!(fail.snapshot(), before, "unchanged");
                refused += 1;
                fail = degrade;
            }
            Err(e) => panic!("{e}"),
        }
    }
    assert!(refused > 0, "the case has capped steps");
}

#[test]
fn a_restored_snapshot_steps_on_bit_for_bit() {
    let mut problem = Preset::Friction.problem();
    problem.params.force_x = 0.1;
    for scheme in [ContactScheme::Exprb43, ContactScheme::Exprb2] {
        let config = StepperConfig {
            scheme,
            ..StepperConfig::with_dt(1e-3)
        };
        let mut a = Stepper::new(&problem, config).unwrap();
        for k in 0..30_000 {
            a.step(1e-3).unwrap();
            if k == 1234 {
                a.set_speed_ratio(1.7).unwrap();
            }
        }
        let words = a.snapshot().to_words();
        let mut b = Stepper::restore(&Snapshot::from_words(&words).unwrap()).unwrap();
        for _ in 0..10_000 {
            assert_eq!(a.step(1e-3).unwrap(), b.step(1e-3).unwrap());
        }
        let mut bad = words;
        bad[Snapshot::WORDS - 1] ^= 1;
        assert!(Snapshot::from_words(&bad).is_err());
    }
}

#[test]
fn hermite_started_switches_are_the_same_switches_to_rounding() {
    // SwitchStart::Hermite changes only where the refinement of a bracketed switch starts: the
    // same switches, times and states to rounding (chaos over 20 periods amplifies rounding
    // only far below the tolerance checked).
    use rotor_rub::stepper::SwitchStart;
    let problem = Preset::Paper.problem();
    for dt in [1e-3, 1e-2] {
        let mut a = Stepper::new(&problem, StepperConfig::with_dt(dt)).unwrap();
        let mut b = Stepper::new(
            &problem,
            StepperConfig {
                switch_start: SwitchStart::Hermite,
                ..StepperConfig::with_dt(dt)
            },
        )
        .unwrap();
        let (mut worst_t, mut worst_s, mut n) = (0.0f64, 0.0f64, 0);
        let steps = (5.0 * problem.params.forcing_period() / dt) as usize;
        for _ in 0..steps {
            let (ra, rb) = (a.step(dt).unwrap(), b.step(dt).unwrap());
            assert_eq!(ra.events.len(), rb.events.len());
            for (x, y) in ra.events.iter().zip(rb.events.iter()) {
                assert_eq!(x.kind, y.kind);
                worst_t = worst_t.max((x.time - y.time).abs());
                n += 1;
            }
            assert!(!rb.search_capped);
            worst_s = worst_s.max(max_abs_diff(ra.state, rb.state));
        }
        println!(
            "dt = {dt}: {n} switches, times within {worst_t:.1e}, states within {worst_s:.1e}"
        );
        assert!(
            n >= 15 && worst_t < 1e-11 && worst_s < 1e-10,
            "{worst_t:e} {worst_s:e}"
        );
    }
}

#[test]
fn a_constant_force_under_friction_matches_dop853() {
    // The friction preset (backward whirl, slipping) pushed sideways: λ, the roll and slip
    // decisions and the slipping closed form all see u.
    let mut problem = Preset::Friction.problem();
    problem.params.force_x = 0.1;
    problem.params.force_y = -0.05;
    let end = 3.0 * problem.params.forcing_period();
    let mut events_ref = Vec::new();
    let at_end = advance_to(&mut reference(&problem), end, |e| events_ref.push(*e)).unwrap();
    assert!(
        events_ref.len() >= 4,
        "contact happens: {}",
        events_ref.len()
    );
    for (name, options) in [
        (
            "analytic",
            Options {
                tol: Some(1e-11),
                ..Options::default()
            },
        ),
        (
            "hybrid",
            Options {
                tol: Some(1e-12),
                ..Options::with_method(Method::Hybrid)
            },
        ),
    ] {
        let mut events = Vec::new();
        let mut p = Propagator::new(&problem, &options).unwrap();
        let s = advance_to(&mut p, end, |e| events.push(*e)).unwrap();
        let kinds: Vec<_> = events.iter().map(|e| e.kind).collect();
        let kinds_ref: Vec<_> = events_ref.iter().map(|e| e.kind).collect();
        assert_eq!(kinds, kinds_ref, "{name}");
        let worst = events
            .iter()
            .zip(&events_ref)
            .map(|(a, b)| (a.time - b.time).abs())
            .fold(0.0, f64::max);
        let err = max_abs_diff(s.state, at_end.state);
        println!(
            "friction + force, {name}: {} switches within {worst:.1e}, end within {err:.1e}",
            events.len()
        );
        // Measured: analytic 1.0e-12 / 4.0e-13, hybrid 1.6e-12 / 4.0e-13.
        assert!(worst < 1e-10 && err < 1e-10, "{name}: {worst:e} {err:e}");
    }
    let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(1e-3)).unwrap();
    let mut kinds = Vec::new();
    while stepper.time() < end - 1e-9 {
        let dt = (end - stepper.time()).min(1e-3);
        kinds.extend(stepper.step(dt).unwrap().events.iter().map(|e| e.kind));
    }
    let err = max_abs_diff(stepper.state(), at_end.state);
    println!("friction + force, stepper dt = 1e-3: end within {err:.1e}");
    assert_eq!(kinds, events_ref.iter().map(|e| e.kind).collect::<Vec<_>>());
    // Measured 2.7e-13.
    assert!(err < 1e-10, "stepper: {err:e}");
}
