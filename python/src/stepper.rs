//! The fixed-step stepper for Python loops (`rotor_rub.Stepper`): one step at a time, or many in
//! one call with the GIL released (Ctrl-C and progress checked), its full state readable and
//! settable (`Stepper.state`, a [`PyStepperState`]).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::{ContactScheme, Event, Parameter, Problem, State, Stepper, StepperConfig};
use rotor_rub_cli::limits::{fits_memory, memory_limit};
use rotor_rub_cli::options::parse_scheme;

use crate::args;
use crate::errors::{cli, input, stepper};
use crate::inputs;
use crate::runs::{kind_code, regime_code, states};
use crate::stepper_state::PyStepperState;
use crate::watch::{self, Progress};

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// A switch as (time, kind, (x, y, vx, vy)).
type PyEvent = (f64, &'static str, [f64; 4]);

fn event(e: &Event) -> PyEvent {
    (e.time, e.kind.name(), e.state.to_array())
}

/// Steps between two polls of a run's watch.
const STEPS_PER_POLL: u64 = 1024;

/// Bytes kept per step of `run`: time, state, regime code.
const BYTES_PER_STEP: usize = 8 + 32 + 1;

/// Fixed-step propagation (the C ABI's stepper): exact free flight, contact sub-steps, switches
/// located inside each step.
#[pyclass(name = "Stepper", module = "rotor_rub._core", subclass)]
pub struct PyStepper {
    inner: Stepper,
    /// The problem it started from, with every parameter change since (a start value changed
    /// before the first step rebuilds the stepper from it).
    problem: Problem,
    /// Whether it has stepped (or been set to a saved state): the start values are then fixed.
    moved: bool,
}

impl PyStepper {
    fn dt(&self, dt: Any<'_, '_>) -> PyResult<f64> {
        Ok(args::real_opt("dt", dt)?.unwrap_or(self.inner.config().dt))
    }

    /// The parameters in force copied back into the problem (after a change the stepper made).
    fn sync(&mut self) {
        self.problem.params = *self.inner.params();
    }
}

#[pymethods]
impl PyStepper {
    #[new]
    #[pyo3(signature = (*, preset=None, config=None, dt=None, contact_scheme=None,
        contact_substeps=None, max_substeps=None, **params))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        preset: Option<&str>,
        config: Option<String>,
        dt: Any<'_, '_>,
        contact_scheme: Any<'_, '_>,
        contact_substeps: Any<'_, '_>,
        max_substeps: Any<'_, '_>,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let problem = inputs::problem(preset, inputs::path(config), params)?;
        let scheme = args::text("contact_scheme", contact_scheme)?
            .map(|s| parse_scheme(&s))
            .transpose()
            .map_err(input)?
            .unwrap_or(ContactScheme::Exprb43);
        let small = |name: &str, value: Any<'_, '_>, default: u32| -> PyResult<u32> {
            match value {
                None => Ok(default),
                Some(v) => {
                    let n = args::count(name, v, 1)?;
                    u32::try_from(n).map_err(|_| {
                        input(format!(
                            "{name}: {n} is out of range: it must be an integer from 1 to {}",
                            rotor_rub::stepper::MAX_SUBSTEPS
                        ))
                    })
                }
            }
        };
        let config = StepperConfig {
            dt: args::real_opt("dt", dt)?.unwrap_or(1e-3),
            scheme,
            contact_substeps: small("contact_substeps", contact_substeps, 1)?,
            max_substeps: small("max_substeps", max_substeps, 8)?,
            ..StepperConfig::default()
        };
        let inner = Stepper::new(&problem, config).map_err(stepper)?;
        Ok(PyStepper {
            inner,
            problem,
            moved: false,
        })
    }

    /// Advance one step of `dt` (default: the configured one). Returns (time, state, regime,
    /// events), events as (time, kind, state) tuples.
    #[pyo3(signature = (dt=None))]
    fn step(&mut self, dt: Any<'_, '_>) -> PyResult<(f64, [f64; 4], &'static str, Vec<PyEvent>)> {
        let dt = self.dt(dt)?;
        let report = self.inner.step(dt).map_err(stepper)?;
        self.moved = true;
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
    /// codes index `EVENT_KINDS`). The Python layer turns codes into names. Stops at the first
    /// error (the stepper then stands after the last good step). The arrays' size is checked
    /// against memory before any step.
    #[pyo3(signature = (steps, dt=None, progress=None))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        steps: &Bound<'py, PyAny>,
        dt: Any<'_, 'py>,
        progress: Any<'_, 'py>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let steps = args::count("steps", steps, 0)?;
        let dt = self.dt(dt)?;
        let n = fits_memory("steps", steps, BYTES_PER_STEP).map_err(cli)?;
        let max_events = memory_limit() / 2 / std::mem::size_of::<Event>() as u64;
        let inner = &mut self.inner;
        let taken = Arc::new(AtomicU64::new(0));
        let counted = Arc::clone(&taken);
        let done: watch::Done = Box::new(move |_| counted.load(Ordering::Relaxed) as f64);
        let progress = Progress::new(progress, steps as f64);
        let mut error = None;
        let (mut times, mut kept, mut regimes, mut events) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::new(),
        );
        let stopped = watch::on_this_thread(py, progress, done, |watch| {
            for k in 0..steps {
                if k % STEPS_PER_POLL == 0 {
                    taken.store(k, Ordering::Relaxed);
                    watch.poll(inner.time())?;
                }
                match inner.step(dt) {
                    Ok(report) => {
                        times.push(report.time);
                        kept.push(report.state);
                        regimes.push(regime_code(report.regime));
                        if (events.len() + report.events.len()) as u64 > max_events {
                            fits_memory(
                                "switches kept",
                                max_events + 1,
                                std::mem::size_of::<Event>(),
                            )?;
                        }
                        events.extend(report.events.iter().copied());
                    }
                    Err(e) => {
                        error = Some(e);
                        break;
                    }
                }
            }
            Ok(())
        });
        if !times.is_empty() {
            self.moved = true;
        }
        stopped?;
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

    /// Change parameters between steps (e.g. `speed_ratio=2.0`); state and time are kept. The
    /// start values (x0, y0, vx0, vy0) and the phase may change only before the first step
    /// (the stepper then starts again from them), as in the FMU.
    #[pyo3(signature = (**params))]
    fn set_params(&mut self, params: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let overrides = inputs::overrides(params)?;
        let mut problem = self.problem;
        let mut restart = false;
        for &(p, v) in &overrides {
            let fixed = !p.is_model() || p == Parameter::Phase;
            if fixed && self.moved {
                return Err(input(format!(
                    "{p}: the start values (x0, y0, vx0, vy0) and the phase are fixed once the \
                     stepper has stepped (τ = {}); make a new Stepper, set Stepper.state to a saved \
                     state, or change the speed with set_speed_ratio (the phase stays continuous)",
                    rotor_rub_cli::error::num(self.inner.time())
                )));
            }
            restart |= fixed;
            p.set(&mut problem, v);
        }
        problem
            .validate()
            .map_err(|e| input(format!("invalid parameters (from keyword arguments): {e}")))?;
        if restart {
            self.inner = Stepper::new(&problem, *self.inner.config()).map_err(stepper)?;
        } else {
            self.inner.set_params(&problem.params).map_err(stepper)?;
        }
        self.problem = problem;
        Ok(())
    }

    /// Apply the external input force (fx, fy) from now on, held until the next call (a
    /// controller's output; `docs/MODEL.md` §15). Cheap: the precomputed free map is kept.
    fn set_input_force(&mut self, fx: &Bound<'_, PyAny>, fy: &Bound<'_, PyAny>) -> PyResult<()> {
        let (fx, fy) = (args::real("fx", fx)?, args::real("fy", fy)?);
        self.inner
            .set_input_force(fx, fy)
            .map_err(|e| input(e.to_string()))?;
        self.sync();
        Ok(())
    }

    /// Change the speed ratio from now on with a continuous forcing phase.
    fn set_speed_ratio(&mut self, speed_ratio: &Bound<'_, PyAny>) -> PyResult<()> {
        let eta = args::real("speed_ratio", speed_ratio)?;
        self.inner
            .set_speed_ratio(eta)
            .map_err(|e| input(e.to_string()))?;
        self.sync();
        Ok(())
    }

    /// The full internal state (a `StepperState`): set it back and the stepper repeats its run
    /// bit for bit.
    #[getter]
    fn get_state(&self) -> PyStepperState {
        PyStepperState::of(&self.inner)
    }

    #[setter]
    fn set_state(&mut self, state: &Bound<'_, PyAny>) -> PyResult<()> {
        let state = state.cast::<PyStepperState>().map_err(|_| {
            input(format!(
                "state: {} is not a StepperState (one read from Stepper.state); to start from \
                 a position and velocity make a Stepper with x0=, y0=, vx0=, vy0=",
                crate::args::shown(state)
            ))
        })?;
        self.inner = state.get().restore()?;
        self.moved = true;
        self.sync();
        Ok(())
    }

    /// The current time τ.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }

    /// The current regime: free, contact or rolling.
    #[getter]
    fn regime(&self) -> &'static str {
        self.inner.regime().name()
    }

    /// The configured step length.
    #[getter(dt)]
    fn configured_dt(&self) -> f64 {
        self.inner.config().dt
    }

    /// Contact sub-steps per step of `dt`: the configured count, or more where the stator's
    /// contact mode needs them (each sub-step at most 0.5/ρ_c; see `largest_resolved_dt`).
    #[getter]
    fn contact_substeps(&self) -> u32 {
        self.inner.contact_substeps()
    }

    /// The longest step whose contact sub-steps fit `max_substeps` for the parameters in force
    /// (a longer step in contact is flagged `capped`, or refused with on_cap="fail").
    #[getter]
    fn largest_resolved_dt(&self) -> f64 {
        self.inner.largest_resolved_dt()
    }

    /// What the Python layer's results carry about this stepper: every parameter (the current
    /// model parameters, the start values it began from), "stepper", its scheme and step.
    fn _problem<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let params = PyDict::new(py);
        for p in rotor_rub_cli::problem::settable() {
            params.set_item(p.name(), p.get(&self.problem))?;
        }
        let config = self.inner.config();
        let out = PyDict::new(py);
        out.set_item("params", params)?;
        out.set_item("method", "stepper")?;
        out.set_item("tol", py.None())?;
        out.set_item("contact_scheme", config.scheme.name())?;
        out.set_item("step", config.dt)?;
        out.set_item(
            "method_text",
            format!("stepper ({}, dt {:e})", config.scheme.name(), config.dt),
        )?;
        out.set_item("version", env!("CARGO_PKG_VERSION"))?;
        Ok(out)
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
