//! The piecewise driver and the method registry: names come from the registry, options out of
//! range are typed errors naming the value and the range, and a start on z = 1 never gives a
//! zero-length segment, for every method.

use rotor_rub::method::{STEP_RANGE, ValidRange};
use rotor_rub::{
    ContactScheme, Event, EventKind, Method, Options, Preset, Problem, PropagationError,
    Propagator, State, events,
};

#[test]
fn the_registry_drives_names_and_defaults() {
    assert_eq!(
        Method::ALL.iter().map(|m| m.name()).collect::<Vec<_>>(),
        ["analytic", "hybrid", "taylor", "dop853", "rk45"]
    );
    for &m in Method::ALL {
        assert_eq!(Method::from_name(m.name()), Some(m));
        assert!(!m.description().is_empty());
        let range = m.tolerance_range();
        assert!(range.min > 0.0 && range.min < range.max, "{m:?}");
        assert!(range.contains(m.default_tolerance()), "{m:?}");
        assert_eq!(Options::with_method(m).tolerance(), m.default_tolerance());
    }
    assert_eq!(Method::from_name("dopri5"), None);
    for s in ContactScheme::ALL {
        assert_eq!(ContactScheme::from_name(s.name()), Some(s));
        assert_eq!(ContactScheme::from_code(s.code()), Some(s));
    }
}

fn is_out_of_range(e: PropagationError, what: &str, value: f64, valid: ValidRange) -> bool {
    let message = e.to_string();
    match e {
        PropagationError::InvalidOption {
            what: w,
            value: v,
            valid: r,
            ..
        } => {
            w == what
                && (v == value || (v.is_nan() && value.is_nan()))
                && r == valid
                && message.contains(&format!("{value:e}"))
                && message.contains(&format!("{:e}", valid.min))
                && message.contains(&format!("{:e}", valid.max))
        }
        _ => false,
    }
}

#[test]
fn tolerances_out_of_range_are_typed_errors_for_every_method() {
    let problem = Preset::Paper.problem();
    for &m in Method::ALL {
        let valid = m.tolerance_range();
        for tol in [
            0.0,
            -1e-8,
            valid.min * 0.5,
            valid.max * 2.0,
            10.0,
            1e300,
            f64::NAN,
            f64::INFINITY,
        ] {
            let options = Options {
                tol: Some(tol),
                ..Options::with_method(m)
            };
            let e = Propagator::new(&problem, &options).err();
            assert!(
                e.is_some_and(|e| is_out_of_range(e, "tol", tol, valid)),
                "{m:?} tol {tol:e}: {e:?}"
            );
        }
        for tol in [valid.min, valid.max] {
            let options = Options {
                tol: Some(tol),
                ..Options::with_method(m)
            };
            assert!(Propagator::new(&problem, &options).is_ok(), "{m:?} {tol:e}");
        }
    }
}

#[test]
fn fixed_steps_out_of_range_are_typed_errors_for_both_schemes() {
    let problem = Preset::Paper.problem();
    for scheme in ContactScheme::ALL {
        for step in [
            1e-300,
            0.5 * STEP_RANGE.min,
            2.0 * STEP_RANGE.max,
            1e300,
            -1e-3,
            f64::NAN,
        ] {
            let options = Options {
                contact_scheme: scheme,
                step: Some(step),
                ..Options::default()
            };
            let e = Propagator::new(&problem, &options).err();
            assert!(
                e.is_some_and(|e| is_out_of_range(e, "step", step, STEP_RANGE)),
                "{scheme:?} step {step:e}: {e:?}"
            );
        }
        for step in [STEP_RANGE.min, STEP_RANGE.max] {
            let options = Options {
                contact_scheme: scheme,
                step: Some(step),
                ..Options::default()
            };
            assert!(Propagator::new(&problem, &options).is_ok());
        }
    }
}

/// Every method at its default settings, exprb2 besides.
fn all_methods() -> Vec<Options> {
    let mut v: Vec<Options> = Method::ALL
        .iter()
        .map(|&m| Options::with_method(m))
        .collect();
    v.push(Options {
        contact_scheme: ContactScheme::Exprb2,
        ..Options::default()
    });
    v
}

/// A start on z = 1 at angle `a` around the stator centre, with radial and tangential speeds.
fn on_boundary(a: f64, radial: f64, tangential: f64) -> Problem {
    let mut p = Preset::Paper.problem();
    let (u, v) = (a.cos(), a.sin());
    p.initial = State {
        x: p.params.offset_x + u,
        y: p.params.offset_y + v,
        vx: radial * u - tangential * v,
        vy: radial * v + tangential * u,
    };
    p
}

fn run(problem: &Problem, options: &Options, end: f64) -> Vec<Event> {
    let mut p = Propagator::new(problem, options).unwrap();
    events(&mut p, end).map(Result::unwrap).collect()
}

#[test]
fn a_start_on_the_boundary_gives_no_zero_length_segment() {
    let reference = Options {
        tol: Some(1e-13),
        ..Options::with_method(Method::Dop853)
    };
    let mut cases = 0;
    for a in [0.3, 1.0, 2.0, 4.0, 5.5] {
        for radial in [1e-12, 1e-15, 0.0, -1e-15, -1e-12] {
            for tangential in [0.0, 0.5, -2.0] {
                let problem = on_boundary(a, radial, tangential);
                let end = 3.0;
                let want = run(&problem, &reference, end);
                for options in all_methods() {
                    let got = run(&problem, &options, end);
                    let mut last = problem.start_time;
                    for e in &got {
                        assert!(
                            e.time - last > 1e-6,
                            "a = {a}, radial {radial:e}, tangential {tangential}, {options:?}: \
                             switch at {:e} after {last:e}: {got:?}",
                            e.time
                        );
                        last = e.time;
                    }
                    // The first real switch is the reference's (DOP853 at tol 1e-13).
                    if let (Some(g), Some(w)) = (got.first(), want.first()) {
                        assert_eq!(g.kind, w.kind, "a = {a}, {radial:e}, {tangential}");
                        assert!(
                            (g.time - w.time).abs() < 1e-4,
                            "a = {a}, {radial:e}, {tangential}, {options:?}: {} vs {}",
                            g.time,
                            w.time
                        );
                    }
                    cases += 1;
                }
            }
        }
    }
    assert_eq!(cases, 5 * 5 * 3 * 6);
}

/// Before the fix, these starts reported an exit (or an enter) within 1e-12 of the start.
#[test]
fn the_touch_examples_report_no_switch_at_the_start() {
    for (a, radial, tangential) in [(0.3, 1e-9, 0.0), (4.0, 1e-9, 0.0), (1.0, 0.0, 0.0)] {
        let problem = on_boundary(a, radial, tangential);
        for options in all_methods() {
            let got = run(&problem, &options, 1.0);
            assert!(
                got.first().is_none_or(|e| e.time > 1e-6),
                "{options:?}: {got:?}"
            );
            assert!(
                got.iter()
                    .all(|e| matches!(e.kind, EventKind::Enter | EventKind::Exit))
            );
        }
    }
}
