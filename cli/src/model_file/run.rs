//! Running a model file: [`simulate_matrix`] (the one entry point the CLI and Python call) and
//! the result assembly every front end shares ([`Recorder`] → [`MatrixRun`], in SI units, with
//! the columns named after the model's DOFs).
//!
//! [`simulate_matrix`] builds the model and its start, runs the matrix methods' propagator
//! (`rotor_rub::matrix::MatrixPropagator`, every method) and records every switch and sample in
//! SI units; everything around it (columns, units, CSV, Python's arrays) is shared by the CLI
//! and Python.

use std::sync::Arc;
use std::time::Duration;

use rotor_rub::matrix::MatrixPropagator;
use rotor_rub::{Event, EventKind, Options, Propagate, PropagationError, Regime, Sample};

use rotor_rub::matrix::{MatrixModel, MatrixState};

use super::spec::{CAPACITY, Model, ModelError, ModelSpec};

/// Why a matrix run did not produce a result.
#[derive(Debug, Clone, PartialEq)]
pub enum MatrixRunError {
    /// The model or its start is wrong (a message naming the key).
    Model(ModelError),
    /// A run option is wrong (the end time, the initial state's length, …).
    Input(String),
    /// The propagation failed (or the method refused an option).
    Propagation(PropagationError),
}

impl std::fmt::Display for MatrixRunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MatrixRunError::Model(e) => write!(f, "{e}"),
            MatrixRunError::Input(m) => f.write_str(m),
            MatrixRunError::Propagation(e) => write!(f, "propagation failed: {e}"),
        }
    }
}

impl std::error::Error for MatrixRunError {}

impl From<ModelError> for MatrixRunError {
    fn from(e: ModelError) -> Self {
        MatrixRunError::Model(e)
    }
}

impl From<PropagationError> for MatrixRunError {
    fn from(e: PropagationError) -> Self {
        MatrixRunError::Propagation(e)
    }
}

/// The state columns of a model's results: the DOFs (m, or rad on rotations), their velocities
/// (`v` + name), then the rub station's relative displacement P = q_rotor − q_stator (`rub_x`,
/// `rub_y`, m).
pub fn state_columns(spec: &ModelSpec) -> Vec<String> {
    let mut names: Vec<String> = spec.dofs.clone();
    names.extend(spec.dofs.iter().map(|d| format!("v{d}")));
    names.push("rub_x".into());
    names.push("rub_y".into());
    names
}

/// Rows of one kind of record (events or samples): times, a code per row, states row-major.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rows {
    /// Times, s.
    pub time: Vec<f64>,
    /// Event kinds (index into [`EventKind::ALL`]) or regimes (0 free, 1 contact, 2 rolling).
    pub code: Vec<u8>,
    /// States, `width` entries per row, SI.
    pub state: Vec<f64>,
}

impl Rows {
    /// The number of rows.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }
}

/// A matrix run's result, SI units: every switch and the samples, state columns as
/// [`state_columns`].
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixRun {
    /// The state columns' names.
    pub columns: Vec<String>,
    /// Every switch, in time order (codes: event kinds).
    pub events: Rows,
    /// The samples (codes: regimes).
    pub samples: Rows,
    /// The end time, s.
    pub end_time: f64,
    /// The state at the end, SI.
    pub end_state: Vec<f64>,
    /// Time free, in contact (slipping or frictionless), rolling, s.
    pub time_in: [f64; 3],
    /// Propagation wall time.
    pub elapsed: Duration,
}

impl MatrixRun {
    /// The number of events of `kind`.
    pub fn count(&self, kind: EventKind) -> usize {
        let code = kind_code(kind);
        self.events.code.iter().filter(|&&c| c == code).count()
    }

    /// The fraction of the run in contact (slipping or rolling).
    pub fn contact_fraction(&self) -> f64 {
        let total: f64 = self.time_in.iter().sum();
        if total > 0.0 {
            (self.time_in[1] + self.time_in[2]) / total
        } else {
            0.0
        }
    }
}

