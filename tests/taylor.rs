//! The `taylor` method (`docs/MODEL.md` §16): the generated recurrences against the field they
//! come from (coefficients 1 and 2 against the field and a finite difference of it, the
//! convergence order against a fine RK4 integration of the field), the switch search on grazing
//! contacts and starts on z = 1 against DOP853 at tol 1e-13, continuity at switches, and switch
//! times against a 30-digit reference where one is checked in.

use proptest::prelude::*;
use rotor_rub::coefficients::ModelParams;
use rotor_rub::field;
use rotor_rub::taylor::expansion::Expansion;
use rotor_rub::{
    Event, EventKind, Method, Options, Params, Preset, Problem, Propagator, Regime, State, events,
};

fn phasor(p: &Params, t: f64) -> (f64, f64) {
    let th = p.speed_ratio * t + p.phase;
    (th.cos(), th.sin())
}

/// A contact state: radius `z` > 1 at angle `a` around the stator centre, velocity (vx, vy).
fn contact_state(p: &Params, z: f64, a: f64, vx: f64, vy: f64) -> State {
    State::new(p.offset_x + z * a.cos(), p.offset_y + z * a.sin(), vx, vy)
}

fn f(p: &Params, regime: Regime, slip: f64, t: f64, s: &State) -> State {
    field::derivative(p, regime, slip, t, s)
}

fn axpy(s: &State, h: f64, d: &State) -> State {
    State::new(
        s.x + h * d.x,
        s.y + h * d.y,
        s.vx + h * d.vx,
        s.vy + h * d.vy,
    )
}

/// Classical RK4 on the field, `n` steps to `t0 + h`.
fn rk4(p: &Params, regime: Regime, slip: f64, t0: f64, s0: State, h: f64, n: usize) -> State {
    let dt = h / n as f64;
    let mut s = s0;
    for i in 0..n {
        let t = t0 + i as f64 * dt;
        let k1 = f(p, regime, slip, t, &s);
        let k2 = f(p, regime, slip, t + dt / 2.0, &axpy(&s, dt / 2.0, &k1));
        let k3 = f(p, regime, slip, t + dt / 2.0, &axpy(&s, dt / 2.0, &k2));
        let k4 = f(p, regime, slip, t + dt, &axpy(&s, dt, &k3));
        s = State::new(
            s.x + dt / 6.0 * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x),
            s.y + dt / 6.0 * (k1.y + 2.0 * k2.y + 2.0 * k3.y + k4.y),
            s.vx + dt / 6.0 * (k1.vx + 2.0 * k2.vx + 2.0 * k3.vx + k4.vx),
            s.vy + dt / 6.0 * (k1.vy + 2.0 * k2.vy + 2.0 * k3.vy + k4.vy),
        );
    }
    s
}

fn diff(a: &State, b: &State) -> f64 {
    [a.x - b.x, a.y - b.y, a.vx - b.vx, a.vy - b.vy]
        .iter()
        .fold(0.0, |m, d| m.max(d.abs()))
}

