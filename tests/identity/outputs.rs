//! Every method's output on every preset, friction and the input force included, written bit for
//! bit: the record `tests/data/outputs.txt` that refactorings are held to (`tests/output_identity.rs`).
//!
//! Where `frictionless.txt` (`fingerprint.rs`) says "friction changes nothing at μ = 0" against the
//! code before friction, this record covers what that one cannot: the taylor method, friction's
//! events (`reverse`, `roll`, `slip`), the stepper under friction and with exprb2, a speed profile
//! run by each method, and the input force. A change that moves bits on purpose records it again
//! (`RECORD=path cargo test --release --test output_identity`) and says in its commit where and by
//! how much; `DUMP=path` writes every number of every run (events, samples) as text so that two
//! dumps can be compared number by number (`scripts/compare_dumps.py`).

use std::fmt::Write as _;

use rotor_rub::speed::{SpeedPoint, SpeedProfile};
use rotor_rub::variable_speed::{VariableSpeedOptions, VariableSpeedPropagator};
use rotor_rub::{
    ContactScheme, Method, Options, Params, Preset, Problem, Propagate, Propagator, State, Stepper,
    StepperConfig, advance_to,
};

/// The problems: every planar preset (the ring presets run as matrix models: `cli/tests/cli/simulate.rs`) at its own speed and at η = 2.5, started at its start and inside
/// contact, and the paper preset with an input force.
pub fn problems() -> Vec<(String, Problem)> {
    let mut out = Vec::new();
    for preset in Preset::PLANAR {
        let base = preset.problem();
        for eta in [base.params.speed_ratio, 2.5] {
            for (start, initial) in [
                ("start", base.initial),
                ("in-contact", State::new(1.2, 0.3, -0.5, 1.5)),
            ] {
                let problem = Problem {
                    params: Params {
                        speed_ratio: eta,
                        ..base.params
                    },
                    initial,
                    ..base
                };
                out.push((format!("{}/eta={eta}/{start}", preset.name()), problem));
            }
        }
    }
    let mut forced = Preset::Paper.problem();
    forced.params.force_x = 0.3;
    forced.params.force_y = -0.1;
    out.push(("paper/input-force".to_owned(), forced));
    let mut forced_friction = Preset::Friction.problem();
    forced_friction.params.force_y = -0.2;
    out.push(("friction/input-force".to_owned(), forced_friction));
    out
}

/// How a problem is run.
#[derive(Clone, Copy, Debug)]
pub enum Variant {
    /// A method through [`Propagator`].
    Method(Options),
    /// The fixed-step stepper.
    Stepper(StepperConfig),
    /// A method on a speed profile (a ramp from the problem's speed up by 0.5 over τ ∈ [5, 25]).
    Profile(Options),
}

/// The variants: every registered method, exprb2, the stepper with exprb43 and exprb2, and every
/// method on a speed profile.
pub fn variants() -> Vec<(String, Variant)> {
    let mut out = Vec::new();
    for &method in Method::ALL {
        out.push((
            method.name().to_owned(),
            Variant::Method(Options::with_method(method)),
        ));
    }
    let exprb2 = Options {
        contact_scheme: ContactScheme::Exprb2,
        ..Options::with_method(Method::Analytic)
    };
    out.push(("analytic-exprb2".to_owned(), Variant::Method(exprb2)));
    for (name, scheme, dt) in [
        ("stepper-exprb43", ContactScheme::Exprb43, 0.01),
        ("stepper-exprb2", ContactScheme::Exprb2, 0.005),
    ] {
        let config = StepperConfig {
            dt,
            scheme,
            ..StepperConfig::default()
        };
        out.push((name.to_owned(), Variant::Stepper(config)));
    }
    for &method in Method::ALL {
        out.push((
            format!("profile-{}", method.name()),
            Variant::Profile(Options::with_method(method)),
        ));
    }
    out
}

fn numbers(out: &mut String, values: &[f64]) {
    for v in values {
        let _ = write!(out, " {:016x}", v.to_bits());
    }
}

fn event_line(out: &mut String, kind: &str, time: f64, s: &State) {
    let _ = write!(out, "event {kind}");
    numbers(out, &[time, s.x, s.y, s.vx, s.vy]);
    out.push('\n');
}

fn sample_line(out: &mut String, time: f64, s: &State) {
    out.push_str("sample");
    numbers(out, &[time, s.x, s.y, s.vx, s.vy]);
    out.push('\n');
}

/// Events and samples every 0.25 to τ0 + 30 of a propagation, bit for bit.
fn propagate(out: &mut String, p: &mut impl Propagate, t0: f64) {
    for k in 1..=120 {
        let t = t0 + 0.25 * f64::from(k);
        let r = advance_to(p, t, |e| event_line(out, e.kind.name(), e.time, &e.state));
        match r {
            Ok(s) => sample_line(out, t, &s.state),
            Err(e) => {
                let _ = writeln!(out, "error {e}");
                return;
            }
        }
    }
}

/// One run as text: one line per event (kind, time, state) and per sample (time, state), or the
/// error that stopped it.
pub fn run(problem: &Problem, variant: &Variant) -> String {
    let mut out = String::new();
    match variant {
        Variant::Method(options) => match Propagator::new(problem, options) {
            Ok(mut p) => propagate(&mut out, &mut p, problem.start_time),
            Err(e) => return format!("error {e}\n"),
        },
        Variant::Profile(options) => {
            let eta = problem.params.speed_ratio;
            let t0 = problem.start_time;
            let points = [
                SpeedPoint::new(t0, eta),
                SpeedPoint::new(t0 + 5.0, eta),
                SpeedPoint::new(t0 + 25.0, eta + 0.5),
                SpeedPoint::new(t0 + 40.0, eta + 0.5),
            ];
            let profile = match SpeedProfile::new(&points) {
                Ok(p) => p,
                Err(e) => return format!("error {e}\n"),
            };
            let options = VariableSpeedOptions::new(*options);
            match VariableSpeedPropagator::new(problem, profile, &options) {
                Ok(mut p) => propagate(&mut out, &mut p, t0),
                Err(e) => return format!("error {e}\n"),
            }
        }
        Variant::Stepper(config) => {
            let mut stepper = match Stepper::new(problem, *config) {
                Ok(s) => s,
                Err(e) => return format!("error {e}\n"),
            };
            let dt = config.dt;
            let steps = (30.0 / dt).round() as u32;
            let every = (0.25 / dt).round() as u32;
            for k in 1..=steps {
                match stepper.step(dt) {
                    Ok(report) => {
                        for e in report.events.iter() {
                            event_line(&mut out, e.kind.name(), e.time, &e.state);
                        }
                        if k % every == 0 {
                            sample_line(&mut out, report.time, &report.state);
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

/// Every (problem, variant) with its run's text.
pub fn runs() -> Vec<(String, String)> {
    let mut out = Vec::new();
    for (name, problem) in problems() {
        for (variant, v) in variants() {
            out.push((format!("{name} {variant}"), run(&problem, &v)));
        }
    }
    out
}

/// One line per run: its name, its number of events and a 64-bit FNV-1a hash of its text.
pub fn record(runs: &[(String, String)]) -> String {
    let mut out = String::new();
    for (name, text) in runs {
        let events = text.lines().filter(|l| l.starts_with("event")).count();
        let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
        for b in text.bytes() {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
        let _ = writeln!(out, "{name} events={events} {hash:016x}");
    }
    out
}
