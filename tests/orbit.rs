//! Periodic orbits by shooting (`rotor_rub::orbit`, `docs/MODEL.md` §18), checked by what needs
//! no trust in the code: the monodromy matrix from the segments (closed-form free flight,
//! variational equations in contact, saltation at the switches) against central differences of
//! the stroboscopic map computed by DOP853 at tol 1e-13 — on orbits and on stretches with every
//! kind of switch (frictionless contact, slip reversals, rolling) —, Floquet multipliers against
//! the eigenvalues of that finite-difference matrix, Newton's quadratic convergence shown on its
//! residuals, a stable orbit reproduced by a plain simulation for 100 periods, the generated
//! Jacobians against differences of the fields, and the saltation matrices where the field is
//! continuous (identity) and where it jumps (S f⁻ = f⁺).

use rotor_rub::field::{self, Field};
use rotor_rub::linalg::Complex;
use rotor_rub::orbit::{
    IDENTITY, MapObserver, MapSettings, Mat4, OrbitError, ShootingSettings, continuous, jacobian,
    saltation, shoot, stroboscopic_map,
};
use rotor_rub::propagate::{Event, EventKind, Regime};
use rotor_rub::{Method, Options, Params, Preset, Problem, Propagator, State, advance_to};

/// The paper rotor at speed ratio `eta`.
fn paper(eta: f64) -> Params {
    let mut p = Preset::Paper.problem().params;
    p.speed_ratio = eta;
    p
}

/// Guesses near orbits found by `rotor-rub orbit` (rounded: Newton gets back to them).
/// The full annular rub at η = 2.2 (stable, no switch).
const ANNULAR: (f64, [f64; 4]) = (2.2, [2.1, -1.2, 0.5, -5.6]);
/// Period 1 at η = 3 with two contacts per period (unstable).
const RUBBING: (f64, [f64; 4]) = (3.0, [0.0951, 0.3954, 2.4799, 2.5506]);
/// Period 2 at η = 3, four contacts (stable: the sweep's response there).
const PERIOD_TWO: (f64, [f64; 4]) = (3.0, [0.1875, 0.0545, 1.4481, 1.8541]);

fn state(a: [f64; 4]) -> State {
    State::from_array(a)
}

/// P^k by DOP853 at tol 1e-13: the reference map.
fn reference_map(params: &Params, x: State, k: u32) -> State {
    let settings = MapSettings {
        options: Options {
            tol: Some(1e-13),
            ..Options::with_method(Method::Dop853)
        },
        jacobian: false,
        extrema: false,
        ..MapSettings::default()
    };
    stroboscopic_map(params, x, k, &settings, &mut ())
        .expect("the reference map runs")
        .state
}

/// ∂P^k/∂s by central differences of the reference map (step 1e-6).
fn difference_monodromy(params: &Params, x: State, k: u32) -> Mat4 {
    let h = 1e-6;
    let mut m = [[0.0; 4]; 4];
    for j in 0..4 {
        let (mut a, mut b) = (x.to_array(), x.to_array());
        a[j] += h;
        b[j] -= h;
        let (pa, pb) = (
            reference_map(params, state(a), k).to_array(),
            reference_map(params, state(b), k).to_array(),
        );
        for i in 0..4 {
            m[i][j] = (pa[i] - pb[i]) / (2.0 * h);
        }
    }
    m
}

/// The largest |a_ij − b_ij| over max(1, |b_ij|).
fn matrix_gap(a: &Mat4, b: &Mat4) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..4 {
        for j in 0..4 {
            worst = worst.max((a[i][j] - b[i][j]).abs() / b[i][j].abs().max(1.0));
        }
    }
    worst
}

/// The largest distance of a multiplier from its nearest partner (greedy matching).
fn spectrum_gap(a: &[Complex; 4], b: &[Complex; 4]) -> f64 {
    let mut left: Vec<Complex> = b.to_vec();
    let mut worst: f64 = 0.0;
    for z in a {
        let (i, d) = left
            .iter()
            .enumerate()
            .map(|(i, w)| (i, (*z - *w).abs()))
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .expect("as many as matched");
        left.remove(i);
        worst = worst.max(d);
    }
    worst
}

