//! Sweep throughput: Poincaré points per second for a 64-value sweep of the speed ratio η over
//! [1, 3.5] on the `paper` preset (200 transient periods skipped, 50 points kept per value, as
//! `rotor-rub sweep`'s defaults), in process, the values spread over the cores with rayon
//! (`rayon` is a dev-dependency; this machine has 2 cores). Criterion reports the throughput in
//! points per second. Hybrid and DOP853 at tol = 1e-10. Hybrid and DOP853 at tol = 1e-10.

mod common;

use std::time::Duration;

use common::Setting;
use criterion::{BenchmarkId, Throughput};
use rayon::prelude::*;
use rotor_rub::{Method, Preset, Propagator, poincare};

const VALUES: usize = 64;
const TRANSIENT: usize = 200;
const KEEP: usize = 50;

/// Poincaré points of one sweep (points of values that fail are not counted).
fn sweep(setting: Setting) -> usize {
    (0..VALUES)
        .into_par_iter()
        .map(|i| {
            let mut problem = Preset::Paper.problem();
            problem.params.speed_ratio = 1.0 + 2.5 * i as f64 / (VALUES - 1) as f64;
            let Ok(mut p) = Propagator::new(&problem, &setting.options()) else {
                return 0;
            };
            let mut kept = 0;
            for (k, point) in
                poincare(&mut p, problem.params.speed_ratio, TRANSIENT + KEEP + 1).enumerate()
            {
                let Ok(point) = point else { break };
                if k > TRANSIENT {
                    std::hint::black_box(point);
                    kept += 1;
                }
            }
            kept
        })
        .sum()
}

fn main() {
    let mut c = common::criterion();
    eprintln!(
        "sweep: {VALUES} values × {KEEP} points, rayon on {} threads",
        rayon::current_num_threads()
    );
    let mut g = c.benchmark_group(format!(
        "sweep_{VALUES}_speed_ratios/rayon-{}-threads",
        rayon::current_num_threads()
    ));
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(4));
    g.throughput(Throughput::Elements((VALUES * KEEP) as u64));
    // The analytic method (exprb43) is left out: its contact phase makes one sweep take seconds
    // (see the propagation benches for its cost per period).
    for setting in [
        Setting::tol(Method::Hybrid, 1e-10),
        Setting::tol(Method::Dop853, 1e-10),
    ] {
        let points = sweep(setting);
        assert_eq!(points, VALUES * KEEP, "{} lost points", setting.name());
        g.bench_function(
            BenchmarkId::new(setting.name(), setting.knob_label()),
            |b| b.iter(|| sweep(setting)),
        );
    }
    g.finish();
    c.final_summary();
}