/// The index of `kind` in [`EventKind::ALL`].
pub fn kind_code(kind: EventKind) -> u8 {
    EventKind::ALL
        .iter()
        .position(|k| *k == kind)
        .map_or(u8::MAX, |i| i as u8)
}

/// The index of a regime: 0 free, 1 contact, 2 rolling (`rotor_rub.REGIMES`).
pub fn regime_code(regime: Regime) -> u8 {
    match regime {
        Regime::Free => 0,
        Regime::Contact => 1,
        Regime::Rolling => 2,
    }
}

/// Collects a run's events and samples as they come, in SI units.
pub struct Recorder<const CAP: usize = CAPACITY> {
    model: Arc<MatrixModel<CAP>>,
    clearance: f64,
    width: usize,
    run: MatrixRun,
    last: Option<(f64, Regime)>,
}

impl Recorder<CAPACITY> {
    /// A recorder for runs of `model` (stated from `spec`).
    pub fn new(model: Arc<Model>, spec: &ModelSpec) -> Self {
        Recorder::with_columns(model, state_columns(spec), spec.rub.clearance)
    }
}

impl<const CAP: usize> Recorder<CAP> {
    /// A recorder for runs of `model` whose rows are named `columns` (the state's 2n entries
    /// then the station's relative displacement) and scaled by `clearance` (1: dimensionless).
    pub fn with_columns(
        model: Arc<MatrixModel<CAP>>,
        columns: Vec<String>,
        clearance: f64,
    ) -> Self {
        Recorder {
            model,
            clearance,
            width: columns.len(),
            run: MatrixRun {
                columns,
                events: Rows::default(),
                samples: Rows::default(),
                end_time: 0.0,
                end_state: Vec::new(),
                time_in: [0.0; 3],
                elapsed: Duration::ZERO,
            },
            last: None,
        }
    }

    /// The row of `state` (clearances) in SI: q·δ, q'·δ, P·δ.
    pub fn row(&self, state: &MatrixState<CAP>) -> Vec<f64> {
        let y = state.as_slice();
        let p = self.model.station_motion(y).at;
        let mut row = Vec::with_capacity(self.width);
        row.extend(y.iter().map(|x| x * self.clearance));
        row.push(p.x * self.clearance);
        row.push(p.y * self.clearance);
        row
    }

    /// The run starts at `time` in `regime` (the regime account's origin).
    pub fn begin(&mut self, time: f64, regime: Regime) {
        self.last = Some((time, regime));
    }

    /// A switch (also the regime's time account: the regime before it holds until it).
    pub fn event(&mut self, e: &Event<MatrixState<CAP>>) {
        let after = match e.kind {
            EventKind::Exit => Regime::Free,
            EventKind::Roll => Regime::Rolling,
            EventKind::Enter | EventKind::Reverse | EventKind::Slip => Regime::Contact,
        };
        self.account(e.time, after);
        let row = self.row(&e.state);
        self.run.events.time.push(e.time);
        self.run.events.code.push(kind_code(e.kind));
        self.run.events.state.extend(row);
    }

    /// A sample (also the regime's time account: each sample's regime holds until the next).
    pub fn sample(&mut self, s: &Sample<MatrixState<CAP>>) {
        let row = self.row(&s.state);
        self.account(s.time, s.regime);
        self.run.samples.time.push(s.time);
        self.run.samples.code.push(regime_code(s.regime));
        self.run.samples.state.extend(row);
    }

    fn account(&mut self, time: f64, regime: Regime) {
        if let Some((t0, r0)) = self.last
            && let Some(slot) = self.run.time_in.get_mut(regime_code(r0) as usize)
        {
            *slot += (time - t0).max(0.0);
        }
        self.last = Some((time, regime));
    }

    /// The result, ending at the sample `end` after `elapsed` of propagation. `time_in` is
    /// what the propagator reports when it has it, else the account of the switches and
    /// samples.
    pub fn finish(
        mut self,
        end: &Sample<MatrixState<CAP>>,
        time_in: Option<[f64; 3]>,
        elapsed: Duration,
    ) -> MatrixRun {
        self.account(end.time, end.regime);
        self.run.end_time = end.time;
        self.run.end_state = self.row(&end.state);
        if let Some(t) = time_in {
            self.run.time_in = t;
        }
        self.run.elapsed = elapsed;
        self.run
    }
}