fn orbit_at((eta, guess): (f64, [f64; 4]), k: u32) -> rotor_rub::orbit::Shot {
    shoot(&paper(eta), state(guess), k, &ShootingSettings::default()).expect("converges")
}

#[test]
fn newton_converges_quadratically() {
    // Starts 1e-2 off the orbits: the annular rub (no switch) and a rubbing orbit (two contacts
    // per period: the monodromy crosses four switches).
    for (case, k) in [(ANNULAR, 1), (RUBBING, 1), (PERIOD_TWO, 2)] {
        let exact = orbit_at(case, k).orbit.state.to_array();
        let start = exact.map(|v| v + 1e-2);
        let shot = shoot(
            &paper(case.0),
            state(start),
            k,
            &ShootingSettings::default(),
        )
        .expect("converges");
        let r = shot.residuals();
        let shown: Vec<String> = r.iter().map(|x| format!("{x:.2e}")).collect();
        println!("η = {}, k = {k}: residuals {}", case.0, shown.join(", "));
        assert!(r.len() <= 6, "{} iterations", r.len());
        assert!(*r.last().unwrap() <= 1e-10 * (1.0 + 6.0));
        // Each residual at most a constant times the square of the one before, down to the
        // trajectory's accuracy (1e-12).
        for w in r.windows(2) {
            assert!(
                w[1] <= 30.0 * w[0] * w[0] + 1e-12,
                "not quadratic: {:e} after {:e}",
                w[1],
                w[0]
            );
        }
    }
}

#[test]
fn multipliers_match_finite_differences_of_the_map() {
    for (case, k) in [(ANNULAR, 1), (RUBBING, 1), (PERIOD_TWO, 2)] {
        let orbit = orbit_at(case, k).orbit;
        let params = paper(case.0);
        let fd = difference_monodromy(&params, orbit.state, k);
        let entries = matrix_gap(&orbit.monodromy, &fd);
        let fd_multipliers = rotor_rub::orbit::eigenvalues_of(&fd).unwrap();
        let multipliers = spectrum_gap(&orbit.multipliers, &fd_multipliers);
        println!(
            "η = {}, k = {k}: monodromy vs differences {entries:.1e}, multipliers {multipliers:.1e}; |λ| = {:?}",
            case.0,
            orbit.multipliers.map(|m| m.abs())
        );
        assert!(entries <= 1e-6, "monodromy off by {entries:e}");
        assert!(multipliers <= 1e-6, "multipliers off by {multipliers:e}");
    }
}

/// The first forcing period, over 40 from `problem`'s start, whose map sees each of `kinds`;
/// its start state on the section.
fn stretch_with(problem: &Problem, kinds: &[EventKind]) -> State {
    let options = Options {
        tol: Some(1e-12),
        ..Options::with_method(Method::Hybrid)
    };
    let mut p = Propagator::new(problem, &options).unwrap();
    let period = problem.params.forcing_period();
    for j in 1..=40 {
        let s = advance_to(&mut p, j as f64 * period, |_| {}).unwrap().state;
        let point = stroboscopic_map(
            &problem.params,
            s,
            1,
            &MapSettings {
                jacobian: false,
                ..MapSettings::default()
            },
            &mut (),
        )
        .unwrap();
        if kinds.iter().all(|&k| point.summary.count(k) > 0) {
            return s;
        }
    }
    panic!("no forcing period with {kinds:?}");
}

