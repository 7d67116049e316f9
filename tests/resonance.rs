//! Free flight near resonance (`docs/MODEL.md` §11): every method that uses the closed form —
//! the analytic free segment, free flight through the analytic and hybrid propagators, and the
//! fixed-step stepper — against our DOP853 reference at tol 1e-13, uniformly for
//! ν ∈ [0, 1e-3] and η ∈ [1 − 1e-3, 1 + 1e-3], exact resonance ν = 0, η = 1 included.

use proptest::prelude::*;
use rotor_rub::analytic::free::{FreeConstants, FreeSegment};
use rotor_rub::analytic::segment::Segment;
use rotor_rub::{
    Event, Method, Options, Preset, Problem, Propagate, Propagator, State, Stepper, StepperConfig,
    events,
};

/// Largest component difference.
fn diff(a: State, b: State) -> f64 {
    let (a, b) = (a.to_array(), b.to_array());
    a.iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Events and final state of `method` (tol `tol`, default when `None`) run to `end`.
fn run(problem: &Problem, method: Method, tol: Option<f64>, end: f64) -> (Vec<Event>, State) {
    let options = Options {
        tol,
        ..Options::with_method(method)
    };
    let mut p = Propagator::new(problem, &options).expect("valid problem");
    let found: Vec<Event> = events(&mut p, end).map(|e| e.expect("event")).collect();
    (found, p.state())
}

/// The reference: DOP853 at tol 1e-13.
fn reference(problem: &Problem, end: f64) -> (Vec<Event>, State) {
    run(problem, Method::Dop853, Some(1e-13), end)
}

/// A free flight near resonance that stays inside the clearance: F = 0.01 grows by at most
/// F·s/2 = 0.1 over s = 20 from a start within 0.5 of the rest position.
fn free_problem(nu: f64, eta: f64, start: [f64; 4], phase: f64) -> Problem {
    let mut p = Preset::PaperText.problem();
    p.params.damping_ratio = nu;
    p.params.speed_ratio = eta;
    p.params.eccentricity_ratio = 2.0 / (eta * eta);
    p.params.phase = phase;
    p.initial = State::from_array(start);
    p
}

/// Free-flight duration of the property test.
const SPAN: f64 = 20.0;
/// Stated accuracy of free flight near resonance against the reference (absolute, on states of
/// size ≤ 1; the reference itself is good to ~1e-13 here).
const FREE_TOL: f64 = 1e-11;

fn near_one() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-12.0f64..-3.0, any::<bool>())
            .prop_map(|(e, neg)| if neg { -1.0 } else { 1.0 } * 10f64.powf(e)),
    ]
}

fn damping() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-12.0f64..-3.0).prop_map(|e| 10f64.powf(e)),
        0.0f64..1e-3
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn free_flight_near_resonance_matches_the_reference(
        nu in damping(),
        detune in near_one(),
        start in prop::array::uniform4(-0.3f64..0.3),
        phase in 0.0f64..std::f64::consts::TAU,
        t in 0.5f64..SPAN,
    ) {
        let problem = free_problem(nu, 1.0 + detune, start, phase);
        let (ref_events, expected) = reference(&problem, t);
        prop_assert!(ref_events.is_empty(), "the case is contact-free");
        // The free segment directly.
        let params = problem.params;
        let segment = FreeSegment::new(&params, &FreeConstants::new(&params), 0.0, problem.initial);
        let e = diff(segment.point(t).state, expected);
        prop_assert!(e <= FREE_TOL, "segment: error {e:e} (ν = {nu:e}, η − 1 = {detune:e})");
        // Free flight through the analytic and hybrid propagators.
        for method in [Method::Analytic, Method::Hybrid, Method::Taylor] {
            let (found, end) = run(&problem, method, None, t);
            prop_assert!(found.is_empty());
            let e = diff(end, expected);
            prop_assert!(e <= FREE_TOL, "{method:?}: error {e:e} (ν = {nu:e}, η − 1 = {detune:e})");
        }
        // The stepper: Φ(dt) applied step after step (rounding grows like √steps).
        let dt = t / 200.0;
        let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(dt)).expect("stepper");
        let mut state = problem.initial;
        for _ in 0..200 {
            let r = stepper.step(dt).expect("step");
            prop_assert!(r.events.is_empty());
            state = r.state;
        }
        let e = diff(state, expected);
        prop_assert!(e <= 10.0 * FREE_TOL, "stepper: error {e:e} (ν = {nu:e}, η − 1 = {detune:e})");
    }
}

/// Exact resonance: secular growth, no rejection, no NaN.
#[test]
fn exact_resonance_grows_secularly_and_matches_the_reference() {
    let problem = free_problem(0.0, 1.0, [0.0; 4], 0.0);
    let (_, expected) = reference(&problem, SPAN);
    let params = problem.params;
    let segment = FreeSegment::new(&params, &FreeConstants::new(&params), 0.0, problem.initial);
    let got = segment.point(SPAN).state;
    // x = (F/2)·s·sin s from rest at θ0 = 0.
    let f = params.mass_ratio * params.eccentricity_ratio * params.speed_ratio * params.speed_ratio;
    assert!(
        (got.x - 0.5 * f * SPAN * SPAN.sin()).abs() < 1e-13,
        "{got:?}"
    );
    assert!(diff(got, expected) < FREE_TOL, "{got:?} vs {expected:?}");
}

