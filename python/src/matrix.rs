//! Rotors from matrices for Python (issue 29; `rotor_rub.Model`, `python/rotor_rub/_model.py`):
//! the model as the Python layer hands it over (a dict of numpy arrays and numbers, SI units) →
//! the CLI library's [`ModelSpec`], so the checks, the statement in clearances, the modes and
//! the result assembly are the model files' (`cli/src/model_file`). Errors are ValueErrors
//! naming the Python keyword (`M`, `rub.clearance`, `unbalance[0].m_e`, …).
//!
//! [`simulate_matrix`] is THE Python entry point of a matrix run: it calls the CLI library's
//! `model_file::simulate_matrix` (the matrix propagator); the result dict (arrays, columns) is
//! assembled here and in the Python layer.

use numpy::{IntoPyArray, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rotor_rub::{Method, Options};
use rotor_rub_cli::model_file::{
    self, Dense, Key, MatrixRun, MatrixRunError, ModelError, ModelSpec, RubSpec, SpeedPoint,
    UnbalanceSpec,
};
use rotor_rub_cli::options::describe;
use rotor_rub_cli::trajectory::uniform_times;

use crate::args;
use crate::errors::{cli, input};
use crate::inputs::{self, MethodKeywords};

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// How Python names a model value (the keywords of `Model.from_matrices` and `Rub`).
pub fn python_name(key: Key) -> String {
    match key {
        Key::File => "model".into(),
        Key::Dofs => "dofs".into(),
        Key::Mass => "M".into(),
        Key::Damping => "C".into(),
        Key::Gyroscopic => "G".into(),
        Key::Stiffness => "K".into(),
        Key::Speed => "speed".into(),
        Key::Phase => "phase".into(),
        Key::Unbalance(i, f) => format!("unbalance[{i}].{f}"),
        Key::Force => "force".into(),
        Key::Rub(f) => format!("rub.{f}"),
        Key::InitialPositions => "initial (positions)".into(),
        Key::InitialVelocities => "initial (velocities)".into(),
        Key::SpeedDependent(i, f) => format!("speed_dependent[{i}].{f}"),
    }
}

/// A model error as a ValueError naming the Python keyword.
fn model_error(e: &ModelError) -> PyErr {
    PyValueError::new_err(e.message_with(&python_name(e.key)))
}

fn dense(name: &str, a: &Bound<'_, PyAny>) -> PyResult<Dense> {
    let array: PyReadonlyArray2<'_, f64> = a.extract().map_err(|_| {
        input(format!(
            "{name} must be a 2-D array of real numbers (float64), not {}",
            args::shown(a)
        ))
    })?;
    let shape = array.shape();
    let (rows, cols) = (shape[0], shape[1]);
    let data: Vec<f64> = array.as_array().iter().copied().collect();
    Ok(Dense { rows, cols, data })
}

fn item<'py>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<Bound<'py, PyAny>> {
    d.get_item(key)?.ok_or_else(|| {
        input(format!(
            "the model lacks '{key}' (rotor_rub.Model builds it)"
        ))
    })
}

fn optional<'py>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
    Ok(d.get_item(key)?.filter(|v| !v.is_none()))
}

