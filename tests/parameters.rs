//! The parameter table (`rotor_rub::Parameter`): access by name lands in the right field,
//! validation follows each range exactly with messages naming value and range, and runs at the
//! corners of the valid ranges agree with DOP853 at tol 1e-13 (issue 13 point 8).

use rotor_rub::{
    Method, Options, ParamError, Parameter, Params, Preset, Problem, Propagator, State, Stepper,
    StepperConfig, advance_to,
};

/// Each parameter's place in the structs, written out independently of the table's macro.
fn slot<'a>(p: &'a mut Problem, name: &str) -> &'a mut f64 {
    let q = &mut p.params;
    match name {
        "speed_ratio" => &mut q.speed_ratio,
        "damping_ratio" => &mut q.damping_ratio,
        "mass_ratio" => &mut q.mass_ratio,
        "eccentricity_ratio" => &mut q.eccentricity_ratio,
        "phase" => &mut q.phase,
        "k_xx" => &mut q.k_xx,
        "k_xy" => &mut q.k_xy,
        "k_yx" => &mut q.k_yx,
        "k_yy" => &mut q.k_yy,
        "offset_x" => &mut q.offset_x,
        "offset_y" => &mut q.offset_y,
        "friction_coefficient" => &mut q.friction_coefficient,
        "radius_ratio" => &mut q.radius_ratio,
        "force_x" => &mut q.force_x,
        "force_y" => &mut q.force_y,
        "stator_mass_ratio" => &mut q.stator_mass_ratio,
        "contact_stiffness" => &mut q.contact_stiffness,
        "stator_damping" => &mut q.stator_damping,
        "xs0" => &mut q.xs0,
        "ys0" => &mut q.ys0,
        "vxs0" => &mut q.vxs0,
        "vys0" => &mut q.vys0,
        "x0" => &mut p.initial.x,
        "y0" => &mut p.initial.y,
        "vx0" => &mut p.initial.vx,
        "vy0" => &mut p.initial.vy,
        "start_time" => &mut p.start_time,
        other => panic!("unexpected parameter {other}"),
    }
}

#[test]
fn access_by_name_reaches_the_named_field() {
    assert_eq!(Parameter::COUNT, 27);
    assert_eq!(Parameter::MODEL_COUNT, 22);
    for (i, p) in Parameter::ALL.into_iter().enumerate() {
        assert_eq!(Parameter::from_name(p.name()), Some(p));
        assert_eq!(p.is_model(), i < Parameter::MODEL_COUNT, "{p}");
        let mut problem = Preset::Paper.problem();
        let value = 0.25 + i as f64;
        p.set(&mut problem, value);
        assert_eq!(*slot(&mut problem, p.name()), value, "{p}");
        assert_eq!(p.get(&problem), value, "{p}");
        // Nothing else moved.
        for other in Parameter::ALL.into_iter().filter(|&o| o != p) {
            assert_eq!(other.get(&problem), other.get(&Preset::Paper.problem()));
        }
    }
    assert_eq!(Parameter::from_name("omega"), None);
}

#[test]
fn defaults_are_the_paper_preset_and_lie_in_their_ranges() {
    let paper = Preset::Paper.problem();
    assert_eq!(paper.params, Params::DEFAULT);
    assert_eq!(paper.initial, State::new(0.1, 0.1, 0.0, 0.0));
    for p in Parameter::ALL {
        let info = p.info();
        assert_eq!(p.get(&paper), info.default, "{p}");
        assert!(info.range.contains(info.default), "{p}");
        assert!(!info.doc.is_empty() && !info.symbol.is_empty());
    }
    let text = Preset::PaperText.problem();
    assert_eq!(
        (text.params.k_xx, text.params.k_xy, text.params.k_yx),
        (2.0, 2.0, 2.0)
    );
    assert_eq!((text.params.offset_x, text.params.offset_y), (0.0, 0.0));
    for preset in Preset::ALL {
        assert_eq!(preset.problem().validate(), Ok(()));
    }
}

