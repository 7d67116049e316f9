//! The analytic propagator against independent computations: switch continuity and z = 1 over
//! random problems, convergence orders of exprb2 and exprb43, a grazing and a start-on-boundary
//! case with exact events, agreement with DOP853 on the paper's Fig. 2 cases, typed errors.

use proptest::prelude::*;
use rotor_rub::analytic::free::{FreeConstants, FreeSegment};
use rotor_rub::analytic::segment::Segment;
use rotor_rub::analytic::switch::{
    Budget, Direction, EventFunction, Search, first_crossing_to, locate,
};
use rotor_rub::compare::compare_events;
use rotor_rub::{
    ContactScheme, Event, EventKind, Method, Options, Preset, Problem, Propagate, PropagationError,
    Propagator, Regime, State, advance_to, events,
};

fn run(problem: &Problem, options: &Options, periods: f64) -> Result<Vec<Event>, PropagationError> {
    let mut p = Propagator::new(problem, options)?;
    events(&mut p, periods * problem.params.forcing_period()).collect()
}

fn z(problem: &Problem, s: &State) -> f64 {
    (s.x - problem.params.offset_x).hypot(s.y - problem.params.offset_y)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Every switch lies on z = 1, kinds alternate, the state is continuous across it (the new
    /// segment starts from the old one's state: checked by a short step against a Taylor
    /// estimate), and nothing is NaN; failures are typed errors only.
    #[test]
    fn switches_are_continuous_and_on_the_boundary(problem in rotor_rub::strategies::degenerate_problem()) {
        let opts = Options::default();
        let mut p = match Propagator::new(&problem, &opts) {
            Ok(p) => p,
            Err(e) => {
                let expected = matches!(e, PropagationError::Diverged { .. } | PropagationError::SingularContact { .. });
                prop_assert!(expected, "unexpected error {}", e);
                return Ok(());
            }
        };
        let end = 3.0 * problem.params.forcing_period();
        let mut last_kind: Option<EventKind> = None;
        for _ in 0..200 {
            match p.advance(end) {
                Ok(Some(ev)) => {
                    prop_assert!(ev.state.is_finite());
                    prop_assert!((z(&problem, &ev.state) - 1.0).abs() <= 1e-12, "z = {}", z(&problem, &ev.state));
                    if let Some(k) = last_kind { prop_assert_ne!(k, ev.kind); }
                    last_kind = Some(ev.kind);
                    prop_assert_eq!(p.regime(), ev.kind.regime_after());
                    // Continuity: the new segment starts at the switch state. A step of δ = 1e-10
                    // moves it by δ·v + O(δ²) (|O(δ²)| < 1e-18 here), so the new segment's state
                    // at δ against the old state is continuity to 1e-12 relative.
                    let d = 1e-10;
                    let s0 = ev.state;
                    let mut passed = None;
                    match advance_to(&mut p, ev.time + d, |e| passed = Some(e.kind)) {
                        Ok(sample) => {
                            if passed.is_some() {
                                // A contact shorter than δ: its exit was passed on the way.
                                last_kind = passed;
                                continue;
                            }
                            let s1 = sample.state;
                            let scale = 1.0 + s0.x.abs().max(s0.y.abs()).max(s0.vx.abs()).max(s0.vy.abs());
                            prop_assert!((s1.x - s0.x - d * s0.vx).abs() <= 1e-12 * scale);
                            prop_assert!((s1.y - s0.y - d * s0.vy).abs() <= 1e-12 * scale);
                            prop_assert!((s1.vx - s0.vx).abs() <= 1e-12 * scale + 1e-10 * 1e3, "velocity jump");
                            prop_assert!((s1.vy - s0.vy).abs() <= 1e-12 * scale + 1e-10 * 1e3, "velocity jump");
                        }
                        Err(PropagationError::Diverged { .. }) => return Ok(()),
                        Err(e) => prop_assert!(false, "unexpected error {e}"),
                    }
                }
                Ok(None) => break,
                Err(PropagationError::Diverged { .. } | PropagationError::SingularContact { .. }) => break,
                Err(e) => prop_assert!(false, "unexpected error {e}"),
            }
        }
        prop_assert!(p.state().is_finite());
    }
}

/// Start deep in contact; error at τ = 0.2 of fixed-step runs against a fine exprb43 run.
fn fixed_step_error(scheme: ContactScheme, h: f64) -> f64 {
    let mut problem = Preset::Paper.problem();
    problem.params.offset_x = 0.0;
    problem.params.offset_y = 0.0;
    problem.initial = State::new(1.05, 0.0, 0.0, 1.0);
    let end = 0.2;
    let state_at = |scheme, h| {
        let opts = Options {
            contact_scheme: scheme,
            step: Some(h),
            ..Options::default()
        };
        let mut p = Propagator::new(&problem, &opts).unwrap();
        let s = advance_to(&mut p, end, |e| panic!("no switch expected, got {e:?}")).unwrap();
        assert_eq!(s.regime, Regime::Contact);
        s.state
    };
    let reference = state_at(ContactScheme::Exprb43, end / 1024.0);
    let s = state_at(scheme, h);
    (s.x - reference.x)
        .hypot(s.y - reference.y)
        .hypot((s.vx - reference.vx).hypot(s.vy - reference.vy))
}

#[test]
fn exprb2_is_second_order() {
    let (e1, e2) = (
        fixed_step_error(ContactScheme::Exprb2, 0.2 / 32.0),
        fixed_step_error(ContactScheme::Exprb2, 0.2 / 64.0),
    );
    let ratio = e1 / e2;
    assert!(
        (ratio - 4.0).abs() <= 0.6,
        "exprb2 error ratio {ratio} ({e1:e} / {e2:e})"
    );
}

#[test]
fn exprb43_is_fourth_order() {
    let (e1, e2) = (
        fixed_step_error(ContactScheme::Exprb43, 0.2 / 16.0),
        fixed_step_error(ContactScheme::Exprb43, 0.2 / 32.0),
    );
    let ratio = e1 / e2;
    assert!(
        (ratio - 16.0).abs() <= 5.0,
        "exprb43 error ratio {ratio} ({e1:e} / {e2:e})"
    );
}

/// A steady free orbit (a circle of radius R about the origin) that just reaches z = 1 + δ once per
/// period with the stator offset along x: the first entry time is known in closed form.
#[test]
fn grazing_contact_is_found_with_exact_entry() {
    let mut problem = Preset::Paper.problem();
    let p = &mut problem.params;
    let (eta, nu) = (p.speed_ratio, p.damping_ratio);
    let f = p.mass_ratio * p.eccentricity_ratio * p.speed_ratio * p.speed_ratio;
    let d = (1.0 - eta * eta).powi(2) + (2.0 * nu * eta).powi(2);
    let (c11, c22) = (f * (1.0 - eta * eta) / d, 2.0 * nu * eta * f / d);
    let radius = c11.hypot(c22);
    let depth = 1.2e-5;
    let e = 1.0 + depth - radius;
    p.offset_x = e;
    p.offset_y = 0.0;
    problem.initial = State::new(c11, -c22, eta * c22, eta * c11);
    // x_p = R cos(θ − ψ); |r_p − ε|² = R² + e² − 2e x_p > 1 while cos(θ − ψ) < c0,
    // c0 = (R² + e² − 1)/(2eR) ≈ −1: θ − ψ ∈ (arccos c0, 2π − arccos c0).
    let psi = c22.atan2(c11);
    let opening = ((radius * radius + e * e - 1.0) / (2.0 * e * radius)).acos();
    let half_width = std::f64::consts::PI - opening;
    let mut entry = (psi + opening) / eta;
    let period = std::f64::consts::TAU / eta;
    while entry < 0.0 {
        entry += period;
    }
    let exit_rigid = entry + 2.0 * half_width / eta;
    let evs = run(&problem, &Options::default(), 1.2 * entry / period + 0.2).unwrap();
    assert!(evs.len() >= 2, "grazing contact missed: {evs:?}");
    assert_eq!(evs[0].kind, EventKind::Enter);
    assert!(
        (evs[0].time - entry).abs() <= 1e-9,
        "entry {} vs exact {entry}",
        evs[0].time
    );
    assert_eq!(evs[1].kind, EventKind::Exit);
    let duration = evs[1].time - evs[0].time;
    assert!(
        duration > 0.0 && duration < 0.02,
        "contact lasts {duration}"
    );
    // The contact force is tiny (K·δ): the exit is within 1e-5 of the rigid-orbit prediction.
    assert!(
        (evs[1].time - exit_rigid).abs() <= 1e-5,
        "exit {} vs {exit_rigid}",
        evs[1].time
    );
    // DOP853 at a tight tolerance agrees on both switches.
    let reference = run(
        &problem,
        &Options {
            tol: Some(1e-12),
            ..Options::with_method(Method::Dop853)
        },
        1.2 * entry / period + 0.2,
    )
    .unwrap();
    assert!((reference[0].time - evs[0].time).abs() <= 1e-8);
    assert!((reference[1].time - evs[1].time).abs() <= 1e-6);
}

#[test]
fn start_on_boundary_is_decided_by_radial_velocity() {
    let mut problem = Preset::Paper.problem();
    problem.params.offset_x = 0.0;
    problem.params.offset_y = 0.0;
    for (vx, regime, first) in [
        (0.5, Regime::Contact, EventKind::Exit),
        (-0.5, Regime::Free, EventKind::Enter),
    ] {
        problem.initial = State::new(1.0, 0.0, vx, 0.3);
        let mut p = Propagator::new(&problem, &Options::default()).unwrap();
        assert_eq!(p.regime(), regime);
        let ev = p.advance(50.0).unwrap().expect("a switch follows");
        assert_eq!(ev.kind, first);
        assert!(ev.time > 1e-3, "zero-length re-detection at {}", ev.time);
        let reference = run(
            &problem,
            &Options {
                tol: Some(1e-12),
                ..Options::with_method(Method::Dop853)
            },
            50.0 / problem.params.forcing_period(),
        )
        .unwrap();
        assert_eq!(reference[0].kind, first);
        assert!(
            (reference[0].time - ev.time).abs() <= 1e-6,
            "{} vs {}",
            reference[0].time,
            ev.time
        );
    }
}

/// Analytic, hybrid and RK45 vs DOP853 (tol 1e-13) over 20 periods for the six Fig. 2 speeds and
/// both frictionless presets (the friction presets are checked against the friction oracle,
/// `tests/friction`): same kinds,
/// switch times within 1e-6 at default tolerances and 1e-9 at tol = 1e-11 (all switches, or the
/// first 20 for chaotic motion), same counts where the motion is not chaotic.
#[test]
fn methods_agree_on_fig2_cases() {
    // Chaotic per docs/MODEL.md §9: paper preset η = 1.5.
    for preset in [Preset::Paper, Preset::PaperText] {
        for eta in [1.0, 1.5, 2.0, 2.5, 3.0, 3.5] {
            let mut problem = preset.problem();
            problem.params.speed_ratio = eta;
            let chaotic = preset == Preset::Paper && eta == 1.5;
            let reference = run(
                &problem,
                &Options {
                    tol: Some(1e-13),
                    ..Options::with_method(Method::Dop853)
                },
                20.0,
            )
            .unwrap();
            let runs = [
                (Method::Analytic, None, 1e-6),
                (Method::Analytic, Some(1e-11), 1e-9),
                (Method::Hybrid, None, 1e-6),
                (Method::Rk45, None, 1e-6),
            ];
            for (method, tol, bound) in runs {
                let options = Options {
                    tol,
                    ..Options::with_method(method)
                };
                let analytic = run(&problem, &options, 20.0).unwrap();
                let n = if chaotic { 20 } else { reference.len() };
                if !chaotic {
                    assert_eq!(
                        analytic.len(),
                        reference.len(),
                        "{method:?} {preset:?} η={eta} tol={tol:?}: switch counts"
                    );
                }
                let c = compare_events(
                    &analytic[..n.min(analytic.len())],
                    &reference[..n.min(reference.len())],
                    bound,
                );
                assert!(
                    c.agrees(),
                    "{method:?} {preset:?} η={eta} tol={tol:?}: {c:?}"
                );
            }
        }
    }
}

#[test]
fn invalid_inputs_give_typed_errors() {
    let mut problem = Preset::Paper.problem();
    problem.params.damping_ratio = -0.1;
    assert!(matches!(
        Propagator::new(&problem, &Options::default()),
        Err(PropagationError::InvalidProblem(_))
    ));
    problem = Preset::Paper.problem();
    problem.initial.x = f64::NAN;
    assert!(matches!(
        Propagator::new(&problem, &Options::default()),
        Err(PropagationError::InvalidProblem(_))
    ));
    problem = Preset::Paper.problem();
    for tol in [0.0, -1.0, f64::NAN, 2.0] {
        let r = Propagator::new(
            &problem,
            &Options {
                tol: Some(tol),
                ..Options::default()
            },
        );
        assert!(
            matches!(r, Err(PropagationError::InvalidOption { what: "tol", .. })),
            "tol {tol}"
        );
    }
    let r = Propagator::new(
        &problem,
        &Options {
            step: Some(-1.0),
            ..Options::default()
        },
    );
    assert!(matches!(
        r,
        Err(PropagationError::InvalidOption { what: "step", .. })
    ));
    let mut p = Propagator::new(&problem, &Options::default()).unwrap();
    p.advance(1.0).unwrap();
    assert!(matches!(
        p.advance(0.5),
        Err(PropagationError::InvalidTarget { .. })
    ));
    assert!(matches!(
        p.advance(f64::INFINITY),
        Err(PropagationError::InvalidTarget { .. })
    ));
}

/// Contact-sparse motion settles on the non-contact orbit; a million forcing periods then cost
/// nothing and nothing overflows (local time, `docs/MODEL.md` §6 case 12).
#[test]
fn a_million_periods_in_local_time() {
    let mut problem = Preset::Paper.problem();
    problem.params.offset_x = 0.0;
    problem.params.offset_y = 0.0;
    let mut p = Propagator::new(&problem, &Options::default()).unwrap();
    let end = 1e6 * problem.params.forcing_period();
    let n = events(&mut p, end)
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
        .len();
    assert!(n > 0 && n < 100, "{n} switches in the start-up transient");
    let s = p.state();
    assert!(s.is_finite() && p.time() == end);
    assert!(
        (z(&problem, &s) - 0.603).abs() < 0.01,
        "steady free orbit radius {}",
        z(&problem, &s)
    );
}

/// Strong circulatory stiffness (`docs/MODEL.md` §6 case 3): the rotor stays in contact and grows
/// without bound; every method ends with the typed `Diverged` outcome, not NaN or a hang.
#[test]
fn flutter_ends_in_diverged() {
    let mut problem = Preset::Paper.problem();
    problem.params.k_xy = 15.0;
    problem.params.k_yx = -10.0;
    for method in [Method::Analytic, Method::Hybrid, Method::Dop853] {
        let r = run(&problem, &Options::with_method(method), 200.0);
        assert!(
            matches!(r, Err(PropagationError::Diverged { .. })),
            "{method:?}: {r:?}"
        );
    }
}

/// g(s) = A cos(ω(s − peak)) − level on local time, with the exact bound |g''| ≤ Aω² and a
/// count of evaluations: an event function independent of the rotor, with known roots.
struct Cosine {
    amp: f64,
    omega: f64,
    peak: f64,
    level: f64,
    calls: std::cell::Cell<u32>,
}

impl Cosine {
    fn new(amp: f64, omega: f64, peak: f64, level: f64) -> Self {
        let calls = std::cell::Cell::new(0);
        Cosine {
            amp,
            omega,
            peak,
            level,
            calls,
        }
    }

    /// The first root after `lo`: the rising side of the first peak past `lo`.
    fn first_root(&self, lo: f64) -> f64 {
        let period = std::f64::consts::TAU / self.omega;
        let half = (self.level / self.amp).acos() / self.omega;
        let mut p = self.peak;
        while p - half > lo {
            p -= period;
        }
        while p - half <= lo {
            p += period;
        }
        p - half
    }
}

impl EventFunction for Cosine {
    type Point = (f64, f64);
    fn point(&self, s: f64) -> (f64, f64) {
        self.calls.set(self.calls.get() + 1);
        let (sin, cos) = (self.omega * (s - self.peak)).sin_cos();
        (self.amp * cos - self.level, -self.amp * self.omega * sin)
    }
    fn value(&self, p: &(f64, f64)) -> (f64, f64) {
        *p
    }
    fn curvature(&self, _lo: f64, _at: &(f64, f64), _hi: f64) -> f64 {
        self.amp * self.omega * self.omega
    }
}

/// The one switch kernel with any event function: a crossing pair 3e-5 wide whose peak clears
/// 0 by 1e-9 is found first and refined to the exact root, with the analytic method's budget;
/// with the stepper's hard caps it is found the same, or the result is flagged uncertain —
/// never a silent "no crossing".
#[test]
fn the_switch_kernel_finds_a_grazing_crossing_of_any_event_function() {
    for (omega, peak, depth) in [(10.0, 0.7, 1e-9), (37.0, 0.05, 1e-7), (3.0, 0.9, 1e-3)] {
        let f = Cosine::new(1.0, omega, peak, 1.0 - depth);
        let exact = f.first_root(0.0);
        let explore = locate(
            &f,
            0.0,
            f.point(0.0),
            1.0,
            None,
            0.25,
            &Budget::EXPLORE,
            None,
        );
        match explore {
            Search::Found { s, certain, .. } => {
                assert!(certain);
                assert!((s - exact).abs() <= 1e-11, "{s} vs exact {exact}");
            }
            other => panic!("ω {omega}: missed, {other:?}"),
        }
        let capped = locate(
            &f,
            0.0,
            f.point(0.0),
            1.0,
            None,
            0.25,
            &Budget::CAPPED,
            None,
        );
        match capped {
            Search::Found {
                s, certain: true, ..
            } => assert_eq!(s, explore.found().unwrap().0),
            Search::Found { certain: false, .. } | Search::Unresolved => {}
            Search::None => panic!("ω {omega}: the capped search claims no crossing"),
        }
    }
    // A peak that stays below 0 by 1e-9: proved free.
    let f = Cosine::new(1.0, 10.0, 0.7, 1.0 + 1e-9);
    let r = locate(
        &f,
        0.0,
        f.point(0.0),
        1.0,
        None,
        0.25,
        &Budget::EXPLORE,
        None,
    );
    assert_eq!(r, Search::None);
}

/// g within rounding of 0 on a whole interval (a trajectory sliding on z = 1) with a loose
/// curvature bound: the bound can never prove the interval free, and the search stops at its
/// budget, flagged, after at most `tests` + 1 evaluations (the work that once grew like 2^depth).
#[test]
fn the_switch_kernel_work_is_bounded_when_sliding() {
    struct Sliding(std::cell::Cell<u32>);
    impl EventFunction for Sliding {
        type Point = (f64, f64);
        fn point(&self, _s: f64) -> (f64, f64) {
            self.0.set(self.0.get() + 1);
            (-1e-17, 0.0)
        }
        fn value(&self, p: &(f64, f64)) -> (f64, f64) {
            *p
        }
        fn curvature(&self, _lo: f64, _at: &(f64, f64), _hi: f64) -> f64 {
            1.0
        }
    }
    for budget in [Budget::EXPLORE, Budget::CAPPED] {
        let f = Sliding(std::cell::Cell::new(0));
        let r = locate(&f, 0.0, (-1e-17, 0.0), 1.0, None, 1.0, &budget, None);
        assert_eq!(r, Search::Unresolved);
        let calls = f.0.get();
        assert!(calls <= budget.tests + 1, "{calls} evaluations");
    }
}

/// The analytic method and the stepper search with the same kernel: on the same free segment
/// and span, both return the same entry, bit for bit, and it is the propagator's entry.
#[test]
fn the_analytic_method_and_the_stepper_share_the_switch_kernel() {
    let problem = Preset::Paper.problem();
    let mut p = Propagator::new(&problem, &Options::default()).unwrap();
    let entry = p.advance(50.0).unwrap().expect("an entry");
    assert_eq!(entry.kind, EventKind::Enter);
    let params = &problem.params;
    let seg = FreeSegment::new(params, &FreeConstants::new(params), 0.0, problem.initial);
    let (lo, hi) = (entry.time - 0.05, entry.time + 0.03);
    let (a, b) = (seg.point(lo), seg.point(hi));
    let analytic = first_crossing_to(&seg, lo, a, hi, b, Direction::Up).expect("found");
    let stepper = rotor_rub::stepper::locate(&seg, (lo, a), (hi, b), Direction::Up, hi - lo);
    let Search::Found { s, point, certain } = stepper else {
        panic!("{stepper:?}")
    };
    assert!(certain);
    assert_eq!((s, point), analytic);
    assert!((s - entry.time).abs() <= 1e-12, "{s} vs {}", entry.time);
}

/// A tangential start on z = 1 (z' = 0 up to rounding) takes the regime z'' points into, not
/// the one the rounding of z' happens to point into — in `field::regime_of`, the stepper and the
/// event-driven propagators — and no zero-length regime follows the start (`docs/MODEL.md` §6
/// case 14). z'' is computed here from the free equations of motion.
#[test]
fn tangential_start_on_boundary_takes_the_regime_of_its_curvature() {
    let mut problem = Preset::Paper.problem();
    (problem.params.offset_x, problem.params.offset_y) = (-0.16036198459594503, 0.0);
    let q = problem.params;
    let (f, nu) = (
        (q.mass_ratio * q.eccentricity_ratio * q.speed_ratio * q.speed_ratio),
        q.damping_ratio,
    );
    let mut disagreed = 0;
    for i in 0..256 {
        let (s, c) = (f64::from(i) * std::f64::consts::TAU / 256.0 + 0.01).sin_cos();
        let speed = 0.2 + 1.5 * f64::from(i % 7) / 7.0;
        let x = State::new(q.offset_x + c, q.offset_y + s, -speed * s, speed * c);
        problem.initial = x;
        // h''/2 = |r'|² + (r − ε)·r'' with the free r'' = −2ν r' − r + F(cos φ, sin φ).
        let (ct, st) = (q.phase.cos(), q.phase.sin());
        let (ax, ay) = (
            -2.0 * nu * x.vx - x.x + f * ct,
            -2.0 * nu * x.vy - x.y + f * st,
        );
        let (u, v) = (x.x - q.offset_x, x.y - q.offset_y);
        let curvature = x.vx * x.vx + x.vy * x.vy + u * ax + v * ay;
        let expected = if curvature > 0.0 {
            Regime::Contact
        } else {
            Regime::Free
        };
        let radial = u * x.vx + v * x.vy;
        disagreed += usize::from((radial > 0.0) != (curvature > 0.0) && radial != 0.0);
        assert_eq!(
            rotor_rub::field::regime_of(&q, 0.0, &x),
            expected,
            "start {i}: z' = {radial:e}"
        );
        let stepper = rotor_rub::Stepper::new(&problem, Default::default()).unwrap();
        assert_eq!(stepper.regime(), expected, "stepper, start {i}");
        let mut p = Propagator::new(&problem, &Options::default()).unwrap();
        assert_eq!(p.regime(), expected, "start {i}: z' = {radial:e}");
        if let Some(ev) = p.advance(5.0).unwrap() {
            assert!(ev.time > 1e-6, "start {i}: {:?} at {}", ev.kind, ev.time);
        }
    }
    // The rounding of z' pointed the other way for some of the starts.
    assert!(disagreed > 0);
}
