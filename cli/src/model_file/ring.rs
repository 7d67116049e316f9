//! The stator ring with mass (issue 28) from the paper's parameters: `stator_mass_ratio` > 0
//! states the n = 4 matrix model (`rotor_rub::matrix::ring_model`, dimensionless as the paper:
//! lengths in clearances, time τ), which [`simulate_ring`] runs with the matrix propagator. Its
//! results keep the planar model's columns and places (`x, y, vx, vy`) and add the ring's
//! (`xs, ys, vxs, vys`) after them.

use std::sync::Arc;

use rotor_rub::matrix::{ring_model, ring_start};
use rotor_rub::{Options, Problem, PropagationError};

use super::run::{MatrixRun, MatrixRunError, Recorder, Rows, propagate};

/// The state columns of a ring run, in output order: the rotor's, then the ring's.
pub const RING_COLUMNS: [&str; 8] = ["x", "y", "vx", "vy", "xs", "ys", "vxs", "vys"];

/// The ring model's state order (x, y, xs, ys, then the velocities) and the station's relative
/// displacement, as the recorder writes a row.
const MODEL_COLUMNS: [&str; 10] = [
    "x", "y", "xs", "ys", "vx", "vy", "vxs", "vys", "rub_x", "rub_y",
];

/// Where each of [`RING_COLUMNS`] is in a recorded row.
const ORDER: [usize; 8] = [0, 1, 4, 5, 2, 3, 6, 7];

/// Simulate the paper's rotor with a ring of mass (`problem.params.stator_mass_ratio` > 0) from
/// its start time to `end` (τ), sampling at `sample_times`; rows in [`RING_COLUMNS`] order.
///
/// # Errors
/// [`MatrixRunError::Propagation`]: the ring model cannot be stated
/// ([`PropagationError::InvalidModel`]), an option the method refuses, a failed run.
pub fn simulate_ring(
    problem: &Problem,
    options: &Options,
    end: f64,
    sample_times: &[f64],
) -> Result<MatrixRun, MatrixRunError> {
    let model = Arc::new(ring_model(&problem.params).map_err(PropagationError::from)?);
    let start = ring_start(problem);
    let columns = MODEL_COLUMNS.iter().map(|c| c.to_string()).collect();
    let recorder = Recorder::with_columns(Arc::clone(&model), columns, 1.0);
    let t0 = problem.start_time;
    let run = propagate(model, t0, start, options, end, sample_times, recorder)?;
    Ok(reorder(run))
}

fn reorder_rows(rows: Rows, width: usize) -> Rows {
    let state = rows
        .state
        .chunks(width)
        .flat_map(|row| {
            ORDER
                .iter()
                .map(move |&i| row.get(i).copied().unwrap_or(f64::NAN))
        })
        .collect();
    Rows { state, ..rows }
}

/// A recorded ring run in [`RING_COLUMNS`] order (the station's P dropped: it is x − xs).
fn reorder(run: MatrixRun) -> MatrixRun {
    let width = run.columns.len();
    let end_state = ORDER
        .iter()
        .map(|&i| run.end_state.get(i).copied().unwrap_or(f64::NAN))
        .collect();
    MatrixRun {
        columns: RING_COLUMNS.iter().map(|c| c.to_string()).collect(),
        events: reorder_rows(run.events, width),
        samples: reorder_rows(run.samples, width),
        end_state,
        ..run
    }
}

/// The ring's largest displacement |(xs, ys)| (clearances) over a run's switches, samples and
/// end.
pub fn largest_ring_displacement(run: &MatrixRun) -> f64 {
    let w = RING_COLUMNS.len();
    run.events
        .state
        .chunks(w)
        .chain(run.samples.state.chunks(w))
        .chain(std::iter::once(run.end_state.as_slice()))
        .filter_map(|r| Some(r.get(4)?.hypot(*r.get(5)?)))
        .fold(0.0, f64::max)
}
