//! The generated coefficient formulas (`codegen/`, written into `OUT_DIR` by `build.rs`).
//!
//! Every closed form of the model lives here: Taylor terms, linearized stiffness, particular and
//! homogeneous constants, mode data, and segment evaluation. Nothing in it is typed by hand; the
//! checked-in copy `codegen/snapshot/coefficients.rs` shows each change in review. The paper's
//! symbols (ν = `nu`, η = `eta`, F = `f`, ε̂ = `ex`/`ey`, K̂ = `kxx`…) are used inside; see the
//! symbol table in `ARCHITECTURE.md`.
#![allow(
    missing_docs,
    clippy::all,
    clippy::pedantic,
    clippy::suspicious_operation_groupings,
    unused_parens
)]

include!(concat!(env!("OUT_DIR"), "/coefficients.rs"));
