//! Switch location: grazing contacts and starts on the clearance circle.

use rotor_rub::reference::{
    Dop853, Dop853Propagator, Integrator, Interpolant, Rk45Propagator, RotorSystem, SUBDIVISIONS,
    Tolerance, first_crossing_subdivided,
};
use rotor_rub::refine::{Knot, Refinement, refine};
use rotor_rub::{Event, EventKind, Params, Problem, Propagate, Regime, State, advance_to};

use crate::common::{paper, run_events};

/// The first local maximum of z over free flight from `p` (no contact field), up to `end`:
/// (time, z).
fn first_free_maximum(p: &Problem, end: f64) -> Option<(f64, f64)> {
    let sys = RotorSystem {
        params: p.params,
        regime: Regime::Free,
        slip: 0.0,
    };
    let h = |y: &[f64; 4]| switching(&p.params, &State::from_array(*y));
    let mut integ = Integrator::<Dop853, 4>::new(
        &sys,
        p.start_time,
        p.initial.to_array(),
        Tolerance::uniform(1e-13),
        0.05,
    );
    while integ.time() < end {
        let step = integ.step(&sys, end).ok()?;
        let (d0, d1) = (h(&step.y0).1, h(&step.y1).1);
        if d0 > 0.0 && d1 <= 0.0 {
            // The root of h' (falling through 0): the one refinement on −h', secant steps.
            let knot = |t: f64, d: f64| Knot {
                s: t,
                g: -d,
                dg: f64::NAN,
                point: (),
            };
            let settings = Refinement {
                max_steps: 400,
                residual: 0.0,
                scale: 1.0,
                first_guess: None,
                close: false,
            };
            let eval = |t: f64| knot(t, h(&step.dense.eval(t)).1);
            let t = refine(eval, knot(step.t0, d0), knot(step.t1, d1), &settings)
                .best
                .s;
            let z = (h(&step.dense.eval(t)).0 + 1.0).sqrt();
            return Some((t, z));
        }
    }
    None
}

/// A grazing case: the paper preset at η = 1.5 started at rest at the stator centre, with the
/// unbalance scaled so that free flight would reach z = 1 + 1e-5 at its first maximum.
fn grazing_problem() -> (Problem, f64) {
    grazing_problem_depth(1e-5)
}