/// The model dict of `rotor_rub.Model._core_dict()` → a [`ModelSpec`] (not yet checked).
pub fn spec_of(d: &Bound<'_, PyDict>) -> PyResult<ModelSpec> {
    let mass = dense("M", &item(d, "M")?)?;
    let n = mass.rows;
    let zeros = || Dense::zeros(n, n);
    let damping = optional(d, "C")?.map_or(Ok(zeros()), |a| dense("C", &a))?;
    let gyroscopic = optional(d, "G")?.map_or(Ok(zeros()), |a| dense("G", &a))?;
    let stiffness = dense("K", &item(d, "K")?)?;
    let dofs: Vec<String> = item(d, "dofs")?.extract()?;
    let speed = args::real("speed", &item(d, "speed")?)?;
    let phase = optional(d, "phase")?.map_or(Ok(0.0), |v| args::real("phase", &v))?;
    let unbalances: Vec<(usize, usize, f64, f64)> = item(d, "unbalance")?.extract()?;
    let force: Vec<f64> = optional(d, "force")?.map_or(Ok(Vec::new()), |v| v.extract())?;
    let rub = item(d, "rub")?;
    let rub = rub
        .cast::<PyDict>()
        .map_err(|_| input("rub must be a rotor_rub.Rub"))?;
    let k: [[f64; 2]; 2] = item(rub, "contact_stiffness")?.extract()?;
    let rub = RubSpec {
        dof_x: item(rub, "dof_x")?.extract()?,
        dof_y: item(rub, "dof_y")?.extract()?,
        stator: optional(rub, "stator")?.map(|v| v.extract()).transpose()?,
        clearance: args::real("rub.clearance", &item(rub, "clearance")?)?,
        contact_stiffness: k,
        friction_coefficient: args::real(
            "rub.friction_coefficient",
            &item(rub, "friction_coefficient")?,
        )?,
        radius: optional(rub, "radius")?
            .map(|v| args::real("rub.radius", &v))
            .transpose()?,
        offset: item(rub, "offset")?.extract()?,
    };
    let initial: Option<(Vec<f64>, Vec<f64>)> =
        optional(d, "initial")?.map(|v| v.extract()).transpose()?;
    let mut speed_dependent = Vec::new();
    if let Some(points) = optional(d, "speed_dependent")? {
        let points = points
            .cast::<PyList>()
            .map_err(|_| input("speed_dependent must be a list of (speed, C, K)"))?;
        for (i, p) in points.iter().enumerate() {
            let (s, c, k): (f64, Bound<'_, PyAny>, Bound<'_, PyAny>) = p.extract()?;
            let matrix = |name: &str, a: Bound<'_, PyAny>| -> PyResult<Option<Dense>> {
                if a.is_none() {
                    Ok(None)
                } else {
                    dense(&format!("speed_dependent[{i}].{name}"), &a).map(Some)
                }
            };
            speed_dependent.push(SpeedPoint {
                speed: s,
                damping: matrix("damping", c)?,
                stiffness: matrix("stiffness", k)?,
            });
        }
    }
    let name: String = optional(d, "name")?.map_or(Ok(String::new()), |v| v.extract())?;
    Ok(ModelSpec {
        name,
        dofs,
        mass,
        damping,
        gyroscopic,
        stiffness,
        speed,
        phase,
        unbalances: unbalances
            .into_iter()
            .map(|(dof_x, dof_y, m_e, phase)| UnbalanceSpec {
                dof_x,
                dof_y,
                m_e,
                phase,
            })
            .collect(),
        force,
        rub,
        initial,
        speed_dependent,
    })
}

