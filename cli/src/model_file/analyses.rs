//! The analyses (`poincare`, `spectrum`, `sweep`, `runup`) on a matrix model: a model file
//! (`--model FILE`, SI) or the paper's rotor with a stator ring of mass (`stator_mass_ratio` >
//! 0, dimensionless). Both run the matrix propagator (`rotor_rub::matrix::MatrixPropagator`,
//! every method); [`Subject::sample`] records the states at the times an analysis asks for, as
//! rows of named columns, every switch charged to the command's work budget.
//!
//! Columns: a model file's rows are the DOFs (m, or rad on rotations), their velocities (`v` +
//! name), then the rub station's relative displacement and velocity P = q_rotor − q_stator
//! (`rub_x`, `rub_y`, `rub_vx`, `rub_vy`), all SI; the ring's are `x, y, vx, vy, xs, ys, vxs,
//! vys` (clearances, τ). Plots draw the station (the rotor for the ring) in clearances with the
//! clearance circle.

use std::sync::Arc;

use rotor_rub::matrix::{MatrixModel, MatrixPropagator, MatrixState, ring_model, ring_start};
use rotor_rub::{EventKind, Options, Problem, Propagate, PropagationError, Regime};

use super::ring::RING_COLUMNS;
use super::spec::{CAPACITY, ModelError, ModelSpec, on_large_stack};
use crate::error::{CliError, Result};
use crate::limits::Tracker;

/// The station's columns of a model file's rows (after the DOFs and their velocities).
pub const STATION_COLUMNS: [&str; 4] = ["rub_x", "rub_y", "rub_vx", "rub_vy"];

/// What a matrix analysis runs.
#[derive(Clone, Debug)]
pub enum Subject {
    /// A model file, SI (`label`: the file's name, for messages).
    File {
        /// The model.
        spec: Box<ModelSpec>,
        /// The file's path as the user gave it.
        label: String,
    },
    /// The paper's rotor with a stator ring of mass (m̂ > 0), dimensionless.
    Ring(Problem),
}

/// States sampled at chosen times: `columns` (every column of the subject), one row per time.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// The columns' names.
    pub columns: Vec<String>,
    /// The sample times (s for a model file, τ for the ring).
    pub times: Vec<f64>,
    /// The rows, `columns.len()` entries each.
    pub data: Vec<f64>,
    /// The regime at each sample.
    pub regimes: Vec<Regime>,
}

impl Table {
    /// The rows.
    pub fn rows(&self) -> impl Iterator<Item = &[f64]> {
        self.data.chunks(self.columns.len().max(1))
    }

    /// The index of column `name`.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// The values of column `index`, one per row.
    pub fn column(&self, index: usize) -> Vec<f64> {
        self.rows()
            .map(|r| r.get(index).copied().unwrap_or(f64::NAN))
            .collect()
    }
}

impl Subject {
    /// A model file's subject.
    pub fn file(spec: ModelSpec, path: &std::path::Path) -> Self {
        Subject::File {
            spec: Box::new(spec),
            label: path.display().to_string(),
        }
    }

    /// The forcing period: 2π/Ω s for a model file, 2π/η for the ring.
    pub fn period(&self) -> f64 {
        match self {
            Subject::File { spec, .. } => std::f64::consts::TAU / spec.speed,
            Subject::Ring(p) => p.params.forcing_period(),
        }
    }

    /// The run's start time (0 for a model file).
    pub fn start_time(&self) -> f64 {
        match self {
            Subject::File { .. } => 0.0,
            Subject::Ring(p) => p.start_time,
        }
    }

    /// The running speed (Ω rad/s, or η).
    pub fn speed(&self) -> f64 {
        match self {
            Subject::File { spec, .. } => spec.speed,
            Subject::Ring(p) => p.params.speed_ratio,
        }
    }

    /// How reports name the speed: `Ω = … rad/s` or `η = …`.
    pub fn speed_label(&self) -> String {
        match self {
            Subject::File { spec, .. } => {
                format!("Ω = {} rad/s", crate::error::num(spec.speed))
            }
            Subject::Ring(p) => format!("η = {}", crate::error::num(p.params.speed_ratio)),
        }
    }

