//! The fixed-step stepper (`rotor_rub::stepper`): cost per step and accuracy.
//!
//! `cargo bench --bench stepper` prints, before criterion's per-step medians:
//! 1. **Per-step timing over 10⁶ steps** of the paper preset (mixed free and contact motion) at
//!    dt = 1e-3 and 1e-2, each step timed with `std::time::Instant` (overhead reported, and
//!    included), split by kind: free, free with a contact entry, contact, contact with an exit.
//!    Median, 99th and 99.99th percentiles and the maximum; then the 16 slowest steps of each
//!    kind re-timed from their saved start (least of 200 runs): the largest of those is the
//!    worst case of the algorithm itself, where the raw maximum is mostly preemption.
//! 2. **Accuracy** against DOP853 at tol 1e-12 over 10 forcing periods (state at every step
//!    end, max over components and steps), for the stepper (exprb43 and exprb2) and a classic
//!    RK4 at the same step on `field::derivative` (regime by the sign of h at every stage), with
//!    the mean cost per step of each; then RK4 at the step that costs the same per time unit as
//!    the stepper.
//!
//! `STEPPER_BENCH=timing cargo bench --bench stepper` stops after the timing (1.).
//!
//! Criterion then measures single steps from fixed states (free, free with entry, contact,
//! contact with exit), two parameter changes (`set_params`: a new speed, which keeps Φ and
//! recomputes the forcing's columns G — the bench named "set_params (recomputes Φ)" before Φ was
//! kept —, and a new damping, which recomputes Φ; each on cache-resident copies and on cold
//! ones) and one RK4 step.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BatchSize, Criterion};
use rotor_rub::coefficients::ModelParams;
use rotor_rub::geometry;
use rotor_rub::stepper::SwitchStart;
use rotor_rub::{
    ContactScheme, Method, Options, Preset, Problem, Propagator, Regime, State, Stepper,
    StepperConfig, advance_to, field,
};

const STEPS: usize = 1_000_000;
/// How many of the slowest steps of each kind are re-timed, and how often.
const SLOWEST: usize = 16;
const REPEAT: usize = 200;
const KINDS: [&str; 5] = [
    "free",
    "free+entry",
    "contact",
    "contact+exit",
    "2+ switches",
];

/// The kind of a step: by the regime at its start and whether it held one switch; a step with
/// two or more (an exit and a re-entry, …: two contact sub-steps and searches) is its own kind.
fn kind(start: Regime, switches: usize) -> usize {
    match (start, switches) {
        (_, 2..) => 4,
        (Regime::Free, 0) => 0,
        (Regime::Free, _) => 1,
        (Regime::Contact | Regime::Rolling, 0) => 2,
        (Regime::Contact | Regime::Rolling, _) => 3,
    }
}

