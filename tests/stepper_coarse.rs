//! The fixed-step stepper at coarse steps on stiff stators: no silent wrong answer.
//!
//! The dry-whip preset (isotropic K̂ = 300, μ = 0.6, ρ_R = 2) with the stator stiffened to
//! K̂ = 1e4 … 1e5, against DOP853 at tol 1e-12 over 10 forcing periods. With one contact
//! sub-step per step whatever the stiffness, dt = 1e-2 at K̂ = 1e4 (ρ_c·dt = 2.2) gave a
//! spurious exit/enter pair at an entry (411 switches for 409 over 20 periods, states off by
//! 3.5e-3), K̂ = 1e5 a `SingularContact` at the first contact, K̂ = 1e5 at dt = 3e-3 switch
//! searches capped on 518 steps. The stepper now takes the contact sub-steps the contact mode
//! needs (ρ_c·h ≤ 0.5, `Stepper::contact_substeps`), and where they exceed `max_substeps` the
//! steps in contact are flagged `capped` (or refused with `OnCap::Fail`).

use rotor_rub::stepper::OnCap;
use rotor_rub::stepper::polynomial::MAX_RATE_STEP;
use rotor_rub::{
    Event, Method, Options, Preset, Problem, Propagator, Regime, State, Stepper, StepperConfig,
    StepperError, advance_to,
};

/// The dry-whip preset with the stator stiffness K̂xx = K̂yy = `k`.
fn stiff(k: f64) -> Problem {
    let mut p = Preset::DryWhip.problem();
    p.params.k_xx = k;
    p.params.k_yy = k;
    p
}

/// DOP853 (tol 1e-12): the states at the step ends k·dt over `steps` steps, and the switches.
fn reference(problem: &Problem, dt: f64, steps: usize) -> (Vec<State>, Vec<Event>) {
    let options = Options {
        tol: Some(1e-12),
        ..Options::with_method(Method::Dop853)
    };
    let mut p = Propagator::new(problem, &options).unwrap();
    let mut events = Vec::new();
    let states = (1..=steps)
        .map(|k| {
            advance_to(&mut p, problem.start_time + k as f64 * dt, |e| {
                events.push(*e)
            })
            .unwrap()
            .state
        })
        .collect();
    (states, events)
}

/// The stiff cases: K̂, the step, the sub-step cap (above the sub-steps the contact mode needs:
/// 5, 3, 8, 5, 14).
const CASES: [(f64, f64, u32); 5] = [
    (1e4, 1e-2, 8),
    (3e4, 3e-3, 8),
    (3e4, 1e-2, 16),
    (1e5, 3e-3, 8),
    (1e5, 1e-2, 32),
];

/// The same switches as DOP853 (kinds and count), no cap, and the bounds: step-end states within
/// 6e-6 and switch times within 1.5e-7 of DOP853. Measured 0.7–2.4e-6 and 2.1–5.4e-8 (the
/// exprb43 estimate 0.6–2.5e-6): the accuracy the stepper has at dt = 1e-2 on the unstiffened
/// preset (1.1e-6, 1.3e-7), since each contact sub-step spans the same ρ_c·h ≤ 0.5.
#[test]
fn stiff_stators_at_coarse_steps_match_dop853() {
    let (state_bound, time_bound) = (6e-6, 1.5e-7);
    for (k, dt, max_substeps) in CASES {
        let problem = stiff(k);
        let steps = (10.0 * problem.params.forcing_period() / dt).round() as usize;
        let (want, want_events) = reference(&problem, dt, steps);
        let config = StepperConfig {
            max_substeps,
            ..StepperConfig::with_dt(dt)
        };
        let mut stepper = Stepper::new(&problem, config).unwrap();
        let needed = stepper.contact_substeps();
        assert!(needed > 1 && needed <= max_substeps, "K̂ = {k:e}: {needed}");
        let (mut state_error, mut estimate): (f64, f64) = (0.0, 0.0);
        let mut events = Vec::new();
        for w in &want {
            let r = stepper
                .step(dt)
                .unwrap_or_else(|e| panic!("K̂ = {k:e}, dt = {dt:e}: {e}"));
            assert!(
                !r.capped && !r.search_capped,
                "K̂ = {k:e}: a cap at {}",
                r.time
            );
            if r.regime != Regime::Free || !r.events.is_empty() {
                assert!(
                    r.substeps >= 1,
                    "K̂ = {k:e}: a contact step without sub-steps"
                );
            }
            events.extend(r.events.iter().copied());
            estimate = estimate.max(r.error_estimate);
            for (x, y) in r.state.to_array().iter().zip(&w.to_array()) {
                state_error = state_error.max((x - y).abs());
            }
        }
        let kinds = |e: &[Event]| e.iter().map(|e| e.kind.name()).collect::<Vec<_>>();
        assert_eq!(
            kinds(&events),
            kinds(&want_events),
            "K̂ = {k:e}, dt = {dt:e}"
        );
        let time_error = events
            .iter()
            .zip(&want_events)
            .map(|(a, b)| (a.time - b.time).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "K̂ = {k:.0e}, dt = {dt:.0e}: {needed:2} sub-steps per contact step, {} switches, \
             state error {state_error:.1e} (estimate {estimate:.1e}), switch times {time_error:.1e}",
            events.len()
        );
        assert!(
            state_error <= state_bound,
            "K̂ = {k:e}, dt = {dt:e}: state {state_error:e}"
        );
        assert!(
            time_error <= time_bound,
            "K̂ = {k:e}, dt = {dt:e}: times {time_error:e}"
        );
    }
}