    /// The unit of lengths in the files: `m` or `clearances`.
    pub fn length_unit(&self) -> &'static str {
        match self {
            Subject::File { .. } => "m",
            Subject::Ring(_) => "clearances",
        }
    }

    /// The length that is one clearance in the files' unit (δ m, or 1).
    pub fn clearance(&self) -> f64 {
        match self {
            Subject::File { spec, .. } => spec.rub.clearance,
            Subject::Ring(_) => 1.0,
        }
    }

    /// The stator centre in clearances (the plots' clearance circle).
    pub fn offset(&self) -> (f64, f64) {
        match self {
            Subject::File { spec, .. } => {
                let d = spec.rub.clearance;
                (spec.rub.offset.0 / d, spec.rub.offset.1 / d)
            }
            Subject::Ring(p) => (p.params.offset_x, p.params.offset_y),
        }
    }

    /// Every column of the subject's rows, in order.
    pub fn columns(&self) -> Vec<String> {
        match self {
            Subject::File { spec, .. } => {
                let mut names = spec.dofs.clone();
                names.extend(spec.dofs.iter().map(|d| format!("v{d}")));
                names.extend(STATION_COLUMNS.iter().map(|c| c.to_string()));
                names
            }
            Subject::Ring(_) => RING_COLUMNS.iter().map(|c| c.to_string()).collect(),
        }
    }

    /// The columns a section writes by default: the station's relative state for a model file,
    /// the rotor's then the ring's state for the ring.
    pub fn section_columns(&self) -> Vec<String> {
        match self {
            Subject::File { .. } => STATION_COLUMNS.iter().map(|c| c.to_string()).collect(),
            Subject::Ring(_) => RING_COLUMNS.iter().map(|c| c.to_string()).collect(),
        }
    }

    /// The (x, y) pair whose motion the plots and the response class follow: the station's
    /// relative displacement (`rub_x`, `rub_y`) or the rotor's (`x`, `y`).
    pub fn orbit_columns(&self) -> [&'static str; 4] {
        match self {
            Subject::File { .. } => STATION_COLUMNS,
            Subject::Ring(_) => ["x", "y", "vx", "vy"],
        }
    }

    /// The columns `names` (comma-separated, as an option gives them) as indices into
    /// [`Subject::columns`].
    ///
    /// # Errors
    /// An unknown or repeated name, naming `flag` and the valid names.
    pub fn pick(&self, flag: &str, names: &str) -> Result<Vec<usize>> {
        let all = self.columns();
        let mut picked = Vec::new();
        for name in names.split(',').map(str::trim) {
            let Some(i) = all.iter().position(|c| c == name) else {
                return Err(CliError::input(format!(
                    "{flag}: unknown column '{}': expected names among {}",
                    name.escape_debug(),
                    all.join(", ")
                )));
            };
            if picked.contains(&i) {
                return Err(CliError::input(format!(
                    "{flag}: column '{name}' is given twice"
                )));
            }
            picked.push(i);
        }
        Ok(picked)
    }

    /// Check that the subject states a model the methods run (before any file is created).
    ///
    /// # Errors
    /// The model file's first wrong value (named with the file), or the ring's refusal.
    pub fn check(&self, options: &Options) -> Result<()> {
        options.validate().map_err(CliError::from)?;
        match self {
            Subject::File { spec, label } => {
                let spec = spec.as_ref().clone();
                on_large_stack(move || spec.build().map(|_| ())).map_err(|e| model_error(label, e))
            }
            Subject::Ring(p) => ring_model(&p.params)
                .map(|_| ())
                .map_err(|e| CliError::from(PropagationError::from(e))),
        }
    }

    /// Run from the start to the last of `times` (increasing, from the start time on) and
    /// record every column at each of them; every switch is charged to `tracker`.
    ///
    /// # Errors
    /// The model's refusal (an input error naming the file), an option the method refuses, a
    /// failed run, the budget exceeded.
    pub fn sample(
        &self,
        options: &Options,
        times: &[f64],
        tracker: &mut Tracker<'_>,
    ) -> Result<Table> {
        let segment = Segment { start: None, times };
        Ok(self.run(options, segment, tracker, |_, _, _| Ok(()))?.0)
    }

    /// The subject run at the speed `speed` (Ω rad/s, or η) with the forcing phase `phase`
    /// (θ = speed·t + phase): a model file's matrices re-evaluated at that speed when they
    /// depend on it.
    pub fn at_speed(&self, speed: f64, phase: f64) -> Subject {
        match self {
            Subject::File { spec, label } => {
                let mut spec = spec.clone();
                spec.speed = speed;
                spec.phase = phase;
                Subject::File {
                    spec,
                    label: label.clone(),
                }
            }
            Subject::Ring(problem) => {
                let mut problem = *problem;
                problem.params.speed_ratio = speed;
                problem.params.phase = phase;
                Subject::Ring(problem)
            }
        }
    }

    /// The forcing phase φ0 at time 0 (θ = speed·t + φ0).
    pub fn phase(&self) -> f64 {
        match self {
            Subject::File { spec, .. } => spec.phase,
            Subject::Ring(p) => p.params.phase,
        }
    }

    /// Run `segment` and record every column at each of its times; every switch is charged to
    /// `tracker` and handed to `on_event` (its time, kind and row). Returns the table and the
    /// end state (the model's raw state, in clearances: what [`Segment::start`] takes).
    ///
    /// # Errors
    /// As [`Subject::sample`]; what `on_event` returns.
    pub fn run(
        &self,
        options: &Options,
        segment: Segment<'_>,
        tracker: &mut Tracker<'_>,
        on_event: impl FnMut(f64, EventKind, &[f64]) -> Result<()> + Send,
    ) -> Result<(Table, Vec<f64>)> {
        let columns = self.columns();
        match self {
            Subject::File { spec, label } => {
                let spec = spec.as_ref();
                on_large_stack(|| {
                    let model: Arc<MatrixModel<CAPACITY>> =
                        Arc::from(spec.build().map_err(|e| model_error(label, e))?);
                    let start = match segment.start {
                        Some((_, y)) => MatrixState::from_slice(y)
                            .map_err(|e| CliError::from(PropagationError::from(e)))?,
                        None => spec.start().map_err(|e| model_error(label, e))?,
                    };
                    let t0 = segment.start.map_or(0.0, |(t, _)| t);
                    let delta = spec.rub.clearance;
                    let row = |m: &MatrixModel<CAPACITY>, y: &[f64], out: &mut Vec<f64>| {
                        let p = m.station_motion(y);
                        out.extend(y.iter().map(|x| x * delta));
                        out.extend([p.at.x, p.at.y, p.rate.vx, p.rate.vy].map(|x| x * delta));
                    };
                    let run = Run {
                        t0,
                        columns,
                        times: segment.times,
                    };
                    record(model, start, options, run, tracker, row, on_event)
                })
            }
            Subject::Ring(problem) => {
                let model = Arc::new(ring_model(&problem.params).map_err(PropagationError::from)?);
                let start = match segment.start {
                    Some((_, y)) => MatrixState::from_slice(y)
                        .map_err(|e| CliError::from(PropagationError::from(e)))?,
                    None => ring_start(problem),
                };
                let t0 = segment.start.map_or(problem.start_time, |(t, _)| t);
                // The ring model's state is (x, y, xs, ys, x', y', xs', ys').
                let row = |_: &MatrixModel<8>, y: &[f64], out: &mut Vec<f64>| {
                    out.extend(
                        [0, 1, 4, 5, 2, 3, 6, 7].map(|i| y.get(i).copied().unwrap_or(f64::NAN)),
                    );
                };
                let run = Run {
                    t0,
                    columns,
                    times: segment.times,
                };
                record(model, start, options, run, tracker, row, on_event)
            }
        }
    }
}

