//! The fixed-step stepper for Python loops (`rotor_rub.Stepper`): one step at a time, or many in
//! one call with the GIL released.

use std::path::PathBuf;

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::{ContactScheme, Event, Problem, State, Stepper, StepperConfig};
use rotor_rub_cli::options::parse_scheme;

use crate::errors::{input, stepper};
use crate::inputs;
use crate::runs::{kind_code, regime_code, states};

/// A switch as (time, kind, (x, y, vx, vy)).
type PyEvent = (f64, &'static str, [f64; 4]);

fn event(e: &Event) -> PyEvent {
    (e.time, e.kind.name(), e.state.to_array())
}

/// Fixed-step propagation (the C ABI's stepper): exact free flight, contact sub-steps, switches
/// located inside each step.
#[pyclass(name = "Stepper", module = "rotor_rub._core", subclass)]
pub struct PyStepper {
    inner: Stepper,
}

#[pymethods]
impl PyStepper {
    #[new]
    #[pyo3(signature = (*, preset=None, config=None, dt=1e-3, contact_scheme=None,
        contact_substeps=1, max_substeps=8, **params))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        preset: Option<&str>,
        config: Option<PathBuf>,
        dt: f64,
        contact_scheme: Option<&str>,
        contact_substeps: u32,
        max_substeps: u32,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let problem = inputs::problem(preset, config, params)?;
        let scheme = contact_scheme
            .map(parse_scheme)
            .transpose()
            .map_err(input)?
            .unwrap_or(ContactScheme::Exprb43);
        let config = StepperConfig {
            dt,
            scheme,
            contact_substeps,
            max_substeps,
            ..StepperConfig::default()
        };
        let inner = Stepper::new(&problem, config).map_err(stepper)?;
        Ok(PyStepper { inner })
    }

    /// Advance one step of `dt` (default: the configured one). Returns (time, state, regime,
    /// events), events as (time, kind, state) tuples.
    #[pyo3(signature = (dt=None))]
    fn step(&mut self, dt: Option<f64>) -> PyResult<(f64, [f64; 4], &'static str, Vec<PyEvent>)> {
        let dt = dt.unwrap_or(self.inner.config().dt);
        let report = self.inner.step(dt).map_err(stepper)?;
        let events = report.events.iter().map(event).collect();
        Ok((
            report.time,
            report.state.to_array(),
            report.regime.name(),
            events,
        ))
    }

    /// Take `steps` steps of `dt` with the GIL released; returns a dict of arrays: the time,
    /// state and regime code (index into `REGIMES`) after each step, and every switch (kind
    /// codes index `EVENT_KINDS`). The Python layer turns codes into names. Stops at the first error (the
    /// stepper then stands after the last good step).
    #[pyo3(signature = (steps, dt=None))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        steps: usize,
        dt: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let dt = dt.unwrap_or(self.inner.config().dt);
        let inner = &mut self.inner;
        let (times, kept, regimes, events, error) = py.detach(|| {
            let (mut times, mut kept, mut regimes, mut events) = (
                Vec::with_capacity(steps),
                Vec::with_capacity(steps),
                Vec::with_capacity(steps),
                Vec::new(),
            );
            let mut error = None;
            for _ in 0..steps {
                match inner.step(dt) {
                    Ok(report) => {
                        times.push(report.time);
                        kept.push(report.state);
                        regimes.push(regime_code(report.regime));
                        events.extend(report.events.iter().copied());
                    }
                    Err(e) => {
                        error = Some(e);
                        break;
                    }
                }
            }
            (times, kept, regimes, events, error)
        });
        if let Some(e) = error {
            return Err(stepper(e));
        }
        let out = PyDict::new(py);
        out.set_item("time", times.into_pyarray(py))?;
        out.set_item("state", states(py, &kept)?)?;
        out.set_item("regime", regimes.into_pyarray(py))?;
        let event_states: Vec<State> = events.iter().map(|e| e.state).collect();
        let event_times: Vec<f64> = events.iter().map(|e| e.time).collect();
        let kinds: Vec<u8> = events.iter().map(|e| kind_code(e.kind)).collect();
        out.set_item("event_time", event_times.into_pyarray(py))?;
        out.set_item("event_kind", kinds.into_pyarray(py))?;
        out.set_item("event_state", states(py, &event_states)?)?;
        Ok(out)
    }

    /// Change parameters between steps (e.g. `speed_ratio=2.0`); state and time are kept.
    #[pyo3(signature = (**params))]
    fn set_params(&mut self, params: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let mut problem = Problem {
            params: *self.inner.params(),
            ..Problem::DEFAULT
        };
        for (p, v) in inputs::overrides(params)? {
            p.set(&mut problem, v);
        }
        problem.validate().map_err(|e| input(e.to_string()))?;
        self.inner.set_params(&problem.params).map_err(stepper)
    }

    /// Apply the external input force (fx, fy) from now on, held until the next call (a
    /// controller's output; `docs/MODEL.md` §15). Cheap: the precomputed free map is kept.
    fn set_input_force(&mut self, fx: f64, fy: f64) -> PyResult<()> {
        self.inner
            .set_input_force(fx, fy)
            .map_err(|e| input(e.to_string()))
    }

    /// Change the speed ratio from now on with a continuous forcing phase.
    fn set_speed_ratio(&mut self, speed_ratio: f64) -> PyResult<()> {
        self.inner
            .set_speed_ratio(speed_ratio)
            .map_err(|e| input(e.to_string()))
    }

    /// The current time τ.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }

    /// The current state (x, y, vx, vy).
    #[getter]
    fn state(&self) -> [f64; 4] {
        self.inner.state().to_array()
    }

    /// The current regime: free, contact or rolling.
    #[getter]
    fn regime(&self) -> &'static str {
        self.inner.regime().name()
    }

    /// The configured step length.
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.config().dt
    }

    fn __repr__(&self) -> String {
        format!(
            "Stepper(time={:e}, regime={}, dt={:e})",
            self.inner.time(),
            self.inner.regime().name(),
            self.inner.config().dt
        )
    }
}
