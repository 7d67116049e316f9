//! One-problem runs for Python: `simulate`, `poincare`, `spectrum`. Each builds its inputs as the
//! CLI does, propagates with the GIL released under a watch (Ctrl-C, progress), and returns a
//! dict of numpy arrays that the Python layer (`rotor_rub/__init__.py`) wraps in typed results.

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::{EventKind, Regime, State};
use rotor_rub_cli::analysis::classify::distinct_points;
use rotor_rub_cli::analysis::lyapunov::SKIPPED_INTERVALS;
use rotor_rub_cli::analysis::spectrum::{real_amplitudes, whirl_amplitudes};
use rotor_rub_cli::limits::{add_counts, fits_memory};
use rotor_rub_cli::options::{DefaultMethod, SingleRun, Survey, positive};
use rotor_rub_cli::trajectory::{self, uniform_times};
use rotor_rub_cli::{poincare as section, spectrum as fft};

use crate::args::{self, flag};
use crate::errors::{cli, input};
use crate::inputs::{self, MethodKeywords};
use crate::meta;
use crate::watch::{self, Progress, periods_from};

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// `(n, 4)` array of states.
pub fn states<'py>(py: Python<'py>, states: &[State]) -> PyResult<Bound<'py, PyAny>> {
    rows(py, states.iter().map(|s| s.to_array()), states.len())
}

/// `(n, 4)` array from `n` rows (one allocation, handed to numpy without a copy).
pub fn rows<'py>(
    py: Python<'py>,
    rows: impl Iterator<Item = [f64; 4]>,
    n: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let mut flat = Vec::with_capacity(4 * n);
    for row in rows {
        flat.extend_from_slice(&row);
    }
    let array = numpy::ndarray::Array2::from_shape_vec((flat.len() / 4, 4), flat)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py).into_any())
}

/// The index of `kind` in [`EventKind::ALL`] (`rotor_rub.EVENT_KINDS`).
pub fn kind_code(kind: EventKind) -> u8 {
    EventKind::ALL
        .iter()
        .position(|k| *k == kind)
        .map_or(u8::MAX, |i| i as u8)
}

/// The index of `regime` in `rotor_rub.REGIMES` (free, contact, rolling).
pub fn regime_code(regime: Regime) -> u8 {
    trajectory::regime_index(regime) as u8
}

/// Samples in numpy's layout: times, states row-major (n × 4), regime codes. (Codes, not
/// names: a numpy string array costs about 10 µs per thousand samples to hand over.)
struct Columns {
    time: Vec<f64>,
    state: Vec<f64>,
    regime: Vec<u8>,
}

impl Columns {
    fn with_capacity(n: usize) -> Self {
        Columns {
            time: Vec::with_capacity(n),
            state: Vec::with_capacity(4 * n),
            regime: Vec::with_capacity(n),
        }
    }

    fn push(&mut self, s: &rotor_rub::Sample) {
        self.time.push(s.time);
        self.state.extend_from_slice(&s.state.to_array());
        self.regime.push(regime_code(s.regime));
    }
}

/// The end time from `t_end` or `periods` (default 20 forcing periods), as `--t-end`/`--periods`.
fn end_time(t_end: Any<'_, '_>, periods: Any<'_, '_>, period: f64) -> PyResult<f64> {
    let positive = |name: &str, x: f64| positive(x).map_err(|e| input(format!("{name}: {e}")));
    let t_end = args::real_opt("t_end", t_end)?;
    let periods = args::real_opt("periods", periods)?;
    match (t_end, periods) {
        (Some(_), Some(_)) => Err(input(
            "give t_end or periods, not both (they both set the run length)",
        )),
        (Some(t), None) => positive("t_end", t),
        (None, p) => Ok(positive("periods", p.unwrap_or(20.0))? * period),
    }
}