/// The sub-step count follows the contact mode: ⌈ρ_c·dt/0.5⌉, the configured count when larger,
/// unchanged (1) on the presets at dt ≤ 1e-2, recomputed with the stiffness and the step, kept
/// by a speed change; and the steps in contact take that many.
#[test]
fn contact_substeps_follow_the_contact_mode() {
    for preset in Preset::PLANAR {
        let s = Stepper::new(&preset.problem(), StepperConfig::with_dt(1e-2)).unwrap();
        assert_eq!(s.contact_substeps(), 1, "{preset:?}");
        assert!(s.contact_rate() * 1e-2 <= MAX_RATE_STEP, "{preset:?}");
    }
    let problem = stiff(1e4);
    let mut s = Stepper::new(&problem, StepperConfig::with_dt(1e-2)).unwrap();
    let rate = s.contact_rate();
    // ρ_c ≥ √(1 + K̂) (the frictionless contact frequency; friction adds to the bound).
    assert!(rate >= (1.0 + 1e4_f64).sqrt(), "{rate}");
    let needed = (rate * 1e-2 / MAX_RATE_STEP).ceil() as u32;
    assert_eq!(s.contact_substeps(), needed);
    let largest = s.largest_resolved_dt();
    assert!(
        (largest * rate / MAX_RATE_STEP - 8.0).abs() < 1e-12,
        "{largest}"
    );
    // A configured count above the need is kept.
    let config = StepperConfig {
        contact_substeps: needed + 3,
        max_substeps: 64,
        ..StepperConfig::with_dt(1e-2)
    };
    assert_eq!(
        Stepper::new(&problem, config).unwrap().contact_substeps(),
        needed + 3
    );
    // Every step in contact or rolling without a switch takes the needed sub-steps.
    let mut in_contact = 0;
    for _ in 0..2000 {
        let before = s.regime();
        let r = s.step(1e-2).unwrap();
        if r.events.is_empty() && before != Regime::Free {
            assert_eq!(r.substeps, needed, "at {}", r.time);
            in_contact += 1;
        }
    }
    assert!(in_contact >= 20, "{in_contact} steps in contact");
    // A shorter step needs fewer, a speed change none more, a stiffer stator more.
    s.step(2e-3).unwrap();
    assert_eq!(
        s.contact_substeps(),
        (rate * 2e-3 / MAX_RATE_STEP).ceil() as u32
    );
    s.set_speed_ratio(2.0).unwrap();
    assert_eq!(s.contact_rate(), rate);
    let mut params = *s.params();
    params.k_xx = 1e5;
    params.k_yy = 1e5;
    s.set_params(&params).unwrap();
    assert!(s.contact_rate() > 3.0 * rate);
    let fresh = Stepper::new(&Problem { params, ..problem }, StepperConfig::with_dt(2e-3)).unwrap();
    assert_eq!(s.contact_rate().to_bits(), fresh.contact_rate().to_bits());
    assert_eq!(s.contact_substeps(), fresh.contact_substeps());
}

/// Where the contact mode needs more sub-steps than `max_substeps` (K̂ = 1e5 at dt = 1e-2: 14
/// against the default 8), every step through contact says so: `capped` with `OnCap::Degrade`,
/// `BudgetExceeded` (the stepper unchanged) with `OnCap::Fail`.
#[test]
fn a_contact_mode_beyond_the_cap_is_reported() {
    let problem = stiff(1e5);
    let mut degrade = Stepper::new(&problem, StepperConfig::with_dt(1e-2)).unwrap();
    assert!(
        degrade.contact_substeps() > 8,
        "{}",
        degrade.contact_substeps()
    );
    assert!(degrade.largest_resolved_dt() < 1e-2);
    // Contacts are short here (≈ 0.01): a step that starts in contact needs 14 sub-steps to its
    // end, so it is capped whenever it holds no exit; the measured ones all reached the cap.
    let (mut from_contact, mut capped) = (0, 0);
    for _ in 0..2000 {
        let before = degrade.regime();
        match degrade.step(1e-2) {
            Ok(r) => {
                if before != Regime::Free {
                    from_contact += 1;
                    capped += usize::from(r.capped);
                    assert!(r.capped || !r.events.is_empty(), "uncapped at {}", r.time);
                }
            }
            // The capped remainder may be refused as singular: typed, never silent.
            Err(StepperError::Propagation(_)) => break,
            Err(e) => panic!("{e}"),
        }
    }
    assert!(
        from_contact > 0 && capped > 0,
        "{from_contact} steps from contact"
    );
    let config = StepperConfig {
        on_cap: OnCap::Fail,
        ..StepperConfig::with_dt(1e-2)
    };
    let mut fail = Stepper::new(&problem, config).unwrap();
    loop {
        let (t0, s0) = (fail.time(), fail.state());
        match fail.step(1e-2) {
            Ok(r) => assert!(!r.capped && r.time < 10.0, "at {}", r.time),
            Err(e) => {
                assert!(matches!(e, StepperError::BudgetExceeded { .. }), "{e}");
                assert_eq!((fail.time(), fail.state()), (t0, s0));
                break;
            }
        }
    }
}