fn config(dt: f64, scheme: ContactScheme) -> StepperConfig {
    StepperConfig {
        scheme,
        ..StepperConfig::with_dt(dt)
    }
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// 10⁶ steps, each timed; prints the distribution per kind of step.
fn timing_report(dt: f64, scheme: ContactScheme, switch_start: SwitchStart) {
    let problem = Preset::Paper.problem();
    let config = StepperConfig {
        switch_start,
        ..config(dt, scheme)
    };
    let mut stepper = Stepper::new(&problem, config).expect("stepper");
    let overhead = {
        let mut v: Vec<f64> = (0..10_000)
            .map(|_| {
                let t = Instant::now();
                black_box(t.elapsed()).as_secs_f64()
            })
            .collect();
        v.sort_by(f64::total_cmp);
        percentile(&v, 0.5)
    };
    let mut times: [Vec<f64>; 5] = Default::default();
    // The SLOWEST slowest steps of each kind, with the stepper before them, to re-time.
    let mut slowest: [Vec<(f64, Stepper)>; 5] = Default::default();
    for _ in 0..STEPS {
        let before = stepper;
        let t = Instant::now();
        let r = stepper.step(black_box(dt)).expect("the paper preset steps");
        let elapsed = t.elapsed().as_secs_f64();
        let k = kind(before.regime(), r.events.total());
        times[k].push(elapsed);
        let list = &mut slowest[k];
        if list.len() < SLOWEST || elapsed > list[SLOWEST - 1].0 {
            list.truncate(SLOWEST - 1);
            list.push((elapsed, before));
            list.sort_by(|a, b| b.0.total_cmp(&a.0));
        }
    }
    println!(
        "timing dt={dt:e} {} {switch_start:?} ({STEPS} steps, {:.0} time units; Instant overhead {:.0} ns, included)",
        scheme.name(),
        STEPS as f64 * dt,
        overhead * 1e9
    );
    for ((name, v), slow) in KINDS.iter().zip(times.iter_mut()).zip(&slowest) {
        if v.is_empty() {
            continue;
        }
        v.sort_by(f64::total_cmp);
        // Re-time the slowest steps from their saved start: the least of REPEAT runs is the
        // step's own cost without preemption and cache noise.
        let retimed = slow
            .iter()
            .map(|(_, start)| {
                (0..REPEAT)
                    .map(|_| {
                        let mut s = *start;
                        let t = Instant::now();
                        black_box(s.step(black_box(dt)).expect("step"));
                        t.elapsed().as_secs_f64()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        let ns = |x: f64| x * 1e9;
        println!(
            "  {name:<13} n={:>7}  median {:>5.0}  p99 {:>5.0}  p99.99 {:>6.0}  max {:>7.0}  slowest {SLOWEST} re-timed {:>5.0} (ns)",
            v.len(),
            ns(percentile(v, 0.5)),
            ns(percentile(v, 0.99)),
            ns(percentile(v, 0.9999)),
            ns(v[v.len() - 1]),
            ns(retimed)
        );
    }
}

/// Classic RK4 on the piecewise field, the regime chosen by the sign of h at every stage.
fn rk4_step(problem: &Problem, t: f64, s: &State, dt: f64) -> State {
    let p = &problem.params;
    let f = |t: f64, s: &State| {
        let regime = if geometry::point(&ModelParams::of(p), *s).h > 0.0 {
            Regime::Contact
        } else {
            Regime::Free
        };
        field::derivative(p, regime, 0.0, t, s).to_array()
    };
    let add = |a: &State, k: &[f64; 4], c: f64| {
        let a = a.to_array();
        State::from_array([
            a[0] + c * k[0],
            a[1] + c * k[1],
            a[2] + c * k[2],
            a[3] + c * k[3],
        ])
    };
    let k1 = f(t, s);
    let k2 = f(t + 0.5 * dt, &add(s, &k1, 0.5 * dt));
    let k3 = f(t + 0.5 * dt, &add(s, &k2, 0.5 * dt));
    let k4 = f(t + dt, &add(s, &k3, dt));
    let mut k = [0.0; 4];
    for i in 0..4 {
        k[i] = (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) / 6.0;
    }
    add(s, &k, dt)
}

/// The DOP853 (tol 1e-12) states at the step ends k·dt over `span`.
fn reference(problem: &Problem, dt: f64, steps: usize) -> Vec<State> {
    let options = Options {
        tol: Some(1e-12),
        ..Options::with_method(Method::Dop853)
    };
    let mut p = Propagator::new(problem, &options).expect("reference");
    (1..=steps)
        .map(|k| {
            advance_to(&mut p, k as f64 * dt, |_| {})
                .expect("reference")
                .state
        })
        .collect()
}

fn max_error(states: &[State], reference: &[State]) -> f64 {
    let diff = |a: &State, b: &State| {
        let (a, b) = (a.to_array(), b.to_array());
        (0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
    };
    states
        .iter()
        .zip(reference)
        .map(|(a, b)| diff(a, b))
        .fold(0.0, f64::max)
}

/// Runs `steps` steps with `step` (best of three timed runs): (max error, ns per step).
fn measure(steps: usize, reference: &[State], mut run: impl FnMut(&mut Vec<State>)) -> (f64, f64) {
    let mut states = Vec::with_capacity(steps);
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        states.clear();
        let t = Instant::now();
        run(&mut states);
        best = best.min(t.elapsed().as_secs_f64());
    }
    (max_error(&states, reference), best / steps as f64 * 1e9)
}

fn accuracy_report() {
    let problem = Preset::Paper.problem();
    let span = 10.0 * problem.params.forcing_period();
    println!(
        "accuracy over 10 forcing periods (τ = {span:.2}) vs DOP853 tol 1e-12, max state error at step ends"
    );
    let mut stepper_cost_per_time = Vec::new();
    for dt in [1e-3, 1e-2] {
        let steps = (span / dt) as usize;
        let exact = reference(&problem, dt, steps);
        for scheme in [ContactScheme::Exprb43, ContactScheme::Exprb2] {
            let (err, ns) = measure(steps, &exact, |out| {
                let mut s = Stepper::new(&problem, config(dt, scheme)).expect("stepper");
                out.extend((0..steps).map(|_| s.step(dt).expect("step").state));
            });
            println!(
                "  stepper {:<8} dt={dt:e}: error {err:.1e}, {ns:.0} ns/step",
                scheme.name()
            );
            if scheme == ContactScheme::Exprb43 {
                stepper_cost_per_time.push((dt, err, ns / dt));
            }
        }
        let (err, ns) = measure(steps, &exact, |out| rk4_run(&problem, dt, steps, out));
        println!("  rk4              dt={dt:e}: error {err:.1e}, {ns:.0} ns/step");
    }
    // RK4 at the step that costs as much per time unit as the stepper (exprb43).
    let rk4_ns = {
        let dt = 1e-3;
        let steps = (span / dt) as usize;
        let t = Instant::now();
        let mut out = Vec::with_capacity(steps);
        rk4_run(&problem, dt, steps, &mut out);
        t.elapsed().as_secs_f64() / steps as f64 * 1e9
    };
    for (dt, err, per_time) in stepper_cost_per_time {
        let rk_dt = rk4_ns / per_time;
        let steps = (span / rk_dt) as usize;
        let rk_dt = span / steps as f64;
        let exact = reference(&problem, rk_dt, steps);
        let (rk_err, ns) = measure(steps, &exact, |out| rk4_run(&problem, rk_dt, steps, out));
        println!(
            "  equal cost: stepper dt={dt:e} error {err:.1e} vs rk4 dt={rk_dt:.2e} error {rk_err:.1e} ({:.0} vs {:.0} ns per time unit)",
            per_time,
            ns / rk_dt
        );
    }
}

fn rk4_run(problem: &Problem, dt: f64, steps: usize, out: &mut Vec<State>) {
    let mut s = problem.initial;
    for k in 0..steps {
        s = rk4_step(problem, k as f64 * dt, &s, dt);
        out.push(s);
    }
}

/// Fixed start states of each kind of step for dt (copies of a stepper running the preset).
fn samples(dt: f64, scheme: ContactScheme) -> [Option<Stepper>; 5] {
    let problem = Preset::Paper.problem();
    let mut s = Stepper::new(&problem, config(dt, scheme)).expect("stepper");
    let mut found: [Option<Stepper>; 5] = [None; 5];
    let mut seen = [0usize; 5];
    for _ in 0..(50.0 / dt) as usize {
        let before = s;
        let r = s.step(dt).expect("step");
        let k = kind(before.regime(), r.events.total());
        seen[k] += 1;
        if seen[k] == 20 {
            found[k] = Some(before);
        }
    }
    found
}

/// STEPPER_BENCH=profile-<kind>: re-run every step of one kind (index into [`KINDS`]) from its
/// saved start, many times, for a sampling profiler (`perf record`).
fn profile(kind_index: usize) {
    let dt = 1e-3;
    let problem = Preset::Paper.problem();
    let switch_start = if std::env::var("STEPPER_BENCH_HERMITE").is_ok() {
        SwitchStart::Hermite
    } else {
        SwitchStart::Newton
    };
    let config = StepperConfig {
        switch_start,
        ..config(dt, ContactScheme::Exprb43)
    };
    let mut s = Stepper::new(&problem, config).expect("stepper");
    let mut starts = Vec::new();
    for _ in 0..200_000 {
        let before = s;
        let r = s.step(dt).expect("step");
        if kind(before.regime(), r.events.total()) == kind_index {
            starts.push(before);
        }
    }
    // STEPPER_BENCH_SLOWEST=k: only the k slowest of them (each timed as least of 50 runs).
    if let Some(k) = std::env::var("STEPPER_BENCH_SLOWEST")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        let cost = |start: &Stepper| {
            (0..50)
                .map(|_| {
                    let mut s = *start;
                    let t = Instant::now();
                    black_box(s.step(black_box(dt)).expect("step"));
                    t.elapsed().as_secs_f64()
                })
                .fold(f64::INFINITY, f64::min)
        };
        let mut timed: Vec<(f64, Stepper)> = starts.iter().map(|s| (cost(s), *s)).collect();
        timed.sort_by(|a, b| b.0.total_cmp(&a.0));
        timed.truncate(k);
        println!(
            "slowest {k}: {:?} ns",
            timed
                .iter()
                .map(|(t, _)| (t * 1e9) as u64)
                .collect::<Vec<_>>()
        );
        starts = timed.into_iter().map(|(_, s)| s).collect();
    }
    let t = Instant::now();
    let mut n = 0usize;
    while t.elapsed() < Duration::from_secs(10) {
        for start in &starts {
            let mut s = *start;
            black_box(s.step(black_box(dt)).expect("step"));
            n += 1;
        }
    }
    println!(
        "{} steps of kind {}: {:.0} ns each",
        n,
        KINDS[kind_index],
        t.elapsed().as_secs_f64() / n as f64 * 1e9
    );
}

fn main() {
    if let Ok(mode) = std::env::var("STEPPER_BENCH")
        && let Some(k) = mode.strip_prefix("profile-")
    {
        profile(k.parse().expect("kind index"));
        return;
    }
    for start in [SwitchStart::Newton, SwitchStart::Hermite] {
        for dt in [1e-3, 1e-2, 1e-4] {
            timing_report(dt, ContactScheme::Exprb43, start);
        }
    }
    timing_report(1e-3, ContactScheme::Exprb2, SwitchStart::Newton);
    // STEPPER_BENCH=timing: the per-step timing only (the worst step per kind), no accuracy
    // report and no criterion run.
    if std::env::var("STEPPER_BENCH").is_ok_and(|v| v == "timing") {
        return;
    }
    accuracy_report();
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(30)
        .configure_from_args();
    for scheme in [ContactScheme::Exprb43, ContactScheme::Exprb2] {
        for dt in [1e-3, 1e-2] {
            for (name, start) in KINDS.iter().zip(samples(dt, scheme)) {
                let Some(start) = start else { continue };
                let id = format!("step/{}/dt={dt:e}/{name}", scheme.name());
                c.bench_function(&id, |b| {
                    b.iter_batched_ref(
                        || start,
                        |s| s.step(black_box(dt)).expect("step"),
                        BatchSize::SmallInput,
                    )
                });
            }
        }
    }
    let problem = Preset::Paper.problem();
    let start = Stepper::new(&problem, StepperConfig::default()).expect("stepper");
    let (mut faster, mut damped) = (problem.params, problem.params);
    faster.speed_ratio = 1.6;
    damped.damping_ratio = 0.2;
    // Each change on copies of one stepper, in batches of 64 (≈ 64 KB, cache-resident: the
    // change's own cost) and in criterion's `SmallInput` batches ("cold": up to ≈ 10⁵ copies,
    // so each change also pays the write-allocation of the stepper's cache lines from memory).
    for (change, changed) in [
        ("speed change: keeps Φ", faster),
        ("damping change: recomputes Φ", damped),
    ] {
        for (copies, batch) in [
            ("", BatchSize::NumIterations(64)),
            ("cold copies, ", BatchSize::SmallInput),
        ] {
            c.bench_function(&format!("set_params ({copies}{change})"), |b| {
                b.iter_batched_ref(
                    || start,
                    |s| s.set_params(black_box(&changed)).expect("valid"),
                    batch,
                )
            });
        }
    }
    c.bench_function("rk4/one step", |b| {
        b.iter(|| rk4_step(&problem, black_box(1.0), black_box(&problem.initial), 1e-3))
    });
    c.final_summary();
}