/// A stretch of a run: where it starts and when to record.
#[derive(Clone, Copy, Debug)]
pub struct Segment<'a> {
    /// The start (time, raw state in clearances, as [`Subject::run`] returns it); `None`: the
    /// subject's start.
    pub start: Option<(f64, &'a [f64])>,
    /// The times to record at (increasing).
    pub times: &'a [f64],
}

struct Run<'a> {
    t0: f64,
    columns: Vec<String>,
    times: &'a [f64],
}

/// A model file's refusal as an input error naming the file.
pub fn model_error(label: &str, e: ModelError) -> CliError {
    CliError::input(format!("{label}: {e}"))
}

fn record<const CAP: usize>(
    model: Arc<MatrixModel<CAP>>,
    start: MatrixState<CAP>,
    options: &Options,
    run: Run<'_>,
    tracker: &mut Tracker<'_>,
    row: impl Fn(&MatrixModel<CAP>, &[f64], &mut Vec<f64>),
    mut on_event: impl FnMut(f64, EventKind, &[f64]) -> Result<()>,
) -> Result<(Table, Vec<f64>)> {
    let Run { t0, columns, times } = run;
    let mut propagator = Box::new(MatrixPropagator::new(
        Arc::clone(&model),
        t0,
        start,
        options,
    )?);
    let mut table = Table {
        data: Vec::with_capacity(times.len().saturating_mul(columns.len())),
        columns,
        times: Vec::with_capacity(times.len()),
        regimes: Vec::with_capacity(times.len()),
    };
    let mut event_row = Vec::new();
    for &t in times {
        while let Some(event) = propagator.advance(t)? {
            tracker.switch(event.time)?;
            event_row.clear();
            row(&model, event.state.as_slice(), &mut event_row);
            on_event(event.time, event.kind, &event_row)?;
        }
        tracker.budget().check(t)?;
        let state = propagator.state();
        row(&model, state.as_slice(), &mut table.data);
        table.times.push(propagator.time());
        table.regimes.push(propagator.regime());
    }
    Ok((table, propagator.state().as_slice().to_vec()))
}
