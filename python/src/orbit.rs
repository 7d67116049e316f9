//! Periodic orbits for Python (`rotor_rub.orbit`, `rotor_rub.continuation`): the CLI library's
//! shooting and continuation (`rotor_rub_cli::orbit`), the same numbers and messages as
//! `rotor-rub orbit` and `rotor-rub continue`, with the GIL released under a watch (Ctrl-C,
//! progress).

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use rotor_rub::linalg::Complex;
use rotor_rub::{EventKind, State};
use rotor_rub_cli::error::CliError;
use rotor_rub_cli::options::DefaultMethod;
use rotor_rub_cli::orbit::command::find;
use rotor_rub_cli::orbit::continuation::{Start, continuation as continue_branches};
use rotor_rub_cli::orbit::start::{Guess, Orbits, map_settings, parse_start, start_state};
use rotor_rub_cli::orbit::{ContinuationSettings, Evaluator};
use rotor_rub_cli::problem::parse_parameter;

use crate::args::{self, shown};
use crate::errors::{cli, input};
use crate::inputs::{self, MethodKeywords};
use crate::meta;
use crate::runs::states;
use crate::watch::{self, Progress, periods_from};

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// `guess`: None or `"simulate"`, `"free"`, or four real numbers (x, y, x', y').
fn guess(value: Any<'_, '_>) -> PyResult<Guess> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(Guess::Simulate);
    };
    if value.is_instance_of::<PyString>() {
        let text: String = value.extract()?;
        let spec = parse_start(&text).map_err(|e| input(format!("guess: {e}")))?;
        if spec.value.is_some() || matches!(spec.guess, Guess::Given(_)) {
            return Err(input(format!(
                "guess: '{text}' is not \"simulate\" or \"free\" (a state is given as four numbers)"
            )));
        }
        return Ok(spec.guess);
    }
    let items: Vec<Bound<'_, PyAny>> = value
        .try_iter()
        .map_err(|_| {
            input(format!(
                "guess: {} is not \"simulate\", \"free\" or four numbers x, y, x', y'",
                shown(value)
            ))
        })?
        .collect::<PyResult<_>>()?;
    let numbers: Vec<f64> = items
        .iter()
        .map(|v| args::real("guess", v))
        .collect::<PyResult<_>>()?;
    match numbers[..] {
        [x, y, vx, vy] if numbers.iter().all(|v| v.is_finite()) => {
            Ok(Guess::Given(State::new(x, y, vx, vy)))
        }
        _ => Err(input(format!(
            "guess: {} has {} entries: a state is four finite numbers x, y, x', y'",
            shown(value),
            numbers.len()
        ))),
    }
}

/// The orbit's period k (1 to 32).
fn period(value: Any<'_, '_>) -> PyResult<u32> {
    let max = rotor_rub::orbit::MAX_PERIOD as u64;
    let k = value.map_or(Ok(1), |v| args::count("period", v, 1))?;
    if k > max {
        return Err(input(format!(
            "period: {k} is out of range: it must be an integer in [1, {max}]"
        )));
    }
    Ok(k as u32)
}

/// Newton's residual tolerance, in [1e-14, 1e-3].
fn newton_tol(value: Any<'_, '_>) -> PyResult<f64> {
    let tol = args::real_opt("newton_tol", value)?.unwrap_or(rotor_rub::orbit::DEFAULT_TOLERANCE);
    let range = rotor_rub::orbit::TOLERANCE_RANGE;
    if !range.contains(tol) {
        return Err(input(format!(
            "newton_tol: {} is out of range: it must be in {range}",
            rotor_rub_cli::error::num(tol)
        )));
    }
    Ok(tol)
}

/// (re, im) arrays of complex numbers.
fn parts(values: impl Iterator<Item = Complex>) -> (Vec<f64>, Vec<f64>) {
    values.map(|z| (z.re, z.im)).unzip()
}

