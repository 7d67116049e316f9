//! The fixed-step stepper of the stator ring with mass (issue 28 item 3; `runtime/stepper/
//! matrix.rs`, `ring.rs`): its states at k·dt against the matrix propagator's continuous run
//! sampled at those times, its switches against the independent ring oracle
//! (`matrix_oracle/ring.rs`, DOP853 of another crate at tol 1e-13), m̂ > 0 with and without
//! friction; its inputs, roll-back, work cap and typed errors; and the planar problem through
//! [`AnyStepper`] bit for bit the planar [`Stepper`].

#[allow(
    dead_code,
    reason = "the oracle's other items serve tests/matrix_ring.rs"
)]
mod matrix_oracle {
    pub mod cases;
    pub mod ring;
}

use matrix_oracle::cases::{CASES, Case};
use matrix_oracle::ring;
use rotor_rub::matrix::{MatrixPropagator, ring_model, ring_start};
use rotor_rub::method::Method;
use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub::stepper::{AnyStepper, RingStepper};
use rotor_rub::{
    Parameter, Preset, Problem, Propagate, PropagationError, Regime, Stepper, StepperConfig,
    StepperError, samples,
};

fn case(name: &str) -> &'static Case {
    CASES.iter().find(|c| c.name == name).expect("a case")
}

/// The stepper's states at k·dt equal a continuous run's samples at those times (same method,
/// same tolerance): the stepper asks the same propagator for the same times.
#[test]
fn states_at_the_steps_are_the_continuous_runs_samples() {
    for (name, method) in [
        ("heavy", Method::Taylor),
        ("heavy", Method::Hybrid),
        ("reversal", Method::Taylor),
        ("rolling ring", Method::Hybrid),
    ] {
        let problem = case(name).problem();
        let dt = 0.01;
        let config = MatrixStepperConfig {
            method,
            tol: Some(1e-12),
            ..MatrixStepperConfig::with_dt(dt)
        };
        let mut stepper = RingStepper::new(&problem, config).expect("the ring stepper starts");
        let model = ring_model(&problem.params).expect("the ring model");
        let mut continuous =
            MatrixPropagator::new(&model, 0.0, ring_start(&problem), &config.options())
                .expect("the propagator starts");
        let times: Vec<f64> = (1..=2000).map(|k| k as f64 * dt).collect();
        let sampled: Vec<_> = samples(&mut continuous, times.iter().copied())
            .collect::<Result<_, _>>()
            .expect("the continuous run");
        let mut worst = 0.0f64;
        let mut switches = 0;
        for (k, s) in sampled.iter().enumerate() {
            let report = stepper.step(dt).expect("a step");
            switches += report.events.total();
            assert_eq!(report.time, times[k], "{name}: step {k} ends at k·dt");
            let d = report
                .state
                .as_slice()
                .iter()
                .zip(s.state.as_slice())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            worst = worst.max(d);
        }
        println!("{name} {method:?}: {switches} switches, worst state difference {worst:.1e}");
        assert!(switches > 10, "{name}: the case rubs ({switches} switches)");
        assert!(
            worst <= 1e-9,
            "{name} {method:?}: the stepper's states differ from the continuous run's by {worst:e}"
        );
    }
}

/// Every switch the stepper reports, against the oracle: same kinds, times within 1e-8, over
/// the first 40 switches (m̂ > 0 without friction, with reversal and rolling).
#[test]
fn switches_agree_with_the_oracle() {
    for name in ["heavy", "non-symmetric", "reversal", "rolling ring"] {
        let c = case(name);
        let problem = c.problem();
        let y0: [f64; 8] = ring_start(&problem).as_slice().try_into().expect("8");
        let mut stepper = RingStepper::new(
            &problem,
            MatrixStepperConfig {
                tol: Some(1e-13),
                ..MatrixStepperConfig::with_dt(1e-2)
            },
        )
        .expect("the ring stepper starts");
        let mut got = Vec::new();
        while got.len() < 40 {
            let report = stepper.step(1e-2).expect("a step");
            assert_eq!(report.events.dropped(), 0, "{name}: no switch dropped");
            got.extend(report.events.iter().copied());
        }
        let end = stepper.time();
        let want = ring::run(&problem.params, y0, 0.0, end).events;
        let mut worst = 0.0f64;
        for (k, (a, b)) in got.iter().zip(&want).enumerate() {
            assert_eq!(a.kind.name(), b.kind, "{name}: switch {k} at {}", b.time);
            let d = (a.time - b.time).abs();
            assert!(
                d <= 1e-8,
                "{name}: switch {k} ({}) at {}: the stepper's is {d:e} away",
                b.kind,
                b.time
            );
            worst = worst.max(d);
        }
        assert!(want.len() >= got.len(), "{name}: no extra switch");
        println!("{name}: {} switches, worst time {worst:.1e}", got.len());
    }
}