#[test]
fn monodromy_across_friction_switches_matches_finite_differences() {
    // Slip reversals (the paper's stator, μ = 0.2, ρ_R = 1, η = 2) and rolling (isotropic
    // K = 100, μ = 0.6, ρ_R = 0.5): saltation at reverse and roll, rolling's variational
    // equations, identity at slip. Not orbits: the map over one period from a state on it.
    let mut reversal = Preset::Paper.problem();
    reversal.params.speed_ratio = 2.0;
    reversal.params.friction_coefficient = 0.2;
    reversal.params.radius_ratio = 1.0;
    let mut rolling = Preset::Paper.problem();
    (
        rolling.params.k_xx,
        rolling.params.k_xy,
        rolling.params.k_yx,
        rolling.params.k_yy,
    ) = (100.0, 0.0, 0.0, 100.0);
    rolling.params.friction_coefficient = 0.6;
    rolling.params.radius_ratio = 0.5;
    for (problem, kinds) in [
        (reversal, vec![EventKind::Reverse]),
        (rolling, vec![EventKind::Roll, EventKind::Slip]),
    ] {
        let x = stretch_with(&problem, &kinds);
        let point =
            stroboscopic_map(&problem.params, x, 1, &MapSettings::default(), &mut ()).unwrap();
        let fd = difference_monodromy(&problem.params, x, 1);
        let gap = matrix_gap(&point.monodromy, &fd);
        println!(
            "{kinds:?}: switches {:?}, monodromy vs differences {gap:.1e}",
            point.summary.switches
        );
        assert!(gap <= 1e-6, "off by {gap:e}");
    }
}

#[test]
fn generated_jacobians_match_differences_of_the_fields() {
    let mut params = Preset::Paper.problem().params;
    params.friction_coefficient = 0.3;
    params.radius_ratio = 1.5;
    let model = rotor_rub::coefficients::ModelParams::of(&params);
    let phasor = field::phasor(&model, 0.7);
    let states = [
        State::new(1.4, -0.9, 2.0, 3.0),
        State::new(-0.6, 0.8, -1.5, 0.4),
        State::new(0.3, 1.2, 4.0, -2.0),
    ];
    for field in [
        Field::Contact,
        Field::Slipping(1.0),
        Field::Slipping(-1.0),
        Field::Rolling,
    ] {
        for s in &states {
            let j = jacobian(&model, field, &phasor, s).unwrap();
            let rows = [[j.xx, j.xy, j.xvx, j.xvy], [j.yx, j.yy, j.yvx, j.yvy]];
            for c in 0..4 {
                let h = 1e-6;
                let (mut a, mut b) = (s.to_array(), s.to_array());
                a[c] += h;
                b[c] -= h;
                let fa = field::acceleration(&model, field, &phasor, &state(a));
                let fb = field::acceleration(&model, field, &phasor, &state(b));
                let d = [(fa.0 - fb.0) / (2.0 * h), (fa.1 - fb.1) / (2.0 * h)];
                for r in 0..2 {
                    let scale = d[r].abs().max(1.0);
                    assert!(
                        (rows[r][c] - d[r]).abs() <= 1e-7 * scale,
                        "{field:?} at {s:?}: ∂a{r}/∂s{c} = {} vs {}",
                        rows[r][c],
                        d[r]
                    );
                }
            }
        }
    }
    assert!(jacobian(&model, Field::Free, &phasor, &states[0]).is_none());
}

/// Every switch of a run, with the fields on either side.
#[derive(Default)]
struct Switches(Vec<Event>);

impl MapObserver for Switches {
    fn event(&mut self, e: &Event) {
        self.0.push(*e);
    }
}