/// One periodic orbit by shooting.
#[pyfunction]
#[pyo3(signature = (*, preset=None, config=None, period=None, guess=None, transient=None,
    newton_tol=None, method=None, tol=None, contact_scheme=None, step=None, max_work=None,
    progress=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn orbit<'py>(
    py: Python<'py>,
    preset: Option<&str>,
    config: Option<String>,
    period: Any<'_, 'py>,
    guess: Any<'_, 'py>,
    transient: Any<'_, 'py>,
    newton_tol: Any<'_, 'py>,
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
    let options = inputs::options(&keywords, Orbits::METHOD)?;
    let periods = self::period(period)?;
    let start = self::guess(guess)?;
    let transient = transient.map_or(Ok(200), |t| args::count("transient", t, 0))?;
    let tolerance = self::newton_tol(newton_tol)?;
    let budget = inputs::budget(max_work)?;
    budget.plan("transient", transient).map_err(cli)?;
    let forcing = problem.params.forcing_period();
    let progress = Progress::new(progress, transient as f64);
    let done = periods_from(problem.start_time, forcing);
    let found = watch::on_this_thread(py, progress, done, |watch| {
        let budget = budget.watched(watch);
        find(
            &problem, &options, start, transient, periods, tolerance, &budget,
        )
    })?;
    let orbit = found.orbit();
    let s = &orbit.summary;
    let out = PyDict::new(py);
    out.set_item("state", orbit.state.to_array().to_vec().into_pyarray(py))?;
    out.set_item("period", orbit.periods)?;
    out.set_item("minimal_period", found.minimal_period)?;
    let (re, im) = parts(orbit.multipliers.iter().copied());
    out.set_item("multipliers_re", re.into_pyarray(py))?;
    out.set_item("multipliers_im", im.into_pyarray(py))?;
    out.set_item("stable", orbit.stable())?;
    out.set_item(
        "residuals",
        found.shot.residuals().to_vec().into_pyarray(py),
    )?;
    let flat: Vec<f64> = orbit.monodromy.iter().flatten().copied().collect();
    out.set_item("monodromy", flat.into_pyarray(py))?;
    out.set_item("sections", states(py, orbit.sections())?)?;
    out.set_item("start", found.start.to_array().to_vec().into_pyarray(py))?;
    out.set_item("max_radius", s.max_radius)?;
    out.set_item("min_radius", s.min_radius)?;
    out.set_item("contact_fraction", s.contact_fraction())?;
    out.set_item("contacts", s.count(EventKind::Enter))?;
    let settings = map_settings(&options);
    out.set_item("problem", meta::problem(py, &problem, &settings.options)?)?;
    Ok(out)
}

