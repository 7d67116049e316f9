//! The rotor–stator model as an FMI co-simulation FMU (FMI 3.0 and FMI 2.0, dimensionless or
//! in SI units, all from one binary), for hardware-in-the-loop rigs and system simulators: a
//! thin exported layer over `rotor_rub::Stepper`.
//!
//! * Outputs x, y, vx, vy, in_contact, normal_force, contact_count, slip_regime; inputs fx, fy
//!   (an external force held constant over a communication step) and the speed (phase kept
//!   continuous); every entry of the parameter table as a parameter (`variables.rs`), in the
//!   model's dimensionless units or in SI units scaled by ω_n, δ and M (`units.rs`).
//! * A communication step is covered by internal steps of at most `internal_step`, shortened
//!   where the contact sub-steps' error estimate exceeds `tolerance`, and capped at
//!   `max_internal_steps` (`step.rs`), so accuracy does not depend on the importer's step and no
//!   step blocks; every contact switch is located exactly; FMI 3.0 with early return allowed
//!   returns at the first switch with its time. Tunable parameters take effect at the next
//!   step as one validated set (`model.rs`).
//! * FMU state get/set/serialize (`state.rs`: versioned, checksummed); no allocation in
//!   `DoStep`; every error is an FMI error status with a logged message naming the value and
//!   its valid range, never a panic across the boundary (`instance.rs`).
//! * `description.rs` writes `modelDescription.xml` for either version and unit system from
//!   the same table, `documentation.rs` the FMU's `documentation/index.html`; `cargo xtask fmu`
//!   packs them with the binary into four `.fmu` archives.
//!
//! * `file/`: the FMU built for a model file of at most 4 DOFs (`cargo xtask fmu --model FILE`):
//!   the same binary, the model read from the FMU's resource at instantiation, variables named
//!   by the model's DOFs, stepped by the matrix stepper.
//!
//! The exported function names are FMI's (`fmi2DoStep`, `fmi3DoStep`, …).
#![allow(non_snake_case)]
// Errors carry their message in a fixed buffer (`message::Message`, 400 bytes) so that no error
// path allocates; boxing it, as clippy suggests for large error variants, would.
#![allow(clippy::result_large_err)]
#![deny(unsafe_op_in_unsafe_fn)]
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing
    )
)]

pub mod description;
pub mod documentation;
pub mod file;
pub mod fmi2;
pub mod fmi2_stubs;
pub mod fmi3;
pub mod fmi3_stubs;
pub mod instance;
pub mod log;
pub mod message;
pub mod model;
pub mod saved;
pub mod state;
pub mod step;
pub mod units;
pub mod variables;
