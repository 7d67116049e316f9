//! Sweeps for Python: the Poincaré section, its response class and optionally the largest
//! Lyapunov exponent at each point of a list of parameter points (one or more swept
//! parameters), in parallel on a thread pool of the call's own (fork-safe: no global pool) with
//! the GIL released, under a watch (Ctrl-C, progress). The single-machine sweep and each Dask
//! chunk call this same function; a point's result depends on that point alone, so any chunking
//! gives the same bits — except in continuation, where each point of a line starts from the
//! previous point's last section state.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use numpy::{IntoPyArray, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use rotor_rub::{Options, Parameter, Problem, State};
use rotor_rub_cli::error::{CliError, EXIT_INPUT, num};
use rotor_rub_cli::limits::{Budget, add_counts, fits_memory};
use rotor_rub_cli::options::{DefaultMethod, Survey};
use rotor_rub_cli::poincare::{Section, section};
use rotor_rub_cli::problem::parse_parameter;
use rotor_rub_cli::watch::{EXIT_INTERRUPTED, Watch};

use crate::args::{self, flag};
use crate::errors::{cli, input};
use crate::inputs::{self, MethodKeywords};
use crate::meta;
use crate::runs::states;
use crate::watch::{self, Progress};

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// `name = value, name = value` for messages.
fn label(names: &[Parameter], values: &[f64]) -> String {
    names
        .iter()
        .zip(values)
        .map(|(p, v)| format!("{p} = {}", num(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What one sweep runs: every point's problem and the settings they share.
struct Plan<'a> {
    names: &'a [Parameter],
    points: &'a [(Vec<f64>, Problem)],
    options: Options,
    transient: u64,
    keep: usize,
    lyapunov: bool,
}

impl Plan<'_> {
    /// The section of point `i`, from `initial` when given (continuation).
    fn point(
        &self,
        i: usize,
        initial: Option<State>,
        budget: &Budget,
    ) -> Result<Section, CliError> {
        let (values, problem) = &self.points[i];
        let problem = Problem {
            initial: initial.unwrap_or(problem.initial),
            ..*problem
        };
        section(
            &problem,
            &self.options,
            self.transient,
            self.keep,
            self.lyapunov,
            budget,
        )
        .map_err(|e| e.context(&label(self.names, values)))
    }

    /// Points `first .. first + len` in order, each from the previous one's last section state
    /// (the first from its own initial state); a failed point leaves the next to start from the
    /// last good state.
    fn line(
        &self,
        first: usize,
        len: usize,
        budget: &Budget,
        done: &AtomicUsize,
    ) -> Vec<Result<Section, CliError>> {
        let mut initial = None;
        (first..first + len)
            .map(|i| {
                let r = self.point(i, initial, budget);
                if let Ok(s) = &r {
                    initial = s.points.last().copied().or(initial);
                }
                done.fetch_add(1, Ordering::Relaxed);
                r
            })
            .collect()
    }
}

/// Poincaré points, response class and (with `lyapunov`) the largest Lyapunov exponent at every
/// row of `points` (columns: the parameters `names`), each from the problem's initial state —
/// or, with `line` = n, in consecutive lines of n points run in continuation.
#[pyfunction]
#[pyo3(signature = (names, points, *, preset=None, config=None, transient=None, keep=None,
    lyapunov=None, line=None, method=None, tol=None, contact_scheme=None, step=None,
    skip_errors=None, threads=None, max_work=None, progress=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep_points<'py>(
    py: Python<'py>,
    names: Vec<String>,
    points: PyReadonlyArray2<'py, f64>,
    preset: Option<&str>,
    config: Option<String>,
    transient: Any<'_, 'py>,
    keep: Any<'_, 'py>,
    lyapunov: Any<'_, 'py>,
    line: Any<'_, 'py>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    skip_errors: Any<'_, 'py>,
    threads: Any<'_, 'py>,
    max_work: Any<'_, 'py>,
    progress: Any<'_, 'py>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = inputs::problem(preset, inputs::path(config), params)?;
    let keywords = MethodKeywords {
        method,
        tol,
        contact_scheme,
        step,
    };
    let options = inputs::options(&keywords, Survey::METHOD)?;
    let transient = transient.map_or(Ok(200), |t| args::count("transient", t, 0))?;
    let keep = keep.map_or(Ok(50), |k| args::count("keep", k, 1))?;
    let lyapunov = lyapunov.map_or(Ok(false), |l| flag("lyapunov", l))?;
    let skip_errors = skip_errors.map_or(Ok(false), |s| flag("skip_errors", s))?;
    let threads = match threads.filter(|t| !t.is_none()) {
        None => None,
        Some(t) => Some(args::count("threads", t, 1)?),
    };
    add_counts(("transient", transient), ("keep", keep)).map_err(cli)?;
    let names = names
        .iter()
        .map(|n| parse_parameter(n).map_err(input))
        .collect::<PyResult<Vec<Parameter>>>()?;
    let shape = points.shape();
    let (rows, columns) = (shape[0], shape.get(1).copied().unwrap_or(0));
    if columns != names.len() {
        return Err(input(format!(
            "points has {columns} columns but {} parameter names were given",
            names.len()
        )));
    }
    let line = match line.filter(|l| !l.is_none()) {
        None => 1,
        Some(l) => args::count("line", l, 1)?,
    };
    let line = usize::try_from(line).unwrap_or(usize::MAX).min(rows.max(1));
    let array = points.as_array();
    let problems = (0..rows)
        .map(|i| {
            let values: Vec<f64> = array.row(i).iter().copied().collect();
            let mut problem = base;
            for (p, v) in names.iter().zip(&values) {
                p.set(&mut problem, *v);
            }
            problem
                .validate()
                .map(|()| (values.clone(), problem))
                .map_err(|e| input(format!("{} (swept): {e}", label(&names, &values))))
        })
        .collect::<PyResult<Vec<(Vec<f64>, Problem)>>>()?;
    let planned = (rows as u64).saturating_mul(keep);
    fits_memory(
        "points × keep (rows)",
        planned,
        std::mem::size_of::<State>() + 16,
    )
    .map_err(cli)?;
    let keep = usize::try_from(keep).unwrap_or(usize::MAX);
    let budget = inputs::budget(max_work)?;
    let lyapunov_work = if lyapunov { planned } else { 0 };
    budget
        .plan("points × keep", planned.saturating_add(lyapunov_work))
        .map_err(cli)?;
    rotor_rub_cli::trajectory::start(&base, &options).map_err(cli)?;
    let plan = Plan {
        names: &names,
        points: &problems,
        options,
        transient,
        keep,
        lyapunov,
    };
    let done = AtomicUsize::new(0);
    let progress = Progress::new(progress, rows as f64);
    let results = watch::beside(
        py,
        progress,
        || done.load(Ordering::Relaxed) as f64,
        |watch: Arc<Watch>| {
            let budget = budget.watched(watch);
            // A pool per call: rayon's global pool does not survive a fork.
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads.map_or(0, |n| usize::try_from(n).unwrap_or(usize::MAX)))
                .build()
                .map_err(|e| CliError::input(format!("threads: cannot start them: {e}")))?;
            let starts: Vec<usize> = (0..rows).step_by(line).collect();
            let lines: Vec<Vec<Result<Section, CliError>>> = pool.install(|| {
                starts
                    .par_iter()
                    .map(|&first| plan.line(first, line.min(rows - first), &budget, &done))
                    .collect()
            });
            Ok(lines.into_iter().flatten().collect::<Vec<_>>())
        },
    )?;
    let (mut index, mut period, mut kept, mut skipped, mut failed) =
        (vec![], vec![], vec![], vec![], vec![]);
    let mut responses: Vec<Option<String>> = Vec::with_capacity(rows);
    let mut exponents: Vec<f64> = Vec::with_capacity(rows);
    for (i, r) in results.into_iter().enumerate() {
        match r {
            Ok(s) => {
                for (state, k) in s.points.iter().zip(transient..) {
                    index.push(i as u64);
                    period.push(k);
                    kept.push(*state);
                }
                responses.push(Some(s.response.to_string()));
                exponents.push(s.lyapunov.unwrap_or(f64::NAN));
            }
            // A refused run (over max_work) stops the sweep even with skip_errors, as in the CLI.
            Err(e) if skip_errors && e.code != EXIT_INPUT && e.code != EXIT_INTERRUPTED => {
                skipped.push(crate::errors::keywords(&e.message));
                failed.push(i as u64);
                responses.push(None);
                exponents.push(f64::NAN);
            }
            Err(e) => return Err(cli(e)),
        }
    }
    let out = PyDict::new(py);
    out.set_item("index", index.into_pyarray(py))?;
    out.set_item("period", period.into_pyarray(py))?;
    out.set_item("state", states(py, &kept)?)?;
    out.set_item("skipped", skipped)?;
    out.set_item("failed", failed.into_pyarray(py))?;
    out.set_item("response", responses)?;
    out.set_item("lyapunov", lyapunov.then(|| exponents.into_pyarray(py)))?;
    out.set_item("problem", meta::problem(py, &base, &options)?)?;
    Ok(out)
}
