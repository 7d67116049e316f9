//! The fixed-step stepper under friction (issue 12 point 3) against DOP853 at tol 1e-12: the
//! same switches (kinds and count) on the reversal, rolling and dry-whip cases, switch times
//! within the bound measured for each step length, and rolling keeping w at 0.

use rotor_rub::{
    Event, Method, Options, Params, Preset, Problem, Propagator, Regime, Stepper, StepperConfig,
    advance_to, field,
};

fn cases() -> Vec<(&'static str, Problem, f64)> {
    let mut reversal = Preset::Paper.problem();
    reversal.params.speed_ratio = 2.0;
    reversal.params.friction_coefficient = 0.2;
    reversal.params.radius_ratio = 1.0;
    let mut rolling = Preset::Paper.problem();
    let p = &mut rolling.params;
    (p.k_xx, p.k_xy, p.k_yx, p.k_yy) = (100.0, 0.0, 0.0, 100.0);
    p.friction_coefficient = 0.6;
    p.radius_ratio = 0.5;
    let whip = Preset::DryWhip.problem();
    let periods = |p: &Problem, n: f64| n * p.params.forcing_period();
    vec![
        ("slip reversal", reversal, periods(&reversal, 10.0)),
        ("rolling", rolling, periods(&rolling, 8.0)),
        ("dry whip", whip, periods(&whip, 20.0)),
    ]
}

fn reference(problem: &Problem, t_end: f64) -> Vec<Event> {
    let options = Options {
        tol: Some(1e-12),
        ..Options::with_method(Method::Dop853)
    };
    let mut p = Propagator::new(problem, &options).unwrap();
    let mut events = Vec::new();
    advance_to(&mut p, t_end, |e| events.push(*e)).unwrap();
    events
}

fn stepped(problem: &Problem, dt: f64, t_end: f64, params: &Params) -> (Vec<Event>, f64) {
    let mut s = Stepper::new(problem, StepperConfig::with_dt(dt)).unwrap();
    let mut events = Vec::new();
    let mut max_w: f64 = 0.0;
    let steps = (t_end / dt).round() as u64;
    for _ in 0..steps {
        let r = s.step(dt).unwrap();
        events.extend(r.events.iter().copied());
        if r.regime == Regime::Rolling && r.events.is_empty() {
            let f = field::friction_at(params, r.time, &r.state);
            max_w = max_w.max(f.slip_velocity.abs());
        }
    }
    (events, max_w)
}

#[test]
fn stepper_matches_dop853_under_friction() {
    for (name, problem, t_end) in cases() {
        let want = reference(&problem, t_end);
        // Measured: ≤ 2.5e-11 at dt = 1e-3, ≤ 1.3e-7 at dt = 1e-2.
        for (dt, bound) in [(1e-3, 1e-9), (1e-2, 1e-6)] {
            let (got, max_w) = stepped(&problem, dt, t_end, &problem.params);
            let kinds = |e: &[Event]| e.iter().map(|e| e.kind.name()).collect::<Vec<_>>();
            assert_eq!(kinds(&got), kinds(&want), "{name}, dt = {dt}: event kinds");
            let worst = got
                .iter()
                .zip(&want)
                .map(|(a, b)| (a.time - b.time).abs())
                .fold(0.0, f64::max);
            eprintln!(
                "{name:14} dt = {dt:e}: {} events, max switch-time difference {worst:.1e}, \
                 max |w| while rolling {max_w:.1e}",
                got.len()
            );
            assert!(worst <= bound, "{name}, dt = {dt}: {worst:e} > {bound:e}");
            assert!(
                max_w <= 1e-9,
                "{name}, dt = {dt}: |w| = {max_w:e} while rolling"
            );
        }
    }
}
