//! The paper rotor's branches (`rotor_rub_cli::orbit`, `docs/MODEL.md` §18), checked against what
//! needs no trust in the continuation: the free orbit's grazing points against the steady free
//! response in closed form; a fold against the vertex of the branch's own parameter around it;
//! a period doubling and a Neimark–Sacker point against multipliers from shooting at fixed
//! parameter values either side; the run-up's and the coast-down's jumps (the `paper-hysteresis`
//! program, `docs/runup.png`) each past the bifurcation of the branch it leaves and approaching
//! it as the ramp rate falls (three rates); period doubling where the sweep's response turns
//! period-2; the response class on stable orbits; continuation with slipping friction, through
//! rolling (a torus located on a rolling branch) and in another parameter. Each continuation
//! covers a short range: seconds in all.

use rotor_rub::linalg::Complex;
use rotor_rub::orbit::{ShootingSettings, shoot};
use rotor_rub::speed::{Ramp, RampPace};
use rotor_rub::variable_speed::{
    JumpSearch, Revolutions, VariableSpeedOptions, VariableSpeedPropagator, find_jumps,
};
use rotor_rub::{Method, Options, Parameter, Params, Preset, Problem, State};
use rotor_rub_cli::analysis::classify::Response;
use rotor_rub_cli::limits::{Budget, LimitArgs};
use rotor_rub_cli::orbit::correct::{Corrected, correct};
use rotor_rub_cli::orbit::start::{free_steady_state, map_settings};
use rotor_rub_cli::orbit::{
    BranchPoint, Continuation, ContinuationSettings, Evaluator, Kind, Start, continuation,
};

fn budget() -> Budget {
    LimitArgs {
        max_work: 1e9 as u64,
    }
    .budget()
}

fn paper(eta: f64) -> Params {
    let mut p = Preset::Paper.problem().params;
    p.speed_ratio = eta;
    p
}

/// A continuation of the paper rotor's period-1 orbits over `range` from `guess` at its start,
/// no branch switching unless `switch`.
fn run(params: Params, range: (f64, f64), guess: State, switch: bool) -> Continuation {
    let mut settings = ContinuationSettings::new(Parameter::SpeedRatio, range.0, range.1, 1);
    settings.max_period = if switch { 2 } else { 1 };
    run_with(params, &settings, guess)
}

fn run_with(params: Params, settings: &ContinuationSettings, guess: State) -> Continuation {
    let mut poll = |_: f64| Ok(());
    let mut ev = Evaluator {
        base: params,
        parameter: settings.parameter,
        periods: settings.periods,
        map: settings.map,
        poll: &mut poll,
        evaluations: 0,
    };
    let start = Start {
        guess,
        value: settings.from,
    };
    continuation(&mut ev, &[start], settings).expect("the continuation runs")
}

/// The located bifurcations of `kind`, in branch order.
fn located(c: &Continuation, kind: Kind) -> Vec<&BranchPoint> {
    c.bifurcations
        .iter()
        .map(|&i| &c.points[i])
        .filter(|p| p.kind == Some(kind))
        .collect()
}

/// The state after `periods` forcing periods from the preset's start at `eta`.
fn simulated(eta: f64, periods: u64) -> State {
    let mut problem = Preset::Paper.problem();
    problem.params.speed_ratio = eta;
    rotor_rub_cli::orbit::simulated_start(
        &problem,
        &Options::with_method(Method::Hybrid),
        periods,
        &budget(),
    )
    .unwrap()
}

/// The speed ratios where the free orbit's largest distance from the stator centre is 1: its
/// radius F/√D (F = η_m ρ̂ η², D = (1 − η²)² + (2νη)²) equals 1 − |ε̂|, a quadratic in η².
fn free_grazing_speeds(p: &Params) -> (f64, f64) {
    let a = p.mass_ratio * p.eccentricity_ratio;
    let c = 1.0 - p.offset_x.hypot(p.offset_y);
    let nu = p.damping_ratio;
    let (qa, qb, qc) = (a * a - c * c, c * c * (2.0 - 4.0 * nu * nu), -c * c);
    let d = (qb * qb - 4.0 * qa * qc).sqrt();
    let roots = [(-qb + d) / (2.0 * qa), (-qb - d) / (2.0 * qa)];
    let (lo, hi) = (roots[0].min(roots[1]), roots[0].max(roots[1]));
    (lo.sqrt(), hi.sqrt())
}