/// The entries of the stator ring with mass, valid only with `stator_mass_ratio` > 0.
const RING: [Parameter; 6] = [
    Parameter::ContactStiffness,
    Parameter::StatorDamping,
    Parameter::Xs0,
    Parameter::Ys0,
    Parameter::Vxs0,
    Parameter::Vys0,
];

#[test]
fn ring_entries_without_ring_mass_are_refused() {
    for p in RING {
        let mut problem = Preset::Paper.problem();
        p.set(&mut problem, 0.5);
        let e = problem.validate().unwrap_err();
        assert_eq!(
            e,
            ParamError::RingWithoutMass {
                parameter: p,
                value: 0.5
            }
        );
        let message = e.to_string();
        assert!(
            message.starts_with(&format!(
                "{p} = 0.5 has no effect while stator_mass_ratio = 0"
            )),
            "{message}"
        );
        problem.params.stator_mass_ratio = 1.0;
        assert_eq!(problem.validate(), Ok(()), "{p}");
    }
}

#[test]
fn validation_follows_each_range_at_its_ends() {
    for p in Parameter::ALL {
        let range = p.info().range;
        let with = |value: f64| {
            let mut problem = Preset::Paper.problem();
            // The ring's own entries take effect only with a ring mass (`RingWithoutMass`).
            if RING.contains(&p) {
                problem.params.stator_mass_ratio = 1.0;
            }
            p.set(&mut problem, value);
            problem
        };
        let below = if range.min_open {
            range.min
        } else {
            range.min.next_down()
        };
        for bad in [below, range.max.next_up(), f64::NAN, f64::INFINITY] {
            let e = with(bad).validate().unwrap_err();
            assert_eq!(e.parameter(), Some(p), "{p} = {bad}");
            let message = e.to_string();
            assert!(message.starts_with(&format!("{p} = ")), "{message}");
            if bad.is_finite() {
                assert!(
                    matches!(e, ParamError::OutOfRange { value, .. } if value == bad),
                    "{e:?}"
                );
                assert!(message.contains(&range.to_string()), "{message}");
            } else {
                assert!(matches!(e, ParamError::NonFinite { .. }), "{e:?}");
            }
        }
        let lowest = if range.min_open {
            range.min.next_up()
        } else {
            range.min
        };
        for good in [lowest, range.max] {
            let problem = with(good);
            let ok = problem.validate();
            assert_eq!(ok, Ok(()), "{p} = {good}");
            if p.is_model() {
                assert_eq!(problem.params.validate(), ok, "{p} = {good}");
            }
        }
    }
    // The reported examples of issue 13: rejected up front, not run.
    let mut tiny = Preset::Paper.problem();
    tiny.params.speed_ratio = 5e-324;
    assert!(tiny.validate().unwrap_err().to_string().contains("5e-324"));
    let mut far = Preset::Paper.problem();
    far.initial.x = 1e4;
    assert!(matches!(
        far.validate(),
        Err(ParamError::OutOfRange {
            parameter: Parameter::X0,
            ..
        })
    ));
    let mut resonant = Preset::Paper.problem();
    (resonant.params.damping_ratio, resonant.params.speed_ratio) = (0.0, 1.0);
    // Exact undamped resonance is valid (its free flight grows secularly, docs/MODEL.md §11).
    assert_eq!(resonant.validate(), Ok(()));
}

/// The stepper's mid-run parameter change checks only the model parameters: a state or time
/// outside the start ranges (reached by running) does not block it.
#[test]
fn stepper_parameter_change_ignores_start_ranges() {
    let mut problem = Preset::Paper.problem();
    problem.start_time = 1e6;
    let mut stepper = Stepper::new(&problem, StepperConfig::default()).unwrap();
    for _ in 0..10 {
        stepper.step(1e-3).unwrap();
    }
    assert!(stepper.time() > 1e6);
    let mut params = problem.params;
    params.speed_ratio = 2.0;
    assert_eq!(stepper.set_params(&params), Ok(()));
    params.speed_ratio = 1e3;
    assert!(stepper.set_params(&params).is_err());
}

