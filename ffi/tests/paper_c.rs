//! `examples/paper.c`, compiled with the system C compiler (`$CC`, else `cc`) and linked against
//! this crate's static library, agrees with the Rust API.
//!
//! The staticlib is found next to this test binary: cargo builds the library (all its crate
//! types) before the tests and puts `librotor_rub_ffi.a` in the profile folder, the parent of
//! the test binary's `deps/` folder.
//!
//! # Why these checks and tolerances
//! The paper preset at η = 1.5 is chaotic (`docs/MODEL.md` §9): two accurate methods agree on the
//! switch times only up to a predictability horizon. Measured: the analytic method at its
//! default tolerance and DOP853 at 1e-12 differ by O(1) in switch time from τ ≈ 120 (≈ 29
//! periods) on; over 100 periods they do not even agree on the switch count. So:
//! 1. The C run equals the Rust [`Stepper`] run (same code, same arithmetic): same switches,
//!    times within 1e-12 (in practice bit-identical).
//! 2. Over the first 20 periods (97 switches, before the horizon) the C switch times match the
//!    event-driven analytic propagator at default tolerance: same kinds, within 1e-6. Measured
//!    error 1.1e-8, the analytic default's own error (vs DOP853 1e-12: 1.1e-8); the stepper at
//!    dt = 1e-3 is within 2e-10 of DOP853 (exprb43 local error ~(1e-3)⁵ per sub-step, exact
//!    free flight), so 1e-6 leaves two orders of magnitude for growth before the horizon.
//! 3. Over all 100 periods, every switch is checked against the analytic propagator restarted
//!    from the C checkpoint state before it (every 1000 steps, 1 time unit): one time unit is
//!    far below the horizon, so the comparison measures accuracy, not chaos. Same kinds and
//!    count per interval, times and checkpoint states within [`SHADOW_TOL`] = 1e-7. The
//!    analytic method at its default tolerance accumulates 1.1e-8 of switch-time error over
//!    20 free-running periods (84 time units, chaotic growth included), the stepper at
//!    dt = 1e-3 less than 2e-10; over one time unit both are far below 1e-8, so 1e-7 is a
//!    safe bound that still catches any real defect (a wrong step, a missed or shifted switch
//!    moves times and states by ≥ 1e-4). Measured: 1e-10 (times), 2.4e-10 (states).

use rotor_rub::{
    EventKind, Options, Preset, Problem, Propagate, Propagator, State, Stepper, StepperConfig,
    advance_to, events,
};

/// Tolerance of the per-interval (shadowing) comparison: times in time units, states in
/// clearance units (see the module docs; the measured discrepancy is printed).
const SHADOW_TOL: f64 = 1e-7;

struct Switch {
    kind: EventKind,
    time: f64,
}

#[derive(Clone, Copy)]
struct Checkpoint {
    time: f64,
    state: State,
}

#[path = "common/c_example.rs"]
mod c_example;

/// `examples/paper.c` run with `args` (none: the open-loop run; `control …`: the controller).
fn compile_and_run(args: &[&str]) -> String {
    let binary = if args.is_empty() {
        "rotor_rub_paper_c"
    } else {
        "rotor_rub_paper_c_control"
    };
    c_example::compile_and_run("paper", binary, args)
}

fn parse(output: &str) -> (Vec<Switch>, Vec<Checkpoint>) {
    let (mut switches, mut checkpoints) = (Vec::new(), Vec::new());
    for line in output.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let num = |i: usize| -> f64 { words[i].parse().expect("number") };
        match words.first() {
            Some(&"switch") => switches.push(Switch {
                kind: if words[2] == "enter" {
                    EventKind::Enter
                } else {
                    EventKind::Exit
                },
                time: num(3),
            }),
            Some(&"state") => checkpoints.push(Checkpoint {
                time: num(2),
                state: State::new(num(3), num(4), num(5), num(6)),
            }),
            _ => {}
        }
    }
    (switches, checkpoints)
}