#[test]
fn the_free_orbits_grazing_points_are_where_the_closed_form_puts_them() {
    let params = paper(1.0);
    let (low, high) = free_grazing_speeds(&params);
    // Below resonance: from the free orbit at η = 0.6 up; above it: from the free orbit at
    // η = 1.8 down (the coast-down's side).
    let up = run(
        params,
        (0.6, 0.85),
        free_steady_state(&paper(0.6)).unwrap(),
        false,
    );
    let down = run(
        params,
        (1.8, 1.4),
        free_steady_state(&paper(1.8)).unwrap(),
        false,
    );
    for (c, exact) in [(&up, low), (&down, high)] {
        let g = located(c, Kind::Grazing)[0];
        println!(
            "grazing at η = {:.12}, closed form {exact:.12}: {:.1e}",
            g.value(),
            g.value() - exact
        );
        assert!((g.value() - exact).abs() <= 1e-8);
        assert!((g.summary().max_distance - 1.0).abs() <= 1e-9);
    }
}

/// A function of the multipliers whose zero is a bifurcation.
type Test = dyn Fn(&[Complex; 4]) -> f64;

/// The period-1 orbit at η by shooting from `guess`, and its multipliers.
fn multipliers_at(eta: f64, guess: State) -> [Complex; 4] {
    shoot(&paper(eta), guess, 1, &ShootingSettings::default())
        .unwrap()
        .orbit
        .multipliers
}

#[test]
fn a_fold_a_period_doubling_and_a_torus_are_located_to_1e_8() {
    // The high-speed rubbing branch from η = 3.5 down to 2.55: a period doubling at
    // η ≈ 3.1312 (where the sweep turns period-2), another at 2.6285 and a Neimark–Sacker
    // point at 2.6222.
    let c = run(paper(3.5), (3.5, 2.55), simulated(3.5, 200), false);
    let doublings = located(&c, Kind::PeriodDoubling);
    let tori = located(&c, Kind::NeimarkSacker);
    assert!(doublings.len() >= 2 && !tori.is_empty());
    // Either side of each, at fixed η by shooting: the multiplier through −1 (or the pair's
    // modulus through 1) moves linearly; its zero by interpolation is the bifurcation. (1e-7
    // either side: at 2.6285 a second multiplier at −0.983 bends the first one's path within
    // 1e-5 enough to move the interpolated zero by 1.4e-7.)
    let d = 1e-7;
    let through_minus_one = |m: &[Complex; 4]| {
        m.iter()
            .filter(|z| z.im.abs() < 1e-9 && z.re < 0.0)
            .map(|z| z.re + 1.0)
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap()
    };
    let pair_modulus = |m: &[Complex; 4]| {
        m.iter()
            .filter(|z| z.im.abs() > 1e-9)
            .map(|z| z.abs() - 1.0)
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap()
    };
    let cases: [(&BranchPoint, &Test); 3] = [
        (doublings[0], &through_minus_one),
        (doublings[1], &through_minus_one),
        (tori[0], &pair_modulus),
    ];
    for (p, test) in cases {
        let eta = p.value();
        let (a, b) = (
            test(&multipliers_at(eta - d, p.state())),
            test(&multipliers_at(eta + d, p.state())),
        );
        let zero = eta - d + 2.0 * d * a / (a - b);
        println!(
            "{:?} at η = {eta:.12}; from shooting either side: {zero:.12} ({:.1e})",
            p.kind,
            eta - zero
        );
        assert!(a * b < 0.0, "no crossing either side of {eta}");
        assert!((eta - zero).abs() <= 1e-8);
    }
}