/// Problems at the corners of the valid ranges.
fn corners() -> Vec<(&'static str, Problem)> {
    let base = Preset::Paper.problem();
    let with = |values: &[(Parameter, f64)]| {
        let mut p = base;
        for &(parameter, value) in values {
            parameter.set(&mut p, value);
        }
        p
    };
    use Parameter::*;
    vec![
        ("slowest speed", with(&[(SpeedRatio, 1e-3), (X0, 1.2)])),
        ("fastest speed", with(&[(SpeedRatio, 100.0)])),
        (
            "heaviest damping",
            with(&[(DampingRatio, 10.0), (X0, 1.5), (Vy0, 20.0)]),
        ),
        (
            "no damping",
            with(&[(DampingRatio, 0.0), (SpeedRatio, 2.0)]),
        ),
        (
            "stiffest stator",
            with(&[(KXx, 1e5), (KXy, 0.0), (KYx, 0.0), (KYy, 1e5), (Vx0, 3.0)]),
        ),
        (
            "soft stator",
            with(&[(KXx, 0.0), (KXy, 0.0), (KYx, 0.0), (KYy, 0.0), (X0, 3.0)]),
        ),
        (
            "largest unbalance",
            with(&[
                (MassRatio, 1.0),
                (EccentricityRatio, 1e3),
                (SpeedRatio, 3.0),
            ]),
        ),
        (
            "stiffest stator, farthest start",
            with(&[
                (KXx, 1e5),
                (KXy, 1e5),
                (KYx, 1e5),
                (KYy, 1e5),
                (X0, 100.0),
                (Y0, 100.0),
            ]),
        ),
        ("farthest start", with(&[(X0, 100.0), (Y0, -100.0)])),
        ("fastest start", with(&[(Vx0, 100.0), (Vy0, -100.0)])),
        ("largest offset", with(&[(OffsetX, 10.0), (OffsetY, -10.0)])),
        (
            "largest phase and start time",
            with(&[(Phase, 1e3), (StartTime, 1e6)]),
        ),
    ]
}

fn run(problem: &Problem, options: &Options, end: f64) -> (Vec<f64>, State) {
    let mut propagator = Propagator::new(problem, options).unwrap();
    let mut switches = Vec::new();
    let sample = advance_to(&mut propagator, end, |e| switches.push(e.time))
        .unwrap_or_else(|e| panic!("{e}"));
    (switches, sample.state)
}

fn relative(a: State, b: State) -> f64 {
    let scale = b.to_array().iter().fold(1.0f64, |m, v| m.max(v.abs()));
    a.to_array()
        .iter()
        .zip(b.to_array())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// Every corner gives the same switches as DOP853 at tol 1e-13 over 5 time units, times within
/// 1e-6 and end state within 1e-5 relative. Measured: ≤ 1.4e-9 everywhere except the stiffest
/// singular stator with the farthest start (1188 switches: 3.0e-7 analytic, 1.3e-6 hybrid).
#[test]
fn corners_of_the_ranges_agree_with_dop853() {
    let reference = Options {
        tol: Some(1e-13),
        ..Options::with_method(Method::Dop853)
    };
    for (name, problem) in corners() {
        assert_eq!(problem.validate(), Ok(()), "{name}");
        let end = problem.start_time + 5.0;
        let (ref_switches, ref_state) = run(&problem, &reference, end);
        for method in [Method::Analytic, Method::Hybrid] {
            let (switches, state) = run(&problem, &Options::with_method(method), end);
            assert_eq!(switches.len(), ref_switches.len(), "{name} {method:?}");
            let worst_time = switches
                .iter()
                .zip(&ref_switches)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            let worst_state = relative(state, ref_state);
            assert!(
                worst_time <= 1e-6 && worst_state <= 1e-5,
                "{name} {method:?}: switch times {worst_time:e}, state {worst_state:e}"
            );
        }
    }
}