/// One run: every switch and `samples` uniform samples from the start to the end time.
#[pyfunction]
#[pyo3(signature = (*, preset=None, config=None, t_end=None, periods=None, method=None, tol=None,
    contact_scheme=None, step=None, samples=None, max_work=None, progress=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    preset: Option<&str>,
    config: Option<String>,
    t_end: Any<'_, 'py>,
    periods: Any<'_, 'py>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    samples: Any<'_, 'py>,
    max_work: Any<'_, 'py>,
    progress: Any<'_, 'py>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let problem = inputs::problem(preset, inputs::path(config), params)?;
    let keywords = MethodKeywords {
        method,
        tol,
        contact_scheme,
        step,
    };
    let options = inputs::options(&keywords, SingleRun::METHOD)?;
    let end = end_time(t_end, periods, problem.params.forcing_period())?;
    let count = match samples {
        None => 1001,
        Some(s) => args::count("samples", s, 0)?,
    };
    if count == 1 {
        return Err(input(
            "samples: 1 is out of range: it must be 0 (none) or an integer >= 2",
        ));
    }
    let count =
        fits_memory("samples", count, std::mem::size_of::<rotor_rub::Sample>()).map_err(cli)?;
    let budget = inputs::budget(max_work)?;
    budget.plan("samples", count as u64).map_err(cli)?;
    if problem.params.stator_mass_ratio > 0.0 {
        // A stator ring with mass: the n = 4 matrix model (issue 28).
        return crate::matrix::simulate_ring(py, &problem, &options, end, count);
    }
    let propagator = trajectory::start(&problem, &options).map_err(cli)?;
    let start = problem.start_time;
    let period = problem.params.forcing_period();
    let progress = Progress::new(progress, (end - start) / period);
    // Samples go straight into numpy's column layout as they come (no list of samples).
    let mut columns = Columns::with_capacity(count);
    let pass = watch::on_this_thread(py, progress, periods_from(start, period), |watch| {
        let budget = budget.watched(watch);
        let mut tracker = budget.run(start, end);
        trajectory::run(
            propagator,
            end,
            uniform_times(start, end, count),
            &mut tracker,
            true,
            |_| Ok(()),
            |s| {
                columns.push(s);
                Ok(())
            },
        )
    })?;
    let out = PyDict::new(py);
    let event_states: Vec<State> = pass.events.iter().map(|e| e.state).collect();
    let times: Vec<f64> = pass.events.iter().map(|e| e.time).collect();
    let kinds: Vec<u8> = pass.events.iter().map(|e| kind_code(e.kind)).collect();
    out.set_item("event_time", times.into_pyarray(py))?;
    out.set_item("event_kind", kinds.into_pyarray(py))?;
    out.set_item("event_state", states(py, &event_states)?)?;
    let n = columns.time.len();
    let state = numpy::ndarray::Array2::from_shape_vec((n, 4), columns.state)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    out.set_item("sample_time", columns.time.into_pyarray(py))?;
    out.set_item("sample_state", state.into_pyarray(py))?;
    out.set_item("sample_regime", columns.regime.into_pyarray(py))?;
    out.set_item("start_time", start)?;
    out.set_item("end_time", end)?;
    out.set_item(
        "end_state",
        pass.last.state.to_array().to_vec().into_pyarray(py),
    )?;
    out.set_item("time_in", pass.time_in)?;
    out.set_item("contact_fraction", pass.contact_fraction)?;
    out.set_item("elapsed", pass.elapsed.as_secs_f64())?;
    out.set_item("forcing_period", period)?;
    out.set_item("samples", count)?;
    out.set_item("problem", meta::problem(py, &problem, &options)?)?;
    Ok(out)
}

/// The Poincaré section over `keep` forcing periods after `transient`, with its response class
/// and, when asked, the largest Lyapunov exponent.
#[pyfunction]
#[pyo3(signature = (*, preset=None, config=None, transient=None, keep=None, lyapunov=None,
    method=None, tol=None, contact_scheme=None, step=None, max_work=None, progress=None,
    params=None))]