#[test]
fn paper_c_agrees_with_the_rust_api() {
    let (switches, checkpoints) = parse(&compile_and_run(&[]));
    let problem = Preset::Paper.problem();
    let period = problem.params.forcing_period();
    let dt = 1e-3;
    assert!(!switches.is_empty() && checkpoints.len() >= 418);

    // 1. The same run through the Rust API.
    let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(dt)).expect("stepper");
    let steps = (100.0 * period / dt - 1e-9).ceil() as usize;
    let mut rust = Vec::new();
    for _ in 0..steps {
        let r = stepper.step(dt).expect("step");
        assert_eq!(r.events.dropped(), 0);
        rust.extend(r.events.iter().map(|e| (e.kind, e.time)));
    }
    assert_eq!(
        rust.len(),
        switches.len(),
        "switch count, C vs Rust stepper"
    );
    for (c, (kind, time)) in switches.iter().zip(&rust) {
        assert_eq!(c.kind, *kind);
        assert!(
            (c.time - time).abs() <= 1e-12,
            "C {} vs Rust {time}",
            c.time
        );
    }

    // 2. Free-running agreement with the analytic propagator over the first 20 periods.
    let horizon = 20.0 * period;
    let mut analytic = Propagator::new(&problem, &Options::default()).expect("analytic");
    let reference: Vec<_> = events(&mut analytic, horizon)
        .map(|e| e.expect("propagates"))
        .collect();
    let early: Vec<_> = switches.iter().filter(|s| s.time <= horizon).collect();
    assert_eq!(
        early.len(),
        reference.len(),
        "switches in the first 20 periods"
    );
    let mut worst = 0.0f64;
    for (c, r) in early.iter().zip(&reference) {
        assert_eq!(c.kind, r.kind);
        worst = worst.max((c.time - r.time).abs());
    }
    assert!(worst <= 1e-6, "20-period switch-time error {worst:e}");

    // 3. Every switch of the 100 periods against the analytic propagator restarted at the
    // checkpoint before it.
    let mut start = Checkpoint {
        time: problem.start_time,
        state: problem.initial,
    };
    let (mut worst_time, mut worst_state, mut next) = (0.0f64, 0.0f64, 0);
    for end in &checkpoints {
        let restart = Problem {
            initial: start.state,
            start_time: start.time,
            ..problem
        };
        let mut p = Propagator::new(&restart, &Options::default()).expect("restart");
        let mut found = Vec::new();
        let sample = advance_to(&mut p, end.time, |e| found.push(*e)).expect("propagates");
        for e in &found {
            let c = &switches[next];
            assert_eq!(c.kind, e.kind, "switch {next} kind");
            worst_time = worst_time.max((c.time - e.time).abs());
            next += 1;
        }
        let d = sample.state.to_array();
        let c = end.state.to_array();
        worst_state = (0..4).fold(worst_state, |w, i| w.max((d[i] - c[i]).abs()));
        assert_eq!(p.time(), end.time);
        start = *end;
    }
    let tail = switches.iter().filter(|s| s.time > start.time).count();
    assert_eq!(
        next + tail,
        switches.len(),
        "every switch checked or after the last checkpoint"
    );
    println!("shadowing: {next} switches, worst time {worst_time:e}, worst state {worst_state:e}");
    assert!(worst_time <= SHADOW_TOL, "switch time error {worst_time:e}");
    assert!(
        worst_state <= SHADOW_TOL,
        "checkpoint state error {worst_state:e}"
    );
}

/// `paper control 0.5 1.0`: the fixed-rate loop with a PD controller through
/// `rotor_rub_stepper_set_input_force` equals the same loop on the Rust API (same arithmetic,
/// C99 without contraction), and rubs far less than the open loop.
#[test]
fn paper_c_controller_loop_agrees_with_rust_and_reduces_contacts() {
    let output = compile_and_run(&["control", "0.5", "1.0"]);
    let (switches, checkpoints) = parse(&output);
    let summary: Vec<u64> = output
        .lines()
        .find_map(|l| l.strip_prefix("summary "))
        .expect("summary line")
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let problem = Preset::Paper.problem();
    let dt = 1e-3;
    let steps = (100.0 * problem.params.forcing_period() / dt - 1e-9).ceil() as usize;
    let (kp, kd) = (0.5, 1.0);
    let mut stepper = Stepper::new(&problem, StepperConfig::with_dt(dt)).expect("stepper");
    let (mut rust, mut state, mut states) = (Vec::new(), problem.initial, Vec::new());
    let (ox, oy) = (problem.params.offset_x, problem.params.offset_y);
    for k in 1..=steps {
        let fx = -kp * (state.x - ox) - kd * state.vx;
        let fy = -kp * (state.y - oy) - kd * state.vy;
        stepper.set_input_force(fx, fy).expect("force in range");
        let r = stepper.step(dt).expect("step");
        rust.extend(r.events.iter().map(|e| (e.kind, e.time)));
        state = r.state;
        if k % 1000 == 0 {
            states.push(r.state);
        }
    }
    assert_eq!(states.len(), checkpoints.len());
    for (c, r) in checkpoints.iter().zip(&states) {
        assert_eq!(c.state, *r, "C and Rust loops, bit for bit");
    }
    assert_eq!(switches.len(), rust.len());
    let open_loop = parse(&compile_and_run(&[])).0.len();
    println!(
        "switches over 100 periods: open loop {open_loop}, PD {}",
        switches.len()
    );
    assert!(
        switches.len() * 4 <= open_loop,
        "{} vs {open_loop}",
        switches.len()
    );
    assert_eq!(summary[4], 0, "no step exceeded its budget at dt = 1e-3");
}