/// As [`grazing_problem`] with free-flight penetration `depth`, found by bisection on the mass
/// ratio (z_max grows monotonically with it); also returns the time of the free maximum.
fn grazing_problem_depth(depth: f64) -> (Problem, f64) {
    let base = {
        let mut p = paper(1.5);
        p.initial = State::new(p.params.offset_x, p.params.offset_y, 0.0, 0.0);
        p
    };
    let with = |m: f64| {
        let mut p = base;
        p.params.mass_ratio = m;
        p
    };
    let (mut lo, mut hi) = (0.002, 0.004);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let (_, z) = first_free_maximum(&with(mid), 10.0).expect("a maximum");
        if z > 1.0 + depth {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let p = with(hi);
    let (t, _) = first_free_maximum(&p, 10.0).unwrap();
    (p, t)
}

/// The first contact: (entry, exit) times.
fn first_contact<P: Propagate>(prop: &mut P, end: f64) -> Option<(Event, Event)> {
    let ev = run_events(prop, end).ok()?;
    match ev.as_slice() {
        [enter, exit, ..] => Some((*enter, *exit)),
        _ => None,
    }
}

#[test]
fn grazing_contact_is_found_at_every_tolerance() {
    let (p, t_max) = grazing_problem();
    let end = t_max + 0.5;
    // The tightest run (tol 1e-13) is the reference.
    let (enter, exit) =
        first_contact(&mut Dop853Propagator::new(&p, 1e-13).unwrap(), end).expect("contact");
    let duration = exit.time - enter.time;
    println!(
        "grazing: mass ratio {:.9}, contact [{:.9}, {:.9}], duration {duration:.3e}",
        p.params.mass_ratio, enter.time, exit.time
    );
    assert_eq!((enter.kind, exit.kind), (EventKind::Enter, EventKind::Exit));
    assert!(duration > 0.0 && duration < 0.02, "duration {duration}");
    assert!(enter.time < t_max && t_max < exit.time);
    for k in 6..=12 {
        let tol = 10f64.powi(-k);
        let check = |name: &str, found: Option<(Event, Event)>| {
            let (a, b) =
                found.unwrap_or_else(|| panic!("{name} missed the contact at tol {tol:e}"));
            assert_eq!((a.kind, b.kind), (EventKind::Enter, EventKind::Exit));
            println!(
                "{name} tol {tol:e}: entry {:+.2e}, exit {:+.2e}",
                a.time - enter.time,
                b.time - exit.time
            );
            // A state error δ moves a switch by δ/|h'|, and |h'| is small near tangency
            // (≈ 1e-2 here): allow 1e3·tol.
            let slack = 1e3 * tol;
            assert!(
                (a.time - enter.time).abs() < slack,
                "{name} tol {tol:e}: entry {}",
                a.time
            );
            assert!(
                (b.time - exit.time).abs() < slack,
                "{name} tol {tol:e}: exit {}",
                b.time
            );
        };
        check(
            "DOP853",
            first_contact(&mut Dop853Propagator::new(&p, tol).unwrap(), end),
        );
        check(
            "RK45",
            first_contact(&mut Rk45Propagator::new(&p, tol).unwrap(), end),
        );
    }
}

/// A linear "trajectory" y = t on [0, 1] with a switching function that dips below zero only
/// between two of the sample points: found through the minimum, refined to full precision.
#[test]
fn crossing_between_samples_is_found() {
    #[derive(Clone, Copy)]
    struct Line;
    impl Interpolant<1> for Line {
        fn start(&self) -> f64 {
            0.0
        }
        fn end(&self) -> f64 {
            1.0
        }
        fn eval(&self, t: f64) -> [f64; 1] {
            [t]
        }
    }
    let centre = 0.53;
    let depth = 1e-6;
    let g = |y: &[f64; 1]| ((y[0] - centre).powi(2) - depth, 2.0 * (y[0] - centre));
    let t = first_crossing_subdivided(SUBDIVISIONS, &Line, &[0.0], &[1.0], |_, y| g(y))
        .expect("dip found");
    let want = centre - depth.sqrt();
    assert!((t - want).abs() < 1e-15, "{t} vs {want}");
    assert!(
        g(&[t]).0 <= 0.0 && g(&[t]).0.abs() < 1e-17,
        "just past the crossing"
    );
    // A dip that stays positive is not a crossing.
    let g = |y: &[f64; 1]| ((y[0] - centre).powi(2) + depth, 2.0 * (y[0] - centre));
    assert_eq!(
        first_crossing_subdivided(SUBDIVISIONS, &Line, &[0.0], &[1.0], |_, y| g(y)),
        None
    );
    // The start counts as inside even when the function is slightly negative there.
    let g = |y: &[f64; 1]| (y[0] - 1e-12, 1.0);
    assert_eq!(
        first_crossing_subdivided(SUBDIVISIONS, &Line, &[0.0], &[1.0], |_, y| g(y)),
        None
    );
}

/// The paper preset with the stator centre at (0.5, −0.25) (exact in binary) and the rotor on
/// the clearance circle at (1.5, −0.25): z = 1 exactly, with velocity (vx, vy).
fn on_boundary(vx: f64, vy: f64) -> Problem {
    let mut p = paper(1.5);
    p.params.offset_x = 0.5;
    p.params.offset_y = -0.25;
    p.initial = State::new(1.5, -0.25, vx, vy);
    p.start_time = 0.25;
    assert_eq!(switching(&p.params, &p.initial).0, 0.0);
    p
}

fn check_start_on_boundary<P: Propagate>(mut prop: P, params: &Params, want: Regime) {
    let t0 = prop.time();
    assert_eq!(prop.regime(), want);
    assert_eq!(prop.advance(t0), Ok(None));
    // Shortly after the start the rotor is on the side of its regime.
    let s = advance_to(&mut prop, t0 + 1e-3, |e| panic!("zero-length switch {e:?}")).unwrap();
    let (h, _) = switching(params, &s.state);
    match want {
        Regime::Contact | Regime::Rolling => assert!(h > 0.0, "h = {h}"),
        Regime::Free => assert!(h < 0.0, "h = {h}"),
    }
    // The first switch leaves the starting regime, well after the start.
    if let Some(e) = prop.advance(t0 + 10.0).unwrap() {
        let kind = if want == Regime::Contact {
            EventKind::Exit
        } else {
            EventKind::Enter
        };
        assert_eq!(e.kind, kind);
        assert!(e.time > t0 + 1e-3, "switch at {}", e.time);
    }
}

#[test]
fn start_on_boundary_is_decided_by_radial_velocity_then_acceleration() {
    // (vx, vy, regime): outward / inward radial velocity; tangential with z'' > 0 (vy² = 4 beats
    // the inward free acceleration 1.5 − F cos θ0) and z'' < 0.
    let cases = [
        (0.3, 0.2, Regime::Contact),
        (-0.3, 0.2, Regime::Free),
        (0.0, 2.0, Regime::Contact),
        (0.0, 0.1, Regime::Free),
    ];
    for (vx, vy, want) in cases {
        let p = on_boundary(vx, vy);
        check_start_on_boundary(Dop853Propagator::new(&p, 1e-10).unwrap(), &p.params, want);
        check_start_on_boundary(Rk45Propagator::new(&p, 1e-10).unwrap(), &p.params, want);
    }
}

/// Events obey the `Propagate` contract: time() is the event time, a repeated target reports
/// nothing, switches alternate and land on z = 1.
#[test]
fn events_follow_the_propagate_contract() {
    let p = paper(2.5);
    let end = 10.0 * p.params.forcing_period();
    let mut prop = Dop853Propagator::new(&p, 1e-12).unwrap();
    let mut last = p.start_time;
    let mut regime = prop.regime();
    let mut count = 0;
    let mut worst_h: f64 = 0.0;
    while let Some(e) = prop.advance(end).unwrap() {
        assert_eq!(prop.time(), e.time);
        assert_eq!(prop.state(), e.state);
        assert!(e.time > last, "switch times increase strictly");
        assert_eq!(prop.advance(e.time), Ok(None));
        let kind = if regime == Regime::Free {
            EventKind::Enter
        } else {
            EventKind::Exit
        };
        assert_eq!(e.kind, kind);
        regime = e.kind.regime_after();
        assert_eq!(prop.regime(), regime);
        let (h, _) = switching(&p.params, &e.state);
        assert!(h.abs() < 1e-13, "h = {h:e} at the switch state");
        worst_h = worst_h.max(h.abs());
        last = e.time;
        count += 1;
    }
    assert_eq!(prop.time(), end);
    assert!(count > 10);
    println!("{count} switches at tol 1e-12: largest |z² − 1| at a switch state {worst_h:.2e}");
}

/// Sampling is served from the dense output and never changes the step sequence: the switches
/// with dense sampling in between are bit-for-bit those of a run without sampling.
#[test]
fn sampling_does_not_perturb_the_trajectory() {
    let p = paper(1.5);
    let end = 15.0 * p.params.forcing_period();
    let plain = run_events(&mut Dop853Propagator::new(&p, 1e-9).unwrap(), end).unwrap();
    let mut prop = Dop853Propagator::new(&p, 1e-9).unwrap();
    let mut sampled = Vec::new();
    for k in 1..=3000 {
        let t = end * k as f64 / 3000.0;
        advance_to(&mut prop, t, |e| sampled.push(*e)).unwrap();
    }
    assert_eq!(plain, sampled);
    let mut prop = Rk45Propagator::new(&p, 1e-8).unwrap();
    let plain = run_events(&mut prop, end).unwrap();
    let mut prop = Rk45Propagator::new(&p, 1e-8).unwrap();
    let mut sampled = Vec::new();
    for k in 1..=777 {
        advance_to(&mut prop, end * k as f64 / 777.0, |e| sampled.push(*e)).unwrap();
    }
    assert_eq!(plain, sampled);
}

/// A much shallower graze (penetration 1e-8, contact ≈ 4e-4 long) is still found once the
/// tolerance is below the penetration depth (measured: DOP853 from tol 1e-9, RK45 from 1e-8).
#[test]
fn shallow_grazing_is_found_below_its_depth() {
    let (p, t_max) = grazing_problem_depth(1e-8);
    let end = t_max + 0.5;
    let (a, b) = first_contact(&mut Dop853Propagator::new(&p, 1e-13).unwrap(), end).unwrap();
    assert!(b.time - a.time < 1e-3);
    for k in 9..=12 {
        let tol = 10f64.powi(-k);
        assert!(first_contact(&mut Dop853Propagator::new(&p, tol).unwrap(), end).is_some());
        assert!(first_contact(&mut Rk45Propagator::new(&p, tol).unwrap(), end).is_some());
    }
}

/// h = z² − 1 and h' of a state, by hand.
fn switching(p: &rotor_rub::Params, s: &rotor_rub::State) -> (f64, f64) {
    let (u, v) = (s.x - p.offset_x, s.y - p.offset_y);
    (u * u + v * v - 1.0, 2.0 * (u * s.vx + v * s.vy))
}