/// The regimes with their parameters: frictionless (paper), slipping both ways and rolling
/// (the friction preset's μ and ρ_R).
fn regimes() -> Vec<(Params, Regime, f64)> {
    let paper = Preset::Paper.problem().params;
    let friction = Preset::Friction.problem().params;
    vec![
        (paper, Regime::Contact, 0.0),
        (friction, Regime::Contact, 1.0),
        (friction, Regime::Contact, -1.0),
        (friction, Regime::Rolling, 0.0),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Coefficient 1 is the field, 2·coefficient 2 its time derivative along the flow (central
    /// difference of the field over RK4 half-steps, error O(δ²)).
    #[test]
    fn coefficients_are_the_field_and_its_rate(
        z in 1.001f64..1.2, a in 0.0f64..6.3, vx in -3.0f64..3.0, vy in -3.0f64..3.0,
        t in 0.0f64..10.0,
    ) {
        for (p, regime, slip) in regimes() {
            let s = contact_state(&p, z, a, vx, vy);
            let mut e = Expansion::new(&ModelParams::of(&p), 6);
            e.set_regime(&ModelParams::of(&p), regime, slip);
            e.expand(&s, phasor(&p, t));
            let d = f(&p, regime, slip, t, &s);
            // Coefficient 1: the derivative of the polynomial at 0.
            let h = 1e-7;
            let c1 = {
                let (a, b) = (e.state_at(h), e.state_at(-h));
                State::new((a.x - b.x) / (2.0 * h), (a.y - b.y) / (2.0 * h),
                    (a.vx - b.vx) / (2.0 * h), (a.vy - b.vy) / (2.0 * h))
            };
            let scale = 1.0 + d.vx.abs().max(d.vy.abs());
            prop_assert!(diff(&c1, &d) <= 1e-6 * scale, "{regime:?} σ {slip}: {c1:?} vs {d:?}");
            // The acceleration's rate: central difference along the flow.
            let delta = 1e-4;
            let ahead = rk4(&p, regime, slip, t, s, delta, 4);
            let behind = rk4(&p, regime, slip, t, s, -delta, 4);
            let (fa, fb) = (f(&p, regime, slip, t + delta, &ahead), f(&p, regime, slip, t - delta, &behind));
            let rate = ((fa.vx - fb.vx) / (2.0 * delta), (fa.vy - fb.vy) / (2.0 * delta));
            // 2·c2 of the velocity: the polynomial's second difference of the velocity.
            let g = 1e-4;
            let (vp, v0, vm) = (e.state_at(g), e.state_at(0.0), e.state_at(-g));
            let poly_rate = (
                (vp.vx - 2.0 * v0.vx + vm.vx) / (g * g),
                (vp.vy - 2.0 * v0.vy + vm.vy) / (g * g),
            );
            let scale = 1.0 + rate.0.abs().max(rate.1.abs());
            prop_assert!((poly_rate.0 - rate.0).abs() <= 1e-5 * scale
                && (poly_rate.1 - rate.1).abs() <= 1e-5 * scale,
                "{regime:?} σ {slip}: {poly_rate:?} vs {rate:?}");
        }
    }
}

/// Order p of the truncated series: the error against a fine RK4 integration falls like
/// h^{p+1} (halving the step divides it by about 2^{p+1}).
#[test]
fn the_series_converges_at_its_order() {
    for (p, regime, slip) in regimes() {
        let s = contact_state(&p, 1.05, 0.7, 1.5, -0.8);
        let t = 0.4;
        for order in [3usize, 4, 5, 6] {
            let mut e = Expansion::new(&ModelParams::of(&p), order);
            e.set_regime(&ModelParams::of(&p), regime, slip);
            e.expand(&s, phasor(&p, t));
            let err = |h: f64| diff(&e.state_at(h), &rk4(&p, regime, slip, t, s, h, 400));
            let (e1, e2) = (err(0.04), err(0.02));
            let observed = (e1 / e2).log2();
            let expected = (order + 1) as f64;
            eprintln!(
                "{regime:?} σ {slip} order {order}: errors {e1:.2e}, {e2:.2e}, observed order {observed:.2}"
            );
            assert!(
                (observed - expected).abs() < 0.6,
                "{regime:?} σ {slip} order {order}: errors {e1:e}, {e2:e}, observed order {observed:.2}"
            );
        }
    }
}

fn run(problem: &Problem, method: Method, tol: f64, end: f64) -> (Vec<Event>, State) {
    let options = Options {
        tol: Some(tol),
        ..Options::with_method(method)
    };
    let mut p = Propagator::new(problem, &options).unwrap();
    let evs: Vec<Event> = events(&mut p, end).map(Result::unwrap).collect();
    let last = rotor_rub::advance_to(&mut p, end, |_| {}).unwrap();
    (evs, last.state)
}

fn same_switches(label: &str, got: &[Event], want: &[Event], bound: f64) {
    assert_eq!(
        got.iter().map(|e| e.kind).collect::<Vec<_>>(),
        want.iter().map(|e| e.kind).collect::<Vec<_>>(),
        "{label}: switch kinds"
    );
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g.time - w.time).abs() <= bound,
            "{label}: switch at {} vs {} ({:e})",
            g.time,
            w.time,
            (g.time - w.time).abs()
        );
    }
}

/// The contact-heavy case over 20 forcing periods: the switches of DOP853 at tol 1e-13, to
/// 1e-10 at taylor's tol 1e-13 and to 1e-8 at its default.
#[test]
fn matches_dop853_on_the_contact_heavy_case() {
    let mut problem = Preset::Paper.problem();
    problem.params.speed_ratio = 2.5;
    let end = 20.0 * problem.params.forcing_period();
    let (want, want_end) = run(&problem, Method::Dop853, 1e-13, end);
    assert!(want.len() > 50);
    for (tol, bound) in [(1e-13, 1e-10), (1e-10, 1e-8)] {
        let (got, got_end) = run(&problem, Method::Taylor, tol, end);
        same_switches(&format!("tol {tol:e}"), &got, &want, bound);
        assert!(diff(&got_end, &want_end) <= 100.0 * bound);
    }
}

