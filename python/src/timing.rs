//! The Rust side of `simulate` timed without Python (for scripts/bench_python.py): the same
//! problem, options and pass as [`crate::runs::simulate`], repeated in a Rust loop, so the Python
//! call's overhead is measured in one process against the call it wraps.

use std::time::Instant;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::Method;
use rotor_rub_cli::trajectory::{self, uniform_times};

use crate::errors::cli;
use crate::inputs;

/// Seconds per call of the Rust pipeline behind `simulate(preset=…, periods=…, method=…,
/// samples=…, **params)`, the minimum over `rounds` rounds of `repeats` calls.
#[pyfunction]
#[pyo3(signature = (repeats, rounds, *, preset=None, periods=20.0, method=None, samples=1001,
    params=None))]
#[allow(clippy::too_many_arguments)]
pub fn rust_simulate_seconds(
    py: Python<'_>,
    repeats: usize,
    rounds: usize,
    preset: Option<&str>,
    periods: f64,
    method: Option<&str>,
    samples: usize,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<f64> {
    // The keyword overrides as Rust values, converted once: a Rust caller has them already.
    let set = inputs::overrides(params)?;
    let preset = preset
        .map(rotor_rub_cli::problem::parse_preset)
        .transpose()
        .map_err(crate::errors::input)?;
    let method = method
        .map(rotor_rub_cli::options::parse_method)
        .transpose()
        .map_err(crate::errors::input)?
        .unwrap_or(Method::Analytic);
    py.detach(|| {
        let mut best = f64::INFINITY;
        for _ in 0..rounds.max(1) {
            let started = Instant::now();
            for _ in 0..repeats.max(1) {
                let problem = rotor_rub_cli::problem::ProblemArgs {
                    preset,
                    config: None,
                    set: set.clone(),
                }
                .build_naming(&[], crate::inputs::KEYWORDS)?;
                let options = rotor_rub_cli::options::SchemeArgs {
                    tol: None,
                    contact_scheme: None,
                    step: None,
                }
                .options(method)?;
                let end = periods * problem.params.forcing_period();
                let budget = rotor_rub_cli::limits::LimitArgs {
                    max_work: 1_000_000_000,
                }
                .budget();
                budget.plan("samples", samples as u64)?;
                let propagator = trajectory::start(&problem, &options)?;
                let mut tracker = budget.run(problem.start_time, end);
                let out = trajectory::run_collect(
                    propagator,
                    end,
                    uniform_times(problem.start_time, end, samples),
                    &mut tracker,
                )?;
                std::hint::black_box(out);
            }
            best = best.min(started.elapsed().as_secs_f64() / repeats.max(1) as f64);
        }
        Ok(best)
    })
    .map_err(cli)
}
