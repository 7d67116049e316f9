//! Sweeps for Python: the Poincaré section at each point of a list of parameter points (one or
//! more swept parameters), in parallel in Rust with the GIL released. The single-machine sweep and
//! each Dask chunk call this same function; a point's result depends on that point alone, so any
//! chunking gives the same bits.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::{Parameter, Problem, State};
use rotor_rub_cli::error::{CliError, EXIT_INPUT, num};
use rotor_rub_cli::limits::{add_counts, fits_memory};
use rotor_rub_cli::options::{DefaultMethod, Survey};
use rotor_rub_cli::problem::parse_parameter;
use rotor_rub_cli::sweep::sections;

use crate::errors::{cli, input};
use crate::inputs;
use crate::runs::states;

/// `name = value, name = value` for messages.
fn label(names: &[Parameter], values: &[f64]) -> String {
    names
        .iter()
        .zip(values)
        .map(|(p, v)| format!("{p} = {}", num(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Poincaré points at every row of `points` (columns: the parameters `names`), from the same
/// initial state: rows (point index, period, state) in point order, then period.
#[pyfunction]
#[pyo3(signature = (names, points, *, preset=None, config=None, transient=200, keep=50,
    method=None, tol=None, contact_scheme=None, step=None, skip_errors=false, threads=None,
    max_work=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep_points<'py>(
    py: Python<'py>,
    names: Vec<String>,
    points: PyReadonlyArray2<'py, f64>,
    preset: Option<&str>,
    config: Option<PathBuf>,
    transient: i64,
    keep: i64,
    method: Option<&str>,
    tol: Option<f64>,
    contact_scheme: Option<&str>,
    step: Option<f64>,
    skip_errors: bool,
    threads: Option<usize>,
    max_work: Option<f64>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = inputs::problem(preset, config, params)?;
    let options = inputs::options(method, Survey::METHOD, tol, contact_scheme, step)?;
    let transient = inputs::count("transient", transient, 0)?;
    let keep = inputs::count("keep", keep, 1)?;
    add_counts(("--transient", transient), ("--keep", keep)).map_err(cli)?;
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
    let budget = inputs::budget(max_work)?;
    budget.plan("points × keep", planned).map_err(cli)?;
    rotor_rub_cli::trajectory::start(&base, &options).map_err(cli)?;
    let run = || {
        sections(
            &problems,
            &options,
            transient,
            keep,
            &budget,
            |values| label(&names, values),
            || {},
        )
    };
    let results: Vec<Result<Vec<State>, CliError>> = py
        .detach(|| match threads {
            None => Ok(run()),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map(|pool| pool.install(run))
                .map_err(|e| format!("cannot start {n} threads: {e}")),
        })
        .map_err(input)?;
    let (mut index, mut period, mut kept, mut skipped) = (vec![], vec![], vec![], vec![]);
    for (i, r) in results.into_iter().enumerate() {
        match r {
            Ok(points) => {
                for (s, k) in points.into_iter().zip(transient..) {
                    index.push(i as u64);
                    period.push(k);
                    kept.push(s);
                }
            }
            // A refused run (over max_work) stops the sweep even with skip_errors, as in the CLI.
            Err(e) if skip_errors && e.code != EXIT_INPUT => skipped.push(e.message),
            Err(e) => return Err(cli(e)),
        }
    }
    let out = PyDict::new(py);
    out.set_item("index", index.into_pyarray(py))?;
    out.set_item("period", period.into_pyarray(py))?;
    out.set_item("state", states(py, &kept)?)?;
    out.set_item("skipped", skipped)?;
    Ok(out)
}