#[test]
fn saltation_is_the_identity_where_the_field_is_continuous_and_maps_the_field_where_it_jumps() {
    let mut reversal = Preset::Paper.problem().params;
    reversal.speed_ratio = 2.0;
    reversal.friction_coefficient = 0.2;
    reversal.radius_ratio = 1.0;
    let mut rolling = reversal;
    (rolling.k_xx, rolling.k_xy, rolling.k_yx, rolling.k_yy) = (100.0, 0.0, 0.0, 100.0);
    rolling.friction_coefficient = 0.6;
    rolling.radius_ratio = 0.5;
    let mut seen = [0usize; 5];
    for params in [paper(1.5), reversal, rolling] {
        let model = rotor_rub::coefficients::ModelParams::of(&params);
        let mut switches = Switches::default();
        let settings = MapSettings {
            jacobian: false,
            ..MapSettings::default()
        };
        stroboscopic_map(
            &params,
            State::new(0.1, 0.1, 0.0, 0.0),
            10,
            &settings,
            &mut switches,
        )
        .unwrap();
        // The regime before each switch, replayed from the kinds.
        let mut before = Regime::Free;
        for e in &switches.0 {
            let after = e.kind.regime_after();
            let slip_before = if before == Regime::Contact {
                field::slip_direction(&params, e.time, &e.state, None)
            } else {
                0.0
            };
            let slip_after = if after == Regime::Contact {
                field::slip_direction(&params, e.time, &e.state, Some(e.kind))
            } else {
                0.0
            };
            let mut f_before = Field::of(before, slip_before);
            // Before a reversal the slip had the other sign.
            if e.kind == EventKind::Reverse {
                f_before = Field::Slipping(-slip_after);
            }
            let f_after = Field::of(after, slip_after);
            let ph = field::phasor(&model, e.time);
            let a = field::acceleration(&model, f_before, &ph, &e.state);
            let b = field::acceleration(&model, f_after, &ph, &e.state);
            let s = saltation(&model, e, f_before, f_after).unwrap();
            let index = EventKind::ALL.iter().position(|k| *k == e.kind).unwrap();
            seen[index] += 1;
            if continuous(e.kind, f_before) {
                // On z = 1 the contact forces vanish; at slip λ = ±μN: the fields agree.
                let scale = a.0.abs().max(a.1.abs()).max(1.0);
                assert!(
                    (a.0 - b.0).abs() <= 1e-11 * scale && (a.1 - b.1).abs() <= 1e-11 * scale,
                    "{:?} at {}: fields {a:?} and {b:?}",
                    e.kind,
                    e.time
                );
                assert_eq!(s, IDENTITY);
            } else {
                // S f⁻ = f⁺.
                let fm = [e.state.vx, e.state.vy, a.0, a.1];
                let fp = [e.state.vx, e.state.vy, b.0, b.1];
                let mapped = rotor_rub::orbit::apply(&s, fm);
                for i in 0..4 {
                    assert!((mapped[i] - fp[i]).abs() <= 1e-9 * (1.0 + fp[i].abs()));
                }
            }
            before = after;
        }
    }
    println!("switches checked by kind (enter, exit, reverse, roll, slip): {seen:?}");
    assert!(seen.iter().all(|&n| n > 0), "every kind met: {seen:?}");
}

#[test]
fn a_stable_orbit_is_reproduced_by_a_plain_simulation_for_100_periods() {
    for (case, k) in [(ANNULAR, 1), (PERIOD_TWO, 2)] {
        let orbit = orbit_at(case, k).orbit;
        assert!(orbit.stable());
        let problem = Problem {
            params: paper(case.0),
            initial: orbit.state,
            start_time: 0.0,
        };
        for method in [Method::Taylor, Method::Dop853] {
            let options = Options {
                tol: Some(1e-12),
                ..Options::with_method(method)
            };
            let mut p = Propagator::new(&problem, &options).unwrap();
            let period = problem.params.forcing_period();
            let sections = orbit.sections();
            let mut worst: f64 = 0.0;
            for j in 1..=100u32 {
                let s = advance_to(&mut p, f64::from(j) * period, |_| {})
                    .unwrap()
                    .state;
                let expected = sections[(j as usize - 1) % k as usize];
                let d = s
                    .to_array()
                    .iter()
                    .zip(expected.to_array())
                    .fold(0.0, |a: f64, (x, y)| a.max((x - y).abs()));
                worst = worst.max(d);
            }
            println!(
                "η = {}, k = {k}, {method:?}: largest distance over 100 periods {worst:.1e}",
                case.0
            );
            assert!(worst <= 1e-8, "left the orbit by {worst:e}");
        }
    }
}