#[test]
fn a_fold_is_the_vertex_of_the_branch() {
    // The full annular rub's fold (where the run-up falls off the rub branch).
    let guess = State::new(2.1, -1.2, 0.5, -5.6);
    let c = run(paper(2.2), (2.2, 2.5), guess, false);
    let fold = located(&c, Kind::Fold)[0];
    // Three points of the branch around it, on hyperplanes σ = −δ, 0, δ along its tangent,
    // each corrected onto the branch: the parameter's parabola through them peaks at the fold.
    let settings = ContinuationSettings::new(Parameter::SpeedRatio, 2.2, 2.5, 1);
    let mut poll = |_: f64| Ok(());
    let mut ev = Evaluator {
        base: paper(2.2),
        parameter: Parameter::SpeedRatio,
        periods: 1,
        map: map_settings(&Options::with_method(Method::Hybrid)),
        poll: &mut poll,
        evaluations: 0,
    };
    let (u, t) = (fold.solution.u(), fold.solution.tangent);
    let delta = 2e-3;
    let value_at = |ev: &mut Evaluator<'_>, sigma: f64| {
        let guess: [f64; 5] = std::array::from_fn(|i| u[i] + sigma * t[i]);
        let plane = (t, t.iter().zip(&guess).map(|(a, b)| a * b).sum::<f64>());
        match correct(ev, guess, plane, &t, 1e-12, 20, None).unwrap() {
            Corrected::Point(s) => s.value(),
            Corrected::Failed(why) => panic!("{why}"),
        }
    };
    let (a, b, m) = (
        value_at(&mut ev, -delta),
        value_at(&mut ev, delta),
        value_at(&mut ev, 0.0),
    );
    let curvature = a - 2.0 * m + b;
    let vertex = m - (b - a) * (b - a) / (8.0 * curvature);
    println!(
        "fold at η = {:.12}; vertex of the branch's parabola {vertex:.12} ({:.1e}); run-up jump at 1e-3: 2.4736",
        fold.value(),
        fold.value() - vertex
    );
    assert!(curvature < 0.0, "a maximum of η");
    assert!((fold.value() - vertex).abs() <= 1e-8);
    let _ = settings;
}

/// The jumps of a one-way ramp of the paper rotor from `from` to `to` at `rate`, starting on
/// the section at τ = 0 in `state`.
fn jump_speed(from: f64, to: f64, rate: f64, state: State) -> f64 {
    let ramp = Ramp {
        start_time: 0.0,
        from,
        to,
        pace: RampPace::Rate(rate),
        settle_periods: 0.0,
        dwell_periods: 0.0,
        one_way: true,
    };
    let points = ramp.points().unwrap();
    let profile = points.profile().unwrap();
    let problem = Problem {
        params: paper(from),
        initial: state,
        start_time: 0.0,
    };
    let options = VariableSpeedOptions::new(Options::with_method(Method::Hybrid));
    let mut p = VariableSpeedPropagator::new(&problem, profile, &options).unwrap();
    let rows: Vec<_> = Revolutions::new(&mut p, profile, problem.params.phase, 64)
        .map(|r| r.unwrap())
        .collect();
    let jumps = find_jumps(&rows, &JumpSearch::default());
    jumps.largest().expect("a jump").speed_ratio
}

