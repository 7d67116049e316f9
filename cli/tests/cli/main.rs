//! Integration tests of the `rotor-rub` binary (one test binary, one module per area).

mod analyses;
mod common;
mod errors;
mod fig2;
mod friction;
mod inputs;
mod matrix_analyses;
mod memory;
mod messages;
mod orbit;
mod pipes;
mod profiles;
mod readme;
mod reliability;
mod resonance;
mod runtime_reliability;
mod runup;
mod signals;
mod simulate;
mod sweep;