#[test]
fn the_orbits_own_period_divides_k() {
    let two = orbit_at(PERIOD_TWO, 2).orbit;
    assert_eq!(two.minimal_period(1e-6), 2);
    // A period-1 orbit is a fixed point of P² too: its own period is 1.
    let one = orbit_at(RUBBING, 2).orbit;
    assert_eq!(one.minimal_period(1e-6), 1);
    let direct = orbit_at(RUBBING, 1).orbit;
    let d = (one.state.x - direct.state.x).abs() + (one.state.y - direct.state.y).abs();
    assert!(d < 1e-8);
    // Its P² multipliers are the squares of its P multipliers.
    let squares = direct.multipliers.map(|m| m * m);
    assert!(spectrum_gap(&one.multipliers, &squares) < 1e-7);
}

#[test]
fn bad_settings_are_refused_with_the_value_and_the_range() {
    let params = paper(2.0);
    let x = State::new(0.1, 0.1, 0.0, 0.0);
    for k in [0, 33] {
        let e = shoot(&params, x, k, &ShootingSettings::default()).unwrap_err();
        assert_eq!(e, OrbitError::InvalidPeriod { periods: k });
        assert!(e.to_string().contains("[1, 32]"), "{e}");
    }
    let e = shoot(
        &params,
        x,
        1,
        &ShootingSettings {
            tolerance: 1e-20,
            ..ShootingSettings::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("tolerance = 1e-20"), "{e}");
    let mut bad = params;
    bad.speed_ratio = -1.0;
    let e = shoot(&bad, x, 1, &ShootingSettings::default()).unwrap_err();
    assert!(matches!(e, OrbitError::Propagation(_)), "{e}");
    // A start that diverges: a clear error, not a panic or a NaN orbit.
    let e = shoot(
        &params,
        State::new(50.0, 50.0, 90.0, 90.0),
        1,
        &ShootingSettings::default(),
    );
    assert!(e.is_err() || e.unwrap().orbit.state.is_finite());
}

#[test]
fn a_rolling_orbit_has_a_zero_multiplier_and_matches_finite_differences() {
    // The paper rotor with μ = 0.6, ρ_R = 1 at η = 2 settles on a period-2 orbit whose contacts
    // roll and slip again: saltation at `roll` maps every perturbation into the surface w = 0
    // (rolling keeps w), so the monodromy is singular, with a multiplier 0 (docs/MODEL.md §18).
    let mut params = paper(2.0);
    params.friction_coefficient = 0.6;
    params.radius_ratio = 1.0;
    let guess = State::new(-0.4616, -0.0371, -0.2521, 2.1573);
    let orbit = shoot(&params, guess, 2, &ShootingSettings::default())
        .expect("converges")
        .orbit;
    let point =
        stroboscopic_map(&params, orbit.state, 2, &MapSettings::default(), &mut ()).unwrap();
    let switches = [
        EventKind::Enter,
        EventKind::Roll,
        EventKind::Slip,
        EventKind::Exit,
    ]
    .map(|k| point.summary.count(k));
    let fd = difference_monodromy(&params, orbit.state, 2);
    let entries = matrix_gap(&orbit.monodromy, &fd);
    let fd_multipliers = rotor_rub::orbit::eigenvalues_of(&fd).unwrap();
    let multipliers = spectrum_gap(&orbit.multipliers, &fd_multipliers);
    let smallest = orbit
        .multipliers
        .iter()
        .map(|m| m.abs())
        .fold(f64::INFINITY, f64::min);
    println!(
        "rolling orbit: (enter, roll, slip, exit) {switches:?}, monodromy vs differences {entries:.1e}, multipliers {multipliers:.1e}, smallest |λ| {smallest:.1e}, stable {}",
        orbit.stable()
    );
    assert!(switches.iter().all(|&n| n > 0), "{switches:?}");
    assert!(entries <= 1e-6, "monodromy off by {entries:e}");
    assert!(multipliers <= 1e-6, "multipliers off by {multipliers:e}");
    assert!(smallest <= 1e-9, "no zero multiplier: {smallest:e}");
    assert!(orbit.stable() && orbit.minimal_period(1e-6) == 2);
}