/// A planar problem through [`AnyStepper`] is the planar stepper, bit for bit; its ring is at
/// rest.
#[test]
fn the_planar_problem_is_the_planar_stepper() {
    let problem = Preset::Paper.problem();
    let config = StepperConfig::with_dt(1e-3);
    let mut any = AnyStepper::new(&problem, config).expect("starts");
    assert!(matches!(any, AnyStepper::Planar(_)));
    let mut planar = Stepper::new(&problem, config).expect("starts");
    for _ in 0..20_000 {
        assert_eq!(any.step(1e-3), planar.step(1e-3));
    }
    assert_eq!(any.ring_state(), Default::default());
}

/// m̂ > 0 through [`AnyStepper`] runs the ring: the rotor's switches of the ring stepper.
#[test]
fn a_ring_problem_runs_the_ring() {
    let problem = case("heavy").problem();
    let mut any = AnyStepper::new(&problem, StepperConfig::with_dt(1e-2)).expect("starts");
    assert!(matches!(any, AnyStepper::Ring(_)));
    let mut ring = RingStepper::new(&problem, MatrixStepperConfig::with_dt(1e-2)).expect("starts");
    let mut moved = 0.0f64;
    for _ in 0..1000 {
        let a = any.step(1e-2).expect("a step");
        let r = ring.step(1e-2).expect("a step");
        assert_eq!(a.events.total(), r.events.total());
        for (e, f) in a.events.iter().zip(r.events.iter()) {
            assert_eq!((e.time, e.kind), (f.time, f.kind));
            assert_eq!(e.state.x, f.state.get(0));
        }
        assert_eq!(a.state, ring.state());
        moved = moved.max(any.ring_state().xs.hypot(any.ring_state().ys));
    }
    assert!(moved > 0.1, "the ring moves ({moved})");
}

/// Snapshot and restore: stepping on from a restored snapshot repeats the same bits.
#[test]
fn restore_rolls_back() {
    let problem = case("reversal").problem();
    let mut s = RingStepper::new(&problem, MatrixStepperConfig::with_dt(1e-2)).expect("starts");
    for _ in 0..300 {
        s.step(1e-2).expect("a step");
    }
    let snap = s.snapshot();
    let first: Vec<_> = (0..300).map(|_| s.step(1e-2).expect("a step")).collect();
    s.restore(&snap);
    let again: Vec<_> = (0..300).map(|_| s.step(1e-2).expect("a step")).collect();
    assert_eq!(first, again);
}

/// The work cap: a step holding more switches than `max_switches` is refused, typed, the
/// stepper unchanged; shorter steps get through.
#[test]
fn a_step_beyond_its_switch_cap_is_refused() {
    let problem = case("heavy").problem();
    let config = MatrixStepperConfig {
        max_switches: 2,
        ..MatrixStepperConfig::with_dt(1.0)
    };
    let mut s = RingStepper::new(&problem, config).expect("starts");
    let mut refused = 0;
    for _ in 0..50 {
        let before = (s.time(), s.full_state(), s.regime());
        match s.step(1.0) {
            Ok(r) => assert!(r.events.total() <= 2),
            Err(StepperError::BudgetExceeded { substeps, .. }) => {
                refused += 1;
                assert_eq!(substeps, 2);
                assert_eq!((s.time(), s.full_state(), s.regime()), before, "unchanged");
                for _ in 0..1000 {
                    s.step(1e-3).expect("shorter steps get through");
                }
            }
            Err(e) => panic!("unexpected {e}"),
        }
    }
    assert!(
        refused > 0,
        "the heavy rub holds unit steps with three switches"
    );
}

/// Inputs between steps: the input force and the speed (phase continuous) re-state the model;
/// bad values are typed errors and change nothing.
#[test]
fn inputs_between_steps() {
    let problem = case("heavy").problem();
    let mut s = RingStepper::new(&problem, MatrixStepperConfig::with_dt(1e-2)).expect("starts");
    for _ in 0..100 {
        s.step(1e-2).expect("a step");
    }
    let before = s.full_state();
    s.set_input_force(0.5, -0.2).expect("in range");
    assert_eq!(s.input_force(), (0.5, -0.2));
    assert_eq!(s.full_state(), before, "no jump in the state");
    // The forcing phase is continuous across a speed change.
    let theta = |p: &rotor_rub::Params, t: f64| {
        (p.speed_ratio * t + p.phase).rem_euclid(std::f64::consts::TAU)
    };
    let t = s.time();
    let old = theta(s.params(), t);
    s.set_speed_ratio(1.7).expect("in range");
    let new = theta(s.params(), t);
    assert!((old - new).abs() < 1e-12 || (old - new).abs() > std::f64::consts::TAU - 1e-12);
    for _ in 0..100 {
        s.step(1e-2).expect("a step");
    }
    let saved = (s.time(), s.full_state(), *s.params());
    assert!(s.set_input_force(f64::NAN, 0.0).is_err());
    assert!(s.set_speed_ratio(-1.0).is_err());
    let mut massless = *s.params();
    massless.stator_mass_ratio = 0.0;
    massless.contact_stiffness = 0.0;
    massless.stator_damping = 0.0;
    assert!(
        s.set_params(&massless).is_err(),
        "m̂ = 0 is the planar stepper's"
    );
    assert_eq!((s.time(), s.full_state(), *s.params()), saved);
}