#[allow(clippy::too_many_arguments)]
pub fn poincare<'py>(
    py: Python<'py>,
    preset: Option<&str>,
    config: Option<String>,
    transient: Any<'_, 'py>,
    keep: Any<'_, 'py>,
    lyapunov: Any<'_, 'py>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    max_work: Any<'_, 'py>,
    progress: Any<'_, 'py>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let problem = inputs::problem(preset, inputs::path(config), params)?;
    let keywords = MethodKeywords {
        method,
        tol,
        contact_scheme,
        step,
    };
    let options = inputs::options(&keywords, Survey::METHOD)?;
    let transient = transient.map_or(Ok(200), |t| args::count("transient", t, 0))?;
    let keep = keep.map_or(Ok(100), |k| args::count("keep", k, 1))?;
    let lyapunov = lyapunov.map_or(Ok(false), |l| flag("lyapunov", l))?;
    add_counts(("transient", transient), ("keep", keep)).map_err(cli)?;
    let kept = fits_memory("keep", keep, std::mem::size_of::<State>() * 2).map_err(cli)?;
    let budget = inputs::budget(max_work)?;
    let lyapunov_work = if lyapunov { keep } else { 0 };
    budget
        .plan("keep", keep.saturating_add(lyapunov_work))
        .map_err(cli)?;
    let period = problem.params.forcing_period();
    let lyapunov_periods = if lyapunov {
        keep as f64 + SKIPPED_INTERVALS as f64
    } else {
        0.0
    };
    let total = transient as f64 + keep as f64 + lyapunov_periods;
    let progress = Progress::new(progress, total);
    let done = periods_from(problem.start_time, period);
    let result = watch::on_this_thread(py, progress, done, |watch| {
        let budget = budget.watched(watch);
        section::section(&problem, &options, transient, kept, lyapunov, &budget)
    })?;
    let out = PyDict::new(py);
    let periods: Vec<u64> = (transient..transient + keep).collect();
    out.set_item("period", periods.into_pyarray(py))?;
    out.set_item("state", states(py, &result.points)?)?;
    out.set_item("response", result.response.to_string())?;
    out.set_item("lyapunov", result.lyapunov)?;
    out.set_item("distinct", distinct_points(&result.points))?;
    out.set_item("problem", meta::problem(py, &problem, &options)?)?;
    Ok(out)
}

/// Amplitude spectrum over `periods` forcing periods after `transient`, in orders of the running
/// speed: of x and y, or of the whirl x + i y (negative orders: backward whirl).
#[pyfunction]
#[pyo3(signature = (*, preset=None, config=None, transient=None, periods=None,
    samples_per_period=None, whirl=None, method=None, tol=None, contact_scheme=None, step=None,
    max_work=None, progress=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn spectrum<'py>(
    py: Python<'py>,
    preset: Option<&str>,
    config: Option<String>,
    transient: Any<'_, 'py>,
    periods: Any<'_, 'py>,
    samples_per_period: Any<'_, 'py>,
    whirl: Any<'_, 'py>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    max_work: Any<'_, 'py>,
    progress: Any<'_, 'py>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let problem = inputs::problem(preset, inputs::path(config), params)?;
    let keywords = MethodKeywords {
        method,
        tol,
        contact_scheme,
        step,
    };
    let options = inputs::options(&keywords, Survey::METHOD)?;
    let transient = transient.map_or(Ok(100), |t| args::count("transient", t, 0))?;
    let periods = periods.map_or(Ok(60), |p| args::count("periods", p, 1))?;
    let per_period =
        samples_per_period.map_or(Ok(64), |s| args::count("samples_per_period", s, 2))?;
    let whirl = whirl.map_or(Ok(false), |w| flag("whirl", w))?;
    add_counts(("transient", transient), ("periods", periods)).map_err(cli)?;
    let n = fft::sample_count(periods, per_period).map_err(cli)?;
    let budget = inputs::budget(max_work)?;
    budget
        .plan("periods × samples_per_period", n as u64)
        .map_err(cli)?;
    let period = problem.params.forcing_period();
    let progress = Progress::new(progress, transient as f64 + periods as f64);
    let done = periods_from(problem.start_time, period);
    let (x, y) = watch::on_this_thread(py, progress, done, |watch| {
        let budget = budget.watched(watch);
        fft::signal(&problem, &options, transient, periods, per_period, &budget)
    })?;
    let order = |bin: f64| bin / periods as f64;
    let out = PyDict::new(py);
    if whirl {
        let (orders, amps): (Vec<f64>, Vec<f64>) = py
            .detach(|| whirl_amplitudes(&x, &y))
            .into_iter()
            .map(|(k, a)| (order(k as f64), a))
            .unzip();
        out.set_item("order", orders.into_pyarray(py))?;
        out.set_item("whirl", amps.into_pyarray(py))?;
    } else {
        let (ax, ay) = py.detach(|| (real_amplitudes(&x), real_amplitudes(&y)));
        let orders: Vec<f64> = (0..ax.len()).map(|k| order(k as f64)).collect();
        out.set_item("order", orders.into_pyarray(py))?;
        out.set_item("x", ax.into_pyarray(py))?;
        out.set_item("y", ay.into_pyarray(py))?;
    }
    out.set_item("problem", meta::problem(py, &problem, &options)?)?;
    Ok(out)
}
