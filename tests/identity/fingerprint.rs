//! The output of every method on a fixed set of frictionless problems, written bit for bit: the
//! μ = 0 identity test compares it with the record made by the code before friction existed
//! (`tests/data/frictionless.txt`). This file compiles against that older code too (it uses
//! only the API both share), which is how the record was made: in a worktree of commit c4bc988
//! (the last before friction), this file as `tests/identity/fingerprint.rs` and a test
//! `tests/record_before.rs` that declares `mod identity { pub mod fingerprint; }` and writes
//! `identity::fingerprint::record()` to a file, run with `cargo test --test record_before`.
//!
//! A later change that moves results in their last bits (the switch search, a bound) is applied
//! to that old code too, and the record made again: `before-friction.patch` (next to this file,
//! `git apply` in the worktree of c4bc988) is every such change so far — a failed proof after a
//! sign change's refinement searches [a, x] instead of refining again (first switches move by
//! ≤ 3 ulps); the harmonic amplitude σ1 from two sums of squares instead of a nested root (a
//! bound: the analytic method's first switches move by ≤ 7e-15 relative, through its step
//! control); the stepper's Φ(dt) and (away from resonance) G(dt) from the generated step
//! formulas `free_step_transition`, `free_step_forcing` instead of six closed-form evaluations
//! on unit inputs (the stepper's lines only; every propagating method unchanged); the switch
//! refinement's progress test counting a halved residual as progress as well as a halved bracket
//! (Newton converging from one side no longer forced into a bisection: 6 of the 144 lines move,
//! switch times by ≤ 1e-13 relative, states by ≤ 3e-11 under exprb2's step control). So the
//! record stays "friction changes nothing at μ = 0", not "nothing changed".

use std::fmt::Write as _;

use rotor_rub::{
    ContactScheme, Method, Options, Params, Problem, Propagator, State, Stepper, StepperConfig,
    advance_to,
};

/// The frictionless problems: the paper presets and the friction presets' stator with μ = 0
/// (isotropic K = 100 with the paper's offset; isotropic K = 300 centred), each at η = 1, 1.5
/// and 2.5, started at the table's start (0.1, 0.1, 0, 0) and inside contact.
pub fn problems() -> Vec<(String, Problem)> {
    let paper = Params::DEFAULT;
    let paper_text = Params {
        k_xx: 2.0,
        k_xy: 2.0,
        k_yx: 2.0,
        offset_x: 0.0,
        offset_y: 0.0,
        ..Params::DEFAULT
    };
    let friction = Params {
        k_xx: 100.0,
        k_xy: 0.0,
        k_yx: 0.0,
        k_yy: 100.0,
        ..Params::DEFAULT
    };
    let dry_whip = Params {
        k_xx: 300.0,
        k_xy: 0.0,
        k_yx: 0.0,
        k_yy: 300.0,
        offset_x: 0.0,
        offset_y: 0.0,
        ..Params::DEFAULT
    };
    let mut out = Vec::new();
    for (name, params) in [
        ("paper", paper),
        ("paper-text", paper_text),
        ("friction", friction),
        ("dry-whip", dry_whip),
    ] {
        for eta in [1.0, 1.5, 2.5] {
            for (start_name, initial) in [
                ("start", State::new(0.1, 0.1, 0.0, 0.0)),
                ("in-contact", State::new(1.2, 0.3, -0.5, 1.5)),
            ] {
                let problem = Problem {
                    params: Params {
                        speed_ratio: eta,
                        ..params
                    },
                    initial,
                    start_time: 0.0,
                };
                out.push((format!("{name}/eta={eta}/{start_name}"), problem));
            }
        }
    }
    out
}

/// The method variants compared: every registered method, exprb2 besides exprb43, and the
/// fixed-step stepper (exprb43, dt = 0.01).
pub fn variants() -> Vec<(&'static str, Option<Options>)> {
    let mut out: Vec<(&'static str, Option<Options>)> = vec![
        ("analytic", Some(Options::with_method(Method::Analytic))),
        (
            "analytic-exprb2",
            Some(Options {
                contact_scheme: ContactScheme::Exprb2,
                ..Options::with_method(Method::Analytic)
            }),
        ),
        ("hybrid", Some(Options::with_method(Method::Hybrid))),
        ("dop853", Some(Options::with_method(Method::Dop853))),
        ("rk45", Some(Options::with_method(Method::Rk45))),
    ];
    out.push(("stepper", None));
    out
}

fn bits(out: &mut String, values: &[f64]) {
    for v in values {
        let _ = write!(out, " {:016x}", v.to_bits());
    }
}

/// Events and samples (every 0.25 time units to τ = 30) of one run, bit for bit: one line per
/// event (kind, time, state) and per sample (time, state), or the error that stopped it.
pub fn run(problem: &Problem, options: Option<&Options>) -> String {
    let mut out = String::new();
    match options {
        Some(options) => {
            let mut p = match Propagator::new(problem, options) {
                Ok(p) => p,
                Err(e) => return format!("error {e}\n"),
            };
            for k in 1..=120 {
                let t = 0.25 * f64::from(k);
                let r = advance_to(&mut p, t, |e| {
                    let _ = write!(out, "event {}", e.kind.name());
                    bits(
                        &mut out,
                        &[e.time, e.state.x, e.state.y, e.state.vx, e.state.vy],
                    );
                    out.push('\n');
                });
                match r {
                    Ok(s) => {
                        out.push_str("sample");
                        bits(&mut out, &[t, s.state.x, s.state.y, s.state.vx, s.state.vy]);
                        out.push('\n');
                    }
                    Err(e) => {
                        let _ = writeln!(out, "error {e}");
                        return out;
                    }
                }
            }
        }
        None => {
            let config = StepperConfig {
                dt: 0.01,
                ..StepperConfig::default()
            };
            let mut stepper = match Stepper::new(problem, config) {
                Ok(s) => s,
                Err(e) => return format!("error {e}\n"),
            };
            for k in 0..3000 {
                match stepper.step(0.01) {
                    Ok(report) => {
                        for e in report.events.iter() {
                            let _ = write!(out, "event {}", e.kind.name());
                            bits(
                                &mut out,
                                &[e.time, e.state.x, e.state.y, e.state.vx, e.state.vy],
                            );
                            out.push('\n');
                        }
                        if k % 25 == 24 {
                            let s = report.state;
                            out.push_str("sample");
                            bits(&mut out, &[report.time, s.x, s.y, s.vx, s.vy]);
                            out.push('\n');
                        }
                    }
                    Err(e) => {
                        let _ = writeln!(out, "error {e}");
                        return out;
                    }
                }
            }
        }
    }
    out
}

/// One line per (problem, variant): its name and a 64-bit FNV-1a hash of [`run`]'s text, plus
/// the number of events (so that a difference is easy to place).
pub fn record() -> String {
    let mut out = String::new();
    for (name, problem) in problems() {
        for (variant, options) in variants() {
            let text = run(&problem, options.as_ref());
            let events = text.lines().filter(|l| l.starts_with("event")).count();
            let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
            for b in text.bytes() {
                hash ^= u64::from(b);
                hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
            }
            let _ = writeln!(out, "{name} {variant} events={events} {hash:016x}");
        }
    }
    out
}
