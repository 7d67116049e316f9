//! Friction's cost (issue 12, `docs/MODEL.md` §10), over 100 forcing periods:
//!
//! * `friction/contact-heavy/<method>/mu=<μ>`: the contact-heavy case (paper preset, η = 2.5)
//!   without friction and with μ = 0.2 at ρ_R = 100 (slipping only) and ρ_R = 1 (reversals):
//!   the issue asks hybrid with μ = 0.2 to cost at most 1.5× hybrid with μ = 0;
//! * `friction/<preset>/<method>`: the `friction` (backward whirl) and `dry-whip` (sustained
//!   rolling) presets.
//!
//! Every method at tol = 1e-10 (analytic: exprb43). The event counts by kind are printed to
//! stderr before timing, so a reader sees what each run does.

mod common;

use std::collections::BTreeMap;

use common::{PERIODS, Run};
use criterion::{BenchmarkId, Criterion};
use rotor_rub::{Method, Options, Preset, Problem};

const TOL: f64 = 1e-10;

fn options(method: Method) -> Options {
    Options {
        tol: Some(TOL),
        ..Options::with_method(method)
    }
}

fn kinds(run: &Run) -> String {
    let mut counts = BTreeMap::new();
    for e in &run.events {
        *counts.entry(e.kind.name()).or_insert(0) += 1;
    }
    counts
        .iter()
        .map(|(k, n)| format!("{k} {n}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn bench(c: &mut Criterion, group: &str, label: &str, problem: &Problem, method: Method) {
    let options = options(method);
    let run = common::run(problem, &options, PERIODS);
    eprintln!("{group:28} {:8} {label:12} {}", method.name(), kinds(&run));
    let mut g = c.benchmark_group(group);
    let mut out = Run::with_capacity(4096);
    g.bench_function(BenchmarkId::new(method.name(), label), |b| {
        b.iter(|| common::run_into(problem, &options, PERIODS, &mut out));
    });
    g.finish();
}

fn main() {
    let mut c = common::criterion();
    let methods = [Method::Analytic, Method::Hybrid, Method::Dop853];
    let heavy = common::Case::Heavy.problem();
    for method in methods {
        for (label, mu, rho) in [
            ("mu=0", 0.0, 100.0),
            ("mu=0.2", 0.2, 100.0),
            ("mu=0.2,rho=1", 0.2, 1.0),
        ] {
            let mut p = heavy;
            p.params.friction_coefficient = mu;
            p.params.radius_ratio = rho;
            bench(&mut c, "friction/contact-heavy", label, &p, method);
        }
    }
    for preset in [Preset::Friction, Preset::DryWhip] {
        for method in methods {
            let group = format!("friction/{}", preset.name());
            bench(&mut c, &group, "preset", &preset.problem(), method);
        }
    }
    c.final_summary();
}