/// The end time of a run: `t_end` (s) or `periods` forcing periods 2π/Ω (default 20).
///
/// # Errors
/// Both given, or a value that is not a finite number > 0.
pub fn end_time(spec: &ModelSpec, t_end: Option<f64>, periods: Option<f64>) -> Result<f64, String> {
    let positive = |name: &str, x: f64| {
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(format!(
                "{name} = {x} is out of range: it must be a finite number > 0"
            ))
        }
    };
    match (t_end, periods) {
        (Some(_), Some(_)) => {
            Err("give t_end or periods, not both (they both set the run length)".into())
        }
        (Some(t), None) => positive("t_end", t),
        (None, p) => {
            Ok(positive("periods", p.unwrap_or(20.0))? * std::f64::consts::TAU / spec.speed)
        }
    }
}

/// Simulate a model from matrices from t = 0 to `end` (s) with `options`, sampling at
/// `sample_times` (increasing, within [0, end]); `initial` replaces the spec's start (positions
/// then velocities, SI; `None`: the spec's, rest by default).
///
/// THE entry point of a matrix run for every front end (the CLI's `simulate --model`, Python's
/// `rr.simulate(model=…)`). Sample times at or after `end` are sampled at `end`. Run it on a
/// large stack ([`super::on_large_stack`]): the propagator of a capacity-128 model is large.
///
/// # Errors
/// [`MatrixRunError::Model`] for a model or start that is wrong, `Input` for a bad run length or
/// initial state, `Propagation` for a failed run or an option the method refuses.
pub fn simulate_matrix(
    spec: &ModelSpec,
    options: &Options,
    end: f64,
    sample_times: &[f64],
    initial: Option<&[f64]>,
) -> Result<MatrixRun, MatrixRunError> {
    if !(end.is_finite() && end > 0.0) {
        return Err(MatrixRunError::Input(format!(
            "the end time {end} s is out of range: it must be a finite number > 0"
        )));
    }
    options.validate()?;
    let mut spec = spec.clone();
    if let Some(y) = initial {
        let n = spec.dofs();
        if y.len() != 2 * n {
            return Err(MatrixRunError::Input(format!(
                "initial has {} entries; it must have 2n = {} (n = {n} positions, m, then n velocities, m/s)",
                y.len(),
                2 * n
            )));
        }
        let (q, v) = y.split_at(n);
        spec.initial = Some((q.to_vec(), v.to_vec()));
    }
    let model: Arc<Model> = Arc::from(spec.build()?);
    let start = spec.start()?;
    let recorder = Recorder::new(Arc::clone(&model), &spec);
    propagate(model, 0.0, start, options, end, sample_times, recorder)
}

/// The run of `model` from `(t0, start)` to `end` with `options`: every switch and a sample at
/// each of `sample_times` (those at or after `end` at `end`), into `recorder`.
///
/// # Errors
/// [`MatrixRunError::Propagation`] for an option the method refuses or a failed run.
pub fn propagate<const CAP: usize>(
    model: Arc<MatrixModel<CAP>>,
    t0: f64,
    start: MatrixState<CAP>,
    options: &Options,
    end: f64,
    sample_times: &[f64],
    mut recorder: Recorder<CAP>,
) -> Result<MatrixRun, MatrixRunError> {
    let clock = std::time::Instant::now();
    let mut propagator = Box::new(MatrixPropagator::new(model, t0, start, options)?);
    recorder.begin(t0, propagator.regime());
    for &t in sample_times.iter().filter(|&&t| t < end) {
        let s = rotor_rub::advance_to(propagator.as_mut(), t, |e| recorder.event(e))?;
        recorder.sample(&s);
    }
    let last = rotor_rub::advance_to(propagator.as_mut(), end, |e| recorder.event(e))?;
    if sample_times.last().is_some_and(|&t| t >= end) {
        recorder.sample(&last);
    }
    Ok(recorder.finish(&last, None, clock.elapsed()))
}