#[test]
fn the_run_up_and_coast_down_jumps_are_explained_by_the_bifurcations_they_approach() {
    // Run-up: on the full annular rub branch from η = 2.3 (the paper-hysteresis program rides
    // it) up to 2.9; the branch folds at η_F, the jump comes after it.
    let annular = shoot(
        &paper(2.3),
        State::new(2.26, -0.95, 1.46, -6.36),
        1,
        &ShootingSettings::default(),
    )
    .unwrap()
    .orbit
    .state;
    let c = run(paper(2.3), (2.3, 2.6), annular, false);
    let fold = located(&c, Kind::Fold)[0].value();
    // Coast-down: on the free orbit from η = 1.6 down to 1.1; it grazes at η_G (closed form),
    // rubs lightly and stably down to a fold η_F' just below, and the jump comes after it.
    let free = free_steady_state(&paper(1.6)).unwrap();
    let c = run(paper(1.6), (1.6, 1.3), free, false);
    let grazing = located(&c, Kind::Grazing)[0].value();
    let light = located(&c, Kind::Fold)[0];
    assert!(
        light.summary().count(rotor_rub::EventKind::Enter) > 0,
        "a rubbing orbit's fold"
    );
    let (_, exact) = free_grazing_speeds(&paper(1.0));
    assert!((grazing - exact).abs() <= 1e-8);
    let light = light.value();
    println!(
        "run-up: annular branch's fold η = {fold:.6}; coast-down: grazing η = {grazing:.6}, light rub's fold η = {light:.6}"
    );
    let rates = [4e-3, 1e-3, 2.5e-4];
    let mut previous = (f64::INFINITY, f64::NEG_INFINITY);
    for rate in rates {
        let up = jump_speed(2.3, 2.9, rate, annular);
        let down = jump_speed(1.6, 1.1, rate, free);
        println!(
            "rate {rate:e}: run-up jump η = {up:.4} ({:+.4} past the fold), coast-down jump η = {down:.4} ({:+.4} past the fold)",
            up - fold,
            down - light
        );
        assert!(
            up > fold && up < previous.0,
            "run-up jump {up} at rate {rate}"
        );
        assert!(
            down < light && down > previous.1,
            "coast-down jump {down} at rate {rate}"
        );
        if rate == 1e-3 {
            // The paper-hysteresis program's jumps (docs/runup.png): 2.474 and 1.404.
            assert!((up - 2.474).abs() < 0.01 && (down - 1.404).abs() < 0.01);
        }
        previous = (up, down);
    }
    // Slower ramps get nearer: a quarter of the rate at least halves the delay.
    let (up_fast, up_slow) = (
        jump_speed(2.3, 2.9, 1e-3, annular) - fold,
        jump_speed(2.3, 2.9, 2.5e-4, annular) - fold,
    );
    assert!(up_slow < 0.6 * up_fast);
}

/// The response class of the sweep's run at η (from the preset's start, 200 transient and 50
/// kept periods, as `rotor-rub sweep`).
fn sweep_response(eta: f64) -> Response {
    let mut problem = Preset::Paper.problem();
    problem.params.speed_ratio = eta;
    let section = rotor_rub_cli::poincare::section(
        &problem,
        &Options::with_method(Method::Taylor),
        200,
        50,
        false,
        &budget(),
    )
    .unwrap();
    section.response
}

#[test]
fn period_doubling_is_where_the_sweep_turns_period_two() {
    // Below resonance the rub branch doubles at η ≈ 0.873; at high speed the rubbing branch
    // doubles at η ≈ 3.131 (the sweep: period-2 below, period-1 above).
    let low = run(paper(0.5), (0.5, 0.95), simulated(0.5, 200), false);
    let high = run(paper(3.5), (3.5, 2.9), simulated(3.5, 200), false);
    let (pd_low, pd_high) = (
        located(&low, Kind::PeriodDoubling)[0].value(),
        located(&high, Kind::PeriodDoubling)[0].value(),
    );
    println!("period doublings at η = {pd_low:.6} and {pd_high:.6}");
    for (eta, expected) in [
        (0.85, Response::Periodic(1)),
        (0.9, Response::Periodic(2)),
        (3.0, Response::Periodic(2)),
        (3.25, Response::Periodic(1)),
    ] {
        assert_eq!(sweep_response(eta), expected, "sweep at η = {eta}");
    }
    assert!(0.85 < pd_low && pd_low < 0.9);
    assert!(3.0 < pd_high && pd_high < 3.25);
}

#[test]
fn the_response_class_of_a_stable_orbit_is_its_period() {
    let two = rotor_rub_cli::orbit::command::find(
        &Problem {
            params: paper(3.0),
            ..Preset::Paper.problem()
        },
        &Options::with_method(Method::Hybrid),
        rotor_rub_cli::orbit::start::Guess::Simulate,
        200,
        2,
        1e-10,
        &budget(),
    )
    .unwrap();
    assert!(two.orbit().stable());
    assert_eq!(two.minimal_period, 2);
    let section = rotor_rub_cli::poincare::section(
        &Problem {
            params: paper(3.0),
            initial: two.orbit().state,
            start_time: 0.0,
        },
        &Options::with_method(Method::Taylor),
        0,
        40,
        false,
        &budget(),
    )
    .unwrap();
    assert_eq!(section.response, Response::Periodic(2));
}