/// Bad input: typed errors, never a panic.
#[test]
fn bad_input_is_refused() {
    let problem = case("heavy").problem();
    let config = MatrixStepperConfig::with_dt(1e-2);
    assert!(matches!(
        RingStepper::new(&Preset::Paper.problem(), config),
        Err(StepperError::Propagation(PropagationError::InvalidProblem(
            rotor_rub::ParamError::OutOfRange {
                parameter: Parameter::StatorMassRatio,
                ..
            }
        )))
    ));
    for max_switches in [0, 100_000] {
        assert!(matches!(
            RingStepper::new(
                &problem,
                MatrixStepperConfig {
                    max_switches,
                    ..config
                }
            ),
            Err(StepperError::InvalidConfig {
                what: "max_switches",
                ..
            })
        ));
    }
    assert!(matches!(
        RingStepper::new(
            &problem,
            MatrixStepperConfig {
                tol: Some(-1.0),
                ..config
            }
        ),
        Err(StepperError::Propagation(
            PropagationError::InvalidOption { .. }
        ))
    ));
    let mut bad = problem;
    Parameter::StatorMassRatio.set(&mut bad, -1.0);
    assert!(RingStepper::new(&bad, config).is_err());
    let mut s = RingStepper::new(&problem, config).expect("starts");
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY, 2.0] {
        assert!(matches!(s.step(dt), Err(StepperError::InvalidStep { .. })));
    }
    assert_eq!(s.time(), 0.0);
    assert_eq!(s.regime(), Regime::Free);
    let _: Problem = problem;
}

/// The matrix stepper on any rotor from matrices, not only the ring: a 3-DOF gyroscopic rotor
/// with a coupled third DOF and a fixed stator (`MatrixStepper<&MatrixModel<8>, 8>`): its
/// states at k·dt are the continuous run's samples, its switches the continuous run's.
#[test]
fn any_matrix_model_steps() {
    use rotor_rub::linalg::{RealMatrix, SecondOrder};
    use rotor_rub::matrix::{MatrixModel, MatrixState, Running, Station, Unbalance};
    use rotor_rub::stepper::MatrixStepper;
    let m =
        |a: [[f64; 3]; 3]| RealMatrix::<8>::from_fn(3, 3, |i, j| a[i][j]).expect("a 3×3 matrix");
    let mass = m([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.5]]);
    let damping = m([[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.05]]);
    let gyroscopic = m([[0.0, 0.05, 0.0], [-0.05, 0.0, 0.0], [0.0, 0.0, 0.0]]);
    let stiffness = m([[1.0, 0.0, 0.2], [0.0, 1.0, 0.0], [0.2, 0.0, 0.8]]);
    let rotor = SecondOrder {
        mass: &mass,
        damping: &damping,
        gyroscopic: &gyroscopic,
        stiffness: &stiffness,
    };
    let model = MatrixModel::<8>::new(
        &rotor,
        Running {
            speed_ratio: 1.5,
            phase: 0.0,
        },
        &[Unbalance {
            x: 0,
            y: 1,
            amount: 0.6,
            phase: 0.0,
        }],
        &[],
        Station {
            rotor: (0, 1),
            stator: None,
            offset: (0.2, 0.0),
            contact_stiffness: [[25.0, 0.0], [0.0, 25.0]],
            friction_coefficient: 0.0,
            radius_ratio: 1.0,
        },
    )
    .expect("a valid model");
    let start = MatrixState::rest(3).expect("3 DOFs");
    let dt = 1e-2;
    let config = MatrixStepperConfig {
        tol: Some(1e-12),
        ..MatrixStepperConfig::with_dt(dt)
    };
    let mut stepper = MatrixStepper::new(&model, 0.0, start, config).expect("starts");
    let mut continuous =
        MatrixPropagator::new(&model, 0.0, start, &config.options()).expect("starts");
    let times: Vec<f64> = (1..=3000).map(|k| k as f64 * dt).collect();
    let mut want_switches = Vec::new();
    let mut sampled = Vec::new();
    for &t in &times {
        while let Some(e) = continuous.advance(t).expect("the continuous run") {
            want_switches.push((e.time, e.kind));
        }
        sampled.push(continuous.state());
    }
    let mut got_switches = Vec::new();
    for (k, s) in sampled.iter().enumerate() {
        let r = stepper.step(dt).expect("a step");
        got_switches.extend(r.events.iter().map(|e| (e.time, e.kind)));
        assert_eq!(r.time, times[k]);
        assert_eq!(r.state.as_slice(), s.as_slice(), "step {k}");
    }
    assert_eq!(got_switches, want_switches);
    assert!(
        got_switches.len() > 10,
        "it rubs ({} switches)",
        got_switches.len()
    );
}

