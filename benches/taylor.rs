//! The `taylor` method against the hybrid method and DOP853 on the contact-heavy case (`paper`,
//! η = 2.5, 100 forcing periods, every switch and the Poincaré section) at equal switch-time
//! accuracy (issue 16, `docs/MODEL.md` §16).
//!
//! Reference: a taylor run at tol 1e-15, checked against DOP853 at tol 1e-14 (their switch
//! times agree to the printed difference, about 1e-12: the floor of any comparison over 100
//! periods of this quasi-periodic rub). For each accuracy target, each method runs at the
//! loosest tolerance of the ladder {1, 5, 2}·10⁻ᵏ whose largest switch-time error meets it
//! (searched here, before timing); criterion then times those runs. The tolerances, errors and
//! the ratios to hybrid are printed to stderr and written to
//! `target/criterion/rotor-rub-taylor.csv`.

mod common;

use std::fmt::Write as _;

use common::{Case, PERIODS, Run};
use criterion::BenchmarkId;
use rotor_rub::compare::compare_events;
use rotor_rub::{Method, Options};

/// Switch-time accuracy targets.
const TARGETS: [f64; 3] = [1e-9, 1e-10, 1e-11];

fn options(method: Method, tol: f64) -> Options {
    Options {
        tol: Some(tol),
        ..Options::with_method(method)
    }
}

/// Largest switch-time error of `run` against `reference` (∞ when a switch is unmatched).
fn switch_error(run: &Run, reference: &Run) -> f64 {
    let c = compare_events(&run.events, &reference.events, f64::INFINITY);
    if c.unmatched > 0 || run.events.len() != reference.events.len() {
        f64::INFINITY
    } else {
        c.max_time_difference
    }
}

/// The loosest tolerance of `method` meeting `target`, with its error.
fn loosest(method: Method, target: f64, reference: &Run) -> Option<(f64, f64)> {
    let problem = Case::Heavy.problem();
    let valid = method.tolerance_range();
    let mut ladder = Vec::new();
    for e in (-16..=-6).rev() {
        for (m, shift) in [(1, 0), (5, -1), (2, -1)] {
            let tol: f64 = format!("{m}e{}", e + shift).parse().expect("a number");
            if valid.contains(tol) {
                ladder.push(tol);
            }
        }
    }
    ladder.into_iter().find_map(|tol| {
        let run = common::run(&problem, &options(method, tol), PERIODS);
        let err = switch_error(&run, reference);
        (err <= target).then_some((tol, err))
    })
}

fn main() {
    let mut c = common::criterion();
    let problem = Case::Heavy.problem();
    let reference = common::run(&problem, &options(Method::Taylor, 1e-15), PERIODS);
    let check = common::run(&problem, &options(Method::Dop853, 1e-14), PERIODS);
    eprintln!(
        "reference: taylor tol 1e-15, {} switches; DOP853 tol 1e-14 differs by {:.2e}",
        reference.events.len(),
        switch_error(&check, &reference)
    );
    let mut csv = String::from("target,method,tol,switch_time_error\n");
    let mut chosen = Vec::new();
    for target in TARGETS {
        for method in [Method::Taylor, Method::Hybrid, Method::Dop853] {
            match loosest(method, target, &reference) {
                Some((tol, err)) => {
                    eprintln!(
                        "target {target:e}: {:7} tol {tol:e}, switch-time error {err:.2e}",
                        method.name()
                    );
                    let _ = writeln!(csv, "{target:e},{},{tol:e},{err:e}", method.name());
                    chosen.push((target, method, tol));
                }
                None => {
                    eprintln!(
                        "target {target:e}: {:7} meets it at no tolerance",
                        method.name()
                    );
                    let _ = writeln!(csv, "{target:e},{},,", method.name());
                }
            }
        }
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .map(|p| p.join("criterion"));
    if let Some(dir) = dir {
        let _ = std::fs::create_dir_all(&dir);
        let _ = std::fs::write(dir.join("rotor-rub-taylor.csv"), &csv);
    }
    for (target, method, tol) in chosen {
        let group = format!("taylor_vs_hybrid/contact-heavy/switch-error<={target:e}");
        let mut g = c.benchmark_group(group);
        let opts = options(method, tol);
        let mut out = Run::with_capacity(4096);
        g.bench_function(
            BenchmarkId::new(method.name(), format!("tol={tol:e}")),
            |b| b.iter(|| common::run_into(&problem, &opts, PERIODS, &mut out)),
        );
        g.finish();
    }
    c.final_summary();
}
