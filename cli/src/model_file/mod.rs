//! Rotors from matrices in the user's hands (issue 29; `docs/MODEL_FILES.md`): the model file
//! (TOML for small models, `.npz` for matrices), read and checked value by value, stated in the
//! runtime's dimensionless form (lengths in clearances), and the commands on it.
//!
//! - `spec.rs`: [`ModelSpec`], the model in SI as a file or Python states it; [`ModelError`]
//!   naming the [`Key`]; the statement [`ModelSpec::build`] (a boxed `MatrixModel<128>`), the
//!   start, the modes, the speed-dependent matrices.
//! - `read.rs`: TOML and `.npz` → [`ModelSpec`] ([`load`]); `npz.rs`: the `.npz` reader.
//! - `run.rs`: [`simulate_matrix`], THE entry point of a matrix run (the matrix propagator,
//!   every method), and the result assembly ([`Recorder`] →
//!   [`MatrixRun`], SI, columns named after the DOFs).
//! - `ring.rs`: the stator ring with mass (issue 28, `stator_mass_ratio` > 0) as the n = 4
//!   matrix model, run by the same propagation ([`simulate_ring`]).
//! - `analyses.rs`: what `poincare`, `spectrum`, `sweep` and `runup` run on a model file or the
//!   ring ([`Subject`]: states sampled at chosen times, named columns, SI for a file);
//!   `choose.rs`: which model a command runs ([`target`]) and the columns an option names.
//! - `command.rs`: `rotor-rub check-model FILE`, `rotor-rub simulate --model FILE` and the
//!   ring's `simulate` ([`simulate_ring_command`]).

mod analyses;
mod choose;
mod command;
mod npz;
mod read;
mod ring;
mod run;
mod spec;

pub use analyses::{STATION_COLUMNS, Segment, Subject, Table, model_error};
pub use choose::{Target, chosen_columns, orbit_indices, orbit_state, planar_only, target};
pub use command::{
    CheckArgs, SimulateModel, check, read, report, simulate, simulate_ring_command, write_run,
};
pub use npz::{Array, read_npy, read_npz};
pub use read::{FORMAT, MAX_MODEL_BYTES, NPZ_KEYS, from_npz, from_toml, load, locate, npz_message};
pub use ring::{RING_COLUMNS, largest_ring_displacement, simulate_ring};
pub use run::{
    MatrixRun, MatrixRunError, Recorder, Rows, end_time, kind_code, propagate, regime_code,
    simulate_matrix, state_columns,
};
pub use spec::{
    CAPACITY, Dense, Key, MAX_DOFS, Model, ModelError, ModelSpec, ModelState, RubSpec, SpeedPoint,
    UnbalanceSpec, default_dof_names, on_large_stack,
};