/// The slip direction under friction (what the FMU's `slip_regime` reads): ±1 while slipping,
/// its sign flipping at each `reverse`, 0 when free or rolling.
#[test]
fn the_slip_direction_follows_the_switches() {
    let problem = case("reversal").problem();
    let mut s = RingStepper::new(&problem, MatrixStepperConfig::with_dt(1e-2)).expect("starts");
    let (mut seen, mut reversals) = ([false; 3], 0);
    for _ in 0..3000 {
        let before = s.slip_direction();
        let r = s.step_to_switch(1e-2).expect("a step");
        let sigma = s.slip_direction();
        match s.regime() {
            Regime::Contact => assert!(sigma == 1.0 || sigma == -1.0, "slipping: σ = {sigma}"),
            _ => assert_eq!(sigma, 0.0),
        }
        if let Some(e) = r.events.iter().next()
            && e.kind == rotor_rub::EventKind::Reverse
        {
            reversals += 1;
            assert_eq!(sigma, -before, "a reversal flips σ at {}", e.time);
        }
        seen[(sigma + 1.0) as usize] = true;
    }
    assert!(
        reversals > 0 && seen.iter().all(|&x| x),
        "{reversals} reversals, {seen:?}"
    );
}

/// Words restore the side: right after each `reverse` (w = 0 to rounding, its sign no guide)
/// the stepper restored from its words slips in the direction the original does, and both step
/// on through the same switches. A fresh start at the same time and state, which decides the
/// side anew, picks another one there (the trap). Corrupt side words are typed errors.
#[test]
fn words_restore_the_slip_direction() {
    let problem = case("reversal").problem();
    let config = MatrixStepperConfig::with_dt(1e-2);
    let mut s = RingStepper::new(&problem, config).expect("starts");
    let (mut reversals, mut afresh_differs) = (0, 0);
    for _ in 0..3000 {
        let r = s.step_to_switch(1e-2).expect("a step");
        let Some(e) = r.events.iter().next() else {
            continue;
        };
        if e.kind != rotor_rub::EventKind::Reverse {
            continue;
        }
        reversals += 1;
        let words = s.to_words();
        let mut restored = RingStepper::from_words(&words).expect("restores");
        assert_eq!(restored.regime(), s.regime());
        assert_eq!(
            restored.slip_direction(),
            s.slip_direction(),
            "σ after the reversal at {}",
            e.time
        );
        let model = Box::new(ring_model(&problem.params).expect("a ring"));
        let options = rotor_rub::method::Options::with_method(Method::Taylor);
        let state = rotor_rub::matrix::MatrixState::full(s.full_state());
        let afresh = MatrixPropagator::new(&*model, s.time(), state, &options).expect("starts");
        if afresh.regime() != s.regime() || afresh.slip() != s.slip_direction() {
            afresh_differs += 1;
        }
        let mut original = s.snapshot();
        for _ in 0..20 {
            let a = original.step_to_switch(1e-2).expect("a step");
            let b = restored.step_to_switch(1e-2).expect("a step");
            let kinds = |r: &rotor_rub::stepper::matrix::MatrixStepReport<8>| {
                r.events.iter().map(|e| e.kind).collect::<Vec<_>>()
            };
            assert_eq!(kinds(&a), kinds(&b), "the same switches after {}", e.time);
            assert!((a.time - b.time).abs() < 1e-8, "{} vs {}", a.time, b.time);
        }
    }
    println!("{reversals} reversals; a fresh start would pick another side at {afresh_differs}");
    assert!(reversals > 0, "the case reverses");
    assert!(
        afresh_differs > 0,
        "the trap the words avoid: deciding the side afresh after a reversal"
    );

    let mut bad = s.to_words();
    let at = bad
        .iter()
        .rposition(|&w| w != 0)
        .expect("the marker is the last word written");
    bad[at - 2] = 7;
    assert!(matches!(
        RingStepper::from_words(&bad),
        Err(StepperError::InvalidConfig {
            what: "ring stepper regime",
            ..
        })
    ));
    let mut bad = s.to_words();
    bad[at - 1] = 0.5f64.to_bits();
    assert!(matches!(
        RingStepper::from_words(&bad),
        Err(StepperError::InvalidConfig {
            what: "ring stepper slip direction",
            ..
        })
    ));
}