#[test]
fn friction_and_other_parameters_continue_too() {
    // Slipping contact (the friction preset at η = 1.2: three contacts per period), in η.
    let mut params = Preset::Friction.problem().params;
    params.speed_ratio = 1.2;
    let orbit = shoot(
        &params,
        State::new(0.587, -0.654, 0.849, 0.600),
        1,
        &ShootingSettings::default(),
    )
    .unwrap()
    .orbit;
    let c = run(params, (1.2, 1.25), orbit.state, false);
    assert!(c.points.len() > 5, "{:?}", c.branches);
    assert!(
        c.branches[0].end.contains("left the range"),
        "{}",
        c.branches[0].end
    );
    // The annular rub in the damping ratio.
    let mut settings = ContinuationSettings::new(Parameter::DampingRatio, 0.125, 0.2, 1);
    settings.max_period = 1;
    let c = run_with(paper(2.2), &settings, State::new(2.1, -1.2, 0.5, -5.6));
    assert!(
        c.branches[0].end.contains("left the range"),
        "{}",
        c.branches[0].end
    );
    // Each point is an orbit: shooting at its ν from its state stays there.
    let p = &c.points[c.points.len() / 2];
    let mut at = paper(2.2);
    at.damping_ratio = p.value();
    let again = shoot(&at, p.state(), 1, &ShootingSettings::default()).unwrap();
    assert!(again.iterations == 1, "{:?}", again.residuals());
}

#[test]
fn a_rolling_branch_continues_and_its_torus_is_located() {
    // Rolling is supported: the paper rotor with μ = 0.6, ρ_R = 1 has a stable period-2 orbit
    // at η = 2 whose contacts roll (a multiplier 0: rolling's saltation is singular); followed
    // to η = 2.2, it loses stability to a torus at η ≈ 2.1301, located to 1e-8 (checked by the
    // complex pair's modulus from shooting either side), past where its rolling stops.
    let mut params = paper(2.0);
    params.friction_coefficient = 0.6;
    params.radius_ratio = 1.0;
    let mut settings = ContinuationSettings::new(Parameter::SpeedRatio, 2.0, 2.2, 2);
    settings.max_period = 2;
    let c = run_with(
        params,
        &settings,
        State::new(-0.4616, -0.0371, -0.2521, 2.1573),
    );
    assert!(
        c.branches[0].end.contains("left the range"),
        "{}",
        c.branches[0].end
    );
    let smallest = |p: &BranchPoint| {
        p.solution
            .multipliers
            .iter()
            .map(|m| m.abs())
            .fold(f64::INFINITY, f64::min)
    };
    assert!(smallest(&c.points[0]) < 1e-9 && c.points[0].stable());
    // Rolling stops near η = 2.06: the multiplier 0 leaves (0.12 at η = 2.2).
    assert!(smallest(c.points.last().unwrap()) > 1e-2);
    let tori = located(&c, Kind::NeimarkSacker);
    assert_eq!(tori.len(), 1, "{:?}", c.bifurcations);
    let p = tori[0];
    let d = 1e-7;
    let pair_modulus = |eta: f64| {
        let mut at = params;
        at.speed_ratio = eta;
        shoot(&at, p.state(), 2, &ShootingSettings::default())
            .unwrap()
            .orbit
            .multipliers
            .iter()
            .filter(|z| z.im.abs() > 1e-9)
            .map(|z| z.abs() - 1.0)
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap()
    };
    let eta = p.value();
    let (a, b) = (pair_modulus(eta - d), pair_modulus(eta + d));
    let zero = eta - d + 2.0 * d * a / (a - b);
    println!(
        "rolling branch: torus at η = {eta:.12}, from shooting either side {zero:.12} ({:.1e}); {} points",
        eta - zero,
        c.points.len()
    );
    assert!(a * b < 0.0 && (eta - zero).abs() <= 1e-8);
}