/// A start on z = 1 at angle `a` with radial and tangential speeds.
fn on_boundary(a: f64, radial: f64, tangential: f64) -> Problem {
    let mut p = Preset::Paper.problem();
    let (u, v) = (a.cos(), a.sin());
    p.initial = State::new(
        p.params.offset_x + u,
        p.params.offset_y + v,
        radial * u - tangential * v,
        radial * v + tangential * u,
    );
    p
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Starts on z = 1, entering barely (grazing contacts, some of them ending within a
    /// fraction of the first step) or leaving: the switches of DOP853 at tol 1e-13, every
    /// enter/exit on z = 1 to 1e-12 and the state continuous across it.
    #[test]
    fn grazing_and_boundary_starts_match_the_reference(
        a in 0.0f64..6.3, radial in prop_oneof![Just(0.0), 1e-9f64..1e-3, -1e-3f64..-1e-9],
        tangential in -2.0f64..2.0,
    ) {
        let problem = on_boundary(a, radial, tangential);
        let end = 3.0;
        let (want, _) = run(&problem, Method::Dop853, 1e-13, end);
        let (got, _) = run(&problem, Method::Taylor, 1e-13, end);
        prop_assert_eq!(got.len(), want.len(), "{:?} vs {:?}", got, want);
        let p = problem.params;
        for (g, w) in got.iter().zip(&want) {
            prop_assert_eq!(g.kind, w.kind);
            prop_assert!((g.time - w.time).abs() <= 1e-8, "{:?} vs {:?}", g, w);
            if matches!(g.kind, EventKind::Enter | EventKind::Exit) {
                let z = (g.state.x - p.offset_x).hypot(g.state.y - p.offset_y);
                prop_assert!((z - 1.0).abs() <= 1e-12, "z = {} at {:?}", z, g);
            }
            // Continuity: the run through the switch passes its state.
            let options = Options { tol: Some(1e-13), ..Options::with_method(Method::Taylor) };
            let mut prop = Propagator::new(&problem, &options).unwrap();
            let s0 = rotor_rub::advance_to(&mut prop, g.time - 1e-9, |_| {}).unwrap().state;
            let s1 = rotor_rub::advance_to(&mut prop, g.time + 1e-9, |_| {}).unwrap().state;
            let speed = 1.0 + g.state.vx.abs().max(g.state.vy.abs());
            prop_assert!(diff(&s0, &g.state) <= 1e-8 * speed * 10.0, "{:?} vs {:?}", s0, g);
            prop_assert!(diff(&s1, &g.state) <= 1e-8 * speed * 10.0, "{:?} vs {:?}", s1, g);
        }
    }
}

/// A 30-digit reference (`tests/data/switches_30digit*.csv`, made by
/// `scripts/peers/mp_reference.py`): the problem from its header, the switches (kind, time).
fn thirty_digit(file: &str) -> (Problem, f64, Vec<(String, f64)>) {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    let mut problem = Preset::Paper.problem();
    let mut window = 0.0;
    let mut switches = Vec::new();
    for line in text.lines() {
        if let Some(list) = line.strip_prefix("# Parameters (f64 values, used exactly): ") {
            for pair in list.split(", ") {
                let (name, value) = pair.split_once(" = ").unwrap();
                let value: f64 = value.trim().parse().unwrap();
                rotor_rub::Parameter::from_name(name)
                    .unwrap_or_else(|| panic!("{name}"))
                    .set(&mut problem, value);
            }
        } else if let Some(w) = line.strip_prefix("# Start state") {
            let (_, end) = w.split_once("window [").unwrap();
            let end = end.split(", ").nth(1).unwrap().trim_end_matches("].");
            window = end.parse().unwrap();
        } else if !line.starts_with('#') && !line.starts_with("kind") {
            let mut cols = line.split(',');
            let kind = cols.next().unwrap().to_owned();
            switches.push((kind, cols.next().unwrap().parse().unwrap()));
        }
    }
    (problem, window, switches)
}

/// Switch times within 4e-15 (about one ulp of τ ≈ 20) of a 30-digit reference (mpmath, dps 45
/// and 64 agreeing to 1e-44)
/// on two non-chaotic cases, at taylor's tightest tolerance: the period-1 rub of the paper preset
/// at η = 3.5 (43 switches in τ ∈ [0, 20]) and the same with Coulomb friction (52 switches, 7 of
/// them `reverse`).
#[test]
fn switch_times_match_a_30_digit_reference() {
    for file in ["switches_30digit.csv", "switches_30digit_friction.csv"] {
        let (problem, window, want) = thirty_digit(file);
        assert!(window > 0.0 && want.len() > 40, "{file}");
        let (got, _) = run(&problem, Method::Taylor, 1e-16, window);
        assert_eq!(
            got.iter().map(|e| e.kind.name()).collect::<Vec<_>>(),
            want.iter().map(|(k, _)| k.as_str()).collect::<Vec<_>>(),
            "{file}: switch kinds"
        );
        let worst = got
            .iter()
            .zip(&want)
            .map(|(g, (_, t))| (g.time - t).abs())
            .fold(0.0, f64::max);
        eprintln!("{file}: {} switches, largest |Δt| {worst:.2e}", got.len());
        assert!(worst <= 4e-15, "{file}: switch times off by {worst:e}");
    }
}