/// Branches of periodic orbits over `start`..`stop` of `param`, with their bifurcations.
#[pyfunction]
#[pyo3(signature = (param, start, stop, *, preset=None, config=None, period=None, guess=None,
    transient=None, max_period=None, max_points=None, newton_tol=None, method=None, tol=None,
    contact_scheme=None, step=None, max_work=None, progress=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn continuation<'py>(
    py: Python<'py>,
    param: &Bound<'py, PyAny>,
    start: &Bound<'py, PyAny>,
    stop: &Bound<'py, PyAny>,
    preset: Option<&str>,
    config: Option<String>,
    period: Any<'_, 'py>,
    guess: Any<'_, 'py>,
    transient: Any<'_, 'py>,
    max_period: Any<'_, 'py>,
    max_points: Any<'_, 'py>,
    newton_tol: Any<'_, 'py>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    max_work: Any<'_, 'py>,
    progress: Any<'_, 'py>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let name = args::text("param", Some(param))?.unwrap_or_default();
    let parameter = parse_parameter(&name).map_err(|e| input(format!("param: {e}")))?;
    let (from, to) = (args::real("start", start)?, args::real("stop", stop)?);
    let base = inputs::problem(preset, inputs::path(config), params)?;
    let keywords = MethodKeywords {
        method,
        tol,
        contact_scheme,
        step,
    };
    let options = inputs::options(&keywords, Orbits::METHOD)?;
    let periods = self::period(period)?;
    let start_guess = self::guess(guess)?;
    let transient = transient.map_or(Ok(200), |t| args::count("transient", t, 0))?;
    let mut settings = ContinuationSettings::new(parameter, from, to, periods);
    settings.validate().map_err(|e| {
        cli(CliError {
            message: e
                .message
                .replace("--from", "start")
                .replace("--to", "stop")
                .replace("--param", "param")
                .replace("--period", "period"),
            ..e
        })
    })?;
    settings.max_period = match max_period {
        Some(v) => self::period(Some(v)).map_err(|_| {
            input(format!(
                "max_period: {} is out of range: it must be an integer in [1, {}]",
                shown(v),
                rotor_rub::orbit::MAX_PERIOD
            ))
        })?,
        None => 2 * periods,
    };
    if let Some(n) = max_points {
        settings.max_points =
            usize::try_from(args::count("max_points", n, 2)?).unwrap_or(usize::MAX);
    }
    settings.tolerance = self::newton_tol(newton_tol)?;
    settings.map = map_settings(&options);
    let budget = inputs::budget(max_work)?;
    let mut at = base;
    parameter.set(&mut at, from);
    at.validate()
        .map_err(|e| input(format!("{name} = {from}: {e}")))?;
    let span = (to - from).abs();
    let progress = Progress::new(progress, 100.0);
    let done: watch::Done = Box::new(|w| w.reached());
    let started = std::time::Instant::now();
    let result = watch::on_this_thread(py, progress, done, |watch| {
        // The start's transient is short and reports times, not the range's percent: it runs
        // unwatched.
        let guess = start_state(&at, &options, start_guess, transient, &budget)?;
        let mut poll = |p: f64| watch.poll(100.0 * ((p - from).abs() / span).min(1.0));
        let mut ev = Evaluator {
            base: base.params,
            parameter,
            periods,
            map: settings.map,
            poll: &mut poll,
            evaluations: 0,
        };
        continue_branches(&mut ev, &[Start { guess, value: from }], &settings)
    })?;
    let elapsed = started.elapsed().as_secs_f64();
    let points = &result.points;
    let out = PyDict::new(py);
    let value: Vec<f64> = points.iter().map(|p| p.value()).collect();
    let state: Vec<State> = points.iter().map(|p| p.state()).collect();
    let period_k: Vec<i64> = points.iter().map(|p| i64::from(p.periods())).collect();
    let stable: Vec<bool> = points.iter().map(|p| p.stable()).collect();
    let branch: Vec<i64> = points.iter().map(|p| p.branch as i64).collect();
    let (re, im) = parts(points.iter().flat_map(|p| p.solution.multipliers));
    let kind: Vec<&str> = points
        .iter()
        .map(|p| p.kind.map_or("", |k| k.name()))
        .collect();
    out.set_item("value", value.into_pyarray(py))?;
    out.set_item("state", states(py, &state)?)?;
    out.set_item("period", period_k.into_pyarray(py))?;
    out.set_item("stable", stable)?;
    out.set_item("branch", branch.into_pyarray(py))?;
    out.set_item("multipliers_re", re.into_pyarray(py))?;
    out.set_item("multipliers_im", im.into_pyarray(py))?;
    out.set_item("kind", kind)?;
    let summary = |f: fn(&rotor_rub::orbit::Summary) -> f64| -> Vec<f64> {
        points.iter().map(|p| f(p.summary())).collect()
    };
    out.set_item("max_radius", summary(|s| s.max_radius).into_pyarray(py))?;
    out.set_item("min_radius", summary(|s| s.min_radius).into_pyarray(py))?;
    out.set_item(
        "contact_fraction",
        summary(|s| s.contact_fraction()).into_pyarray(py),
    )?;
    out.set_item(
        "contacts",
        summary(|s| f64::from(s.count(EventKind::Enter))).into_pyarray(py),
    )?;
    out.set_item(
        "bifurcations",
        result
            .bifurcations
            .iter()
            .map(|&i| i as i64)
            .collect::<Vec<_>>(),
    )?;
    let branches = PyList::empty(py);
    for b in &result.branches {
        let d = PyDict::new(py);
        d.set_item("id", b.id)?;
        d.set_item("period", b.periods)?;
        d.set_item("parent", b.parent.map(|i| i as i64))?;
        d.set_item("end", &b.end)?;
        branches.append(d)?;
    }
    out.set_item("branches", branches)?;
    out.set_item("evaluations", result.evaluations)?;
    out.set_item("elapsed", elapsed)?;
    out.set_item("param", parameter.info().name)?;
    out.set_item("problem", meta::problem(py, &at, &settings.map.options)?)?;
    Ok(out)
}