/// A [`ModelSpec`] as the model dict (the inverse of [`spec_of`]; a model file read for Python).
fn dict_of<'py>(py: Python<'py>, spec: &ModelSpec) -> PyResult<Bound<'py, PyDict>> {
    let array = |a: &Dense| -> PyResult<Bound<'py, PyAny>> {
        let m = numpy::ndarray::Array2::from_shape_vec((a.rows, a.cols), a.data.clone())
            .map_err(|e| input(e.to_string()))?;
        Ok(m.into_pyarray(py).into_any())
    };
    let d = PyDict::new(py);
    d.set_item("name", &spec.name)?;
    d.set_item("dofs", &spec.dofs)?;
    d.set_item("M", array(&spec.mass)?)?;
    d.set_item("C", array(&spec.damping)?)?;
    d.set_item("G", array(&spec.gyroscopic)?)?;
    d.set_item("K", array(&spec.stiffness)?)?;
    d.set_item("speed", spec.speed)?;
    d.set_item("phase", spec.phase)?;
    let unbalance: Vec<(usize, usize, f64, f64)> = spec
        .unbalances
        .iter()
        .map(|u| (u.dof_x, u.dof_y, u.m_e, u.phase))
        .collect();
    d.set_item("unbalance", unbalance)?;
    d.set_item(
        "force",
        if spec.force.is_empty() {
            None
        } else {
            Some(spec.force.clone())
        },
    )?;
    let r = &spec.rub;
    let rub = PyDict::new(py);
    rub.set_item("dof_x", r.dof_x)?;
    rub.set_item("dof_y", r.dof_y)?;
    rub.set_item("stator", r.stator)?;
    rub.set_item("clearance", r.clearance)?;
    rub.set_item("contact_stiffness", r.contact_stiffness)?;
    rub.set_item("friction_coefficient", r.friction_coefficient)?;
    rub.set_item("radius", r.radius)?;
    rub.set_item("offset", r.offset)?;
    d.set_item("rub", rub)?;
    d.set_item("initial", spec.initial.clone())?;
    let points = PyList::empty(py);
    for p in &spec.speed_dependent {
        let c = p.damping.as_ref().map(array).transpose()?;
        let k = p.stiffness.as_ref().map(array).transpose()?;
        points.append((p.speed, c, k))?;
    }
    d.set_item("speed_dependent", points)?;
    Ok(d)
}

/// Check a model: every value, then the statement (M symmetric positive definite, …).
#[pyfunction]
pub fn matrix_check(py: Python<'_>, model: &Bound<'_, PyDict>) -> PyResult<()> {
    let spec = spec_of(model)?;
    py.detach(|| model_file::on_large_stack(|| spec.build().map(|_| ())))
        .map_err(|e| model_error(&e))
}

/// The eigenvalues of the first-order system at the running speed (1/s, complex), smallest
/// modulus first.
#[pyfunction]
pub fn matrix_modes<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let spec = spec_of(model)?;
    let modes = py
        .detach(|| spec.eigenvalues())
        .map_err(|e| model_error(&e))?;
    let out: Vec<numpy::Complex64> = modes
        .iter()
        .map(|c| numpy::Complex64::new(c.re, c.im))
        .collect();
    Ok(out.into_pyarray(py).into_any())
}

/// A model file (TOML or .npz, docs/MODEL_FILES.md) as the model dict.
#[pyfunction]
pub fn matrix_load<'py>(py: Python<'py>, path: String) -> PyResult<Bound<'py, PyDict>> {
    let spec = model_file::load(std::path::Path::new(&path)).map_err(input)?;
    dict_of(py, &spec)
}

/// What a matrix run's result carries about its problem (`rotor_rub.Problem`): the model's
/// running values in SI (`speed` rad/s, `clearance` m, `friction_coefficient`, `dofs` n), the
/// method and its settings, the version.
fn problem_dict<'py>(
    py: Python<'py>,
    spec: &ModelSpec,
    options: &Options,
) -> PyResult<Bound<'py, PyDict>> {
    let params = PyDict::new(py);
    params.set_item("speed", spec.speed)?;
    params.set_item("clearance", spec.rub.clearance)?;
    params.set_item("friction_coefficient", spec.rub.friction_coefficient)?;
    params.set_item("dofs", spec.dofs() as f64)?;
    let out = PyDict::new(py);
    out.set_item("params", params)?;
    out.set_item("method", options.method.name())?;
    out.set_item("tol", options.tolerance())?;
    let scheme = options.method.info().contact_scheme;
    out.set_item(
        "contact_scheme",
        scheme.then(|| options.contact_scheme.name()),
    )?;
    out.set_item("step", options.step)?;
    out.set_item("method_text", describe(options))?;
    out.set_item("version", env!("CARGO_PKG_VERSION"))?;
    Ok(out)
}