/// Issue 13's examples for `method`: the same switches as the reference and the final state
/// within `state_tol` of it.
fn regression(method: Method, eta: f64, nu: f64, end: f64, state_tol: f64) {
    let mut problem = Preset::Paper.problem();
    problem.params.speed_ratio = eta;
    problem.params.damping_ratio = nu;
    let (ref_events, expected) = reference(&problem, end);
    let (found, got) = run(&problem, method, None, end);
    assert_eq!(found.len(), ref_events.len(), "{method:?}: switch count");
    for (e, r) in found.iter().zip(&ref_events) {
        assert_eq!(e.kind, r.kind);
        assert!(
            (e.time - r.time).abs() < state_tol,
            "{method:?}: {e:?} vs {r:?}"
        );
    }
    assert!(
        diff(got, expected) < state_tol,
        "{method:?}: {got:?} vs {expected:?}"
    );
}

/// `compare --periods 2 --set speed_ratio=1.000001 --set damping_ratio=0` (before: 44 analytic
/// switches against 8).
const COMPARE_ETA: f64 = 1.000001;

fn compare_end() -> f64 {
    2.0 * std::f64::consts::TAU / COMPARE_ETA
}

/// Hybrid: exact free flight and DOP853 in contact at its default tolerance (1e-9 relative):
/// switch times and final state within 1e-7 of the reference.
#[test]
fn hybrid_matches_the_reference_near_resonance() {
    regression(Method::Hybrid, COMPARE_ETA, 0.0, compare_end(), 1e-7);
    // `simulate --t-end 30 --set speed_ratio=1 --set damping_ratio=1e-9` (before: 6151 hybrid
    // switches against 35).
    regression(Method::Hybrid, 1.0, 1e-9, 30.0, 1e-7);
}

/// Taylor: exact free flight and the generated Taylor integrator in contact at its default
/// tolerance: the same bound as hybrid.
#[test]
fn taylor_matches_the_reference_near_resonance() {
    regression(Method::Taylor, COMPARE_ETA, 0.0, compare_end(), 1e-7);
    regression(Method::Taylor, 1.0, 1e-9, 30.0, 1e-7);
}

/// The analytic method's free flight: the first contact entry (free flight from the start) is
/// located as accurately as by the reference.
#[test]
fn analytic_free_flight_finds_the_first_entry_near_resonance() {
    for (eta, nu) in [(COMPARE_ETA, 0.0), (1.0, 1e-9), (1.0, 0.0)] {
        let mut problem = Preset::Paper.problem();
        problem.params.speed_ratio = eta;
        problem.params.damping_ratio = nu;
        let (reference, _) = reference(&problem, 5.0);
        let mut p = Propagator::new(&problem, &Options::default()).expect("valid problem");
        let first = events(&mut p, 5.0)
            .next()
            .expect("an entry")
            .expect("no error");
        let r = reference.first().expect("an entry");
        assert_eq!(first.kind, r.kind);
        assert!(
            (first.time - r.time).abs() < 1e-10,
            "η = {eta}, ν = {nu:e}: {first:?} vs {r:?}"
        );
        assert!(diff(first.state, r.state) < 1e-9);
    }
}

/// The analytic method over the whole examples, contact included.
#[test]
fn analytic_matches_the_reference_near_resonance() {
    regression(Method::Analytic, COMPARE_ETA, 0.0, compare_end(), 1e-6);
    regression(Method::Analytic, 1.0, 1e-9, 30.0, 1e-6);
    // Exact resonance (ν = 0, η = 1): the linearized contact at z = 1 is exactly resonant.
    regression(Method::Analytic, 1.0, 0.0, 30.0, 1e-6);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The one free-flight bound stays rigorous in the resonance-stable form: on random intervals,
    /// |r − ε|, |r'| and |r''| (central differences of r') at sampled times stay below
    /// `Segment::bounds` (the switch search's proof rests on it).
    #[test]
    fn free_bounds_hold_near_resonance(
        nu in damping(),
        detune in near_one(),
        start in prop::array::uniform4(-0.3f64..0.3),
        phase in 0.0f64..std::f64::consts::TAU,
        offset in prop::array::uniform2(-0.3f64..0.3),
        lo in 0.0f64..30.0,
        len in 1e-3f64..5.0,
    ) {
        let mut problem = free_problem(nu, 1.0 + detune, start, phase);
        problem.params.offset_x = offset[0];
        problem.params.offset_y = offset[1];
        let params = problem.params;
        let segment = FreeSegment::new(&params, &FreeConstants::new(&params), 0.0, problem.initial);
        let b = segment.bounds(lo, lo + len);
        let h = 1e-5;
        for k in 0..=64 {
            let s = lo + len * f64::from(k) / 64.0;
            let st = segment.point(s).state;
            let r = (st.x - offset[0]).hypot(st.y - offset[1]);
            prop_assert!(r <= b.radius, "radius {r} > {}", b.radius);
            prop_assert!(st.vx.hypot(st.vy) <= b.speed, "speed > {}", b.speed);
            let (p, m) = (segment.point(s + h).state, segment.point((s - h).max(0.0)).state);
            let span = s + h - (s - h).max(0.0);
            let accel = ((p.vx - m.vx) / span).hypot((p.vy - m.vy) / span);
            prop_assert!(accel <= b.accel * (1.0 + 1e-6) + 1e-8, "accel {accel} > {}", b.accel);
        }
    }
}
