//! The generated coefficient formulas (`codegen/`, written into `OUT_DIR` by `build.rs`).
//!
//! Every closed form of the model lives here: Taylor terms, linearized stiffness, particular and
//! homogeneous constants, mode data, and segment evaluation. Nothing in it is typed by hand; the
//! checked-in copy `codegen/snapshot/coefficients.rs` shows each change in review. The model's
//! parameters are the parameter table's entries by name (`speed_ratio`, `k_xy`, …; their paper
//! symbols are tabled in `docs/MODEL.md` §0).
//!
//! Generated functions take and return small structs ([`ModelParams`], [`Position`],
//! [`LinearizedContact`], …), each field declared once in `codegen/src/model/symbols.rs`.
//! Functions only the generator's verification tests use (`tests/generated`) are
//! `#[doc(hidden)]`: public so that integration tests reach them, outside the documented API.
#![allow(
    missing_docs,
    clippy::all,
    clippy::pedantic,
    clippy::suspicious_operation_groupings,
    unused_parens
)]

include!(concat!(env!("OUT_DIR"), "/coefficients.rs"));

impl ModelParams {
    /// The model's parameters of `params`: the generated [`model_params`] (each table entry the
    /// formulas read, copied by name, and the derived F and η_m ρ̂).
    #[inline]
    pub fn of(params: &crate::params::Params) -> Self {
        model_params(params)
    }
}

impl From<crate::params::State> for StartState {
    #[inline]
    fn from(s: crate::params::State) -> Self {
        StartState {
            x0: s.x,
            y0: s.y,
            vx0: s.vx,
            vy0: s.vy,
        }
    }
}