/// The run of a matrix model as the result dict (`rotor_rub.Run`'s fields, SI units).
fn run_dict<'py>(
    py: Python<'py>,
    spec: &ModelSpec,
    options: &Options,
    run: MatrixRun,
) -> PyResult<Bound<'py, PyDict>> {
    let period = std::f64::consts::TAU / spec.speed;
    let width = run.columns.len();
    let table = |rows: usize, data: Vec<f64>| -> PyResult<Bound<'py, PyAny>> {
        let a = numpy::ndarray::Array2::from_shape_vec((rows, width), data)
            .map_err(|e| input(e.to_string()))?;
        Ok(a.into_pyarray(py).into_any())
    };
    let out = PyDict::new(py);
    let (events, samples) = (run.events, run.samples);
    out.set_item("columns", run.columns)?;
    out.set_item("event_state", table(events.time.len(), events.state)?)?;
    out.set_item("event_time", events.time.into_pyarray(py))?;
    out.set_item("event_kind", events.code.into_pyarray(py))?;
    out.set_item("sample_state", table(samples.time.len(), samples.state)?)?;
    out.set_item("sample_time", samples.time.into_pyarray(py))?;
    out.set_item("sample_regime", samples.code.into_pyarray(py))?;
    out.set_item("start_time", 0.0)?;
    out.set_item("end_time", run.end_time)?;
    out.set_item("end_state", run.end_state.into_pyarray(py))?;
    out.set_item("time_in", run.time_in)?;
    let total: f64 = run.time_in.iter().sum();
    let fraction = if total > 0.0 {
        (run.time_in[1] + run.time_in[2]) / total
    } else {
        0.0
    };
    out.set_item("contact_fraction", fraction)?;
    out.set_item("forcing_period", period)?;
    out.set_item("elapsed", run.elapsed.as_secs_f64())?;
    out.set_item("problem", problem_dict(py, spec, options)?)?;
    Ok(out)
}

/// THE Python entry point of a matrix run (`rr.simulate(model=…)`): the model and its start
/// checked, the run length and samples, then the CLI library's `simulate_matrix` (the matrix
/// propagator, every method) with the GIL released, and the result dict.
#[pyfunction]
#[pyo3(signature = (model, *, t_end=None, periods=None, method=None, tol=None,
    contact_scheme=None, step=None, samples=None, initial=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate_matrix<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyDict>,
    t_end: Any<'_, 'py>,
    periods: Any<'_, 'py>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    samples: Any<'_, 'py>,
    initial: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let spec = spec_of(model)?;
    let options = inputs::options(
        &MethodKeywords {
            method,
            tol,
            contact_scheme,
            step,
        },
        Method::Hybrid,
    )?;
    let end = model_file::end_time(
        &spec,
        args::real_opt("t_end", t_end)?,
        args::real_opt("periods", periods)?,
    )
    .map_err(input)?;
    let count = match samples {
        None => 1001,
        Some(s) => args::count("samples", s, 0)? as usize,
    };
    let times: Vec<f64> = uniform_times(0.0, end, count).collect();
    let result = py.detach(|| {
        model_file::on_large_stack(|| {
            model_file::simulate_matrix(&spec, &options, end, &times, initial.as_deref())
        })
    });
    match result {
        Ok(run) => run_dict(py, &spec, &options, run),
        Err(MatrixRunError::Model(e)) => Err(model_error(&e)),
        Err(MatrixRunError::Input(m)) => Err(input(m)),
        Err(MatrixRunError::Propagation(e)) => Err(cli(rotor_rub_cli::error::CliError::from(e))),
    }
}

/// The result assembly of a matrix run from synthetic events and samples (tests of the Python
/// layer's arrays and plots; the same [`run_dict`] the real run uses): `events` and
/// `samples` as (time, code, SI state row) triples.
#[pyfunction]
pub fn matrix_result_of<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyDict>,
    events: Vec<(f64, u8, Vec<f64>)>,
    samples: Vec<(f64, u8, Vec<f64>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let spec = spec_of(model)?;
    let columns = model_file::state_columns(&spec);
    let width = columns.len();
    let rows = |list: Vec<(f64, u8, Vec<f64>)>| -> PyResult<model_file::Rows> {
        let mut r = model_file::Rows::default();
        for (t, code, state) in list {
            if state.len() != width {
                return Err(input(format!(
                    "a state row has {} entries; the model's rows have {width} ({})",
                    state.len(),
                    columns.join(", ")
                )));
            }
            r.time.push(t);
            r.code.push(code);
            r.state.extend(state);
        }
        Ok(r)
    };
    let events = rows(events)?;
    let samples = rows(samples)?;
    let mut time_in = [0.0; 3];
    for (w, &c) in samples.time.windows(2).zip(&samples.code) {
        if let (Some(slot), [a, b]) = (time_in.get_mut(c as usize), w) {
            *slot += b - a;
        }
    }
    let end_time = samples.time.last().copied().unwrap_or(0.0);
    let end_state = samples
        .state
        .get(samples.state.len().saturating_sub(width)..)
        .unwrap_or(&[])
        .to_vec();
    let run = MatrixRun {
        columns,
        events,
        samples,
        end_time,
        end_state,
        time_in,
        elapsed: std::time::Duration::ZERO,
    };
    run_dict(py, &spec, &Options::with_method(Method::Hybrid), run)
}

/// `rr.simulate` of the paper's rotor with a ring of mass (`stator_mass_ratio` > 0): the n = 4
/// matrix model run by the matrix propagator (GIL released; no progress callback), as the
/// planar result dict with 8 state columns (x, y, vx, vy, xs, ys, vxs, vys).
pub fn simulate_ring<'py>(
    py: Python<'py>,
    problem: &rotor_rub::Problem,
    options: &Options,
    end: f64,
    count: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let start = problem.start_time;
    let times: Vec<f64> = uniform_times(start, end, count).collect();
    let result = py.detach(|| {
        model_file::on_large_stack(|| model_file::simulate_ring(problem, options, end, &times))
    });
    let run = match result {
        Ok(run) => run,
        Err(MatrixRunError::Model(e)) => return Err(model_error(&e)),
        Err(MatrixRunError::Input(m)) => return Err(input(m)),
        Err(MatrixRunError::Propagation(e)) => {
            return Err(cli(rotor_rub_cli::error::CliError::from(e)));
        }
    };
    let width = run.columns.len();
    let table = |rows: usize, data: Vec<f64>| -> PyResult<Bound<'py, PyAny>> {
        let a = numpy::ndarray::Array2::from_shape_vec((rows, width), data)
            .map_err(|e| input(e.to_string()))?;
        Ok(a.into_pyarray(py).into_any())
    };
    let fraction = run.contact_fraction();
    let out = PyDict::new(py);
    let (events, samples) = (run.events, run.samples);
    out.set_item("event_state", table(events.time.len(), events.state)?)?;
    out.set_item("event_time", events.time.into_pyarray(py))?;
    out.set_item("event_kind", events.code.into_pyarray(py))?;
    out.set_item("sample_state", table(samples.time.len(), samples.state)?)?;
    out.set_item("sample_time", samples.time.into_pyarray(py))?;
    out.set_item("sample_regime", samples.code.into_pyarray(py))?;
    out.set_item("start_time", start)?;
    out.set_item("end_time", run.end_time)?;
    out.set_item("end_state", run.end_state.into_pyarray(py))?;
    out.set_item("time_in", run.time_in)?;
    out.set_item("contact_fraction", fraction)?;
    out.set_item("elapsed", run.elapsed.as_secs_f64())?;
    out.set_item("forcing_period", problem.params.forcing_period())?;
    out.set_item("samples", count)?;
    out.set_item("problem", crate::meta::problem(py, problem, options)?)?;
    Ok(out)
}

/// Add the matrix functions to the module (`_core.matrix_*`, `_core.simulate_matrix`).
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(matrix_check, m)?)?;
    m.add_function(wrap_pyfunction!(matrix_modes, m)?)?;
    m.add_function(wrap_pyfunction!(matrix_load, m)?)?;
    m.add_function(wrap_pyfunction!(matrix_result_of, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_matrix, m)?)?;
    Ok(())
}
