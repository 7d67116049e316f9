//! The generated coefficient formulas (`codegen/`, written into `OUT_DIR` by `build.rs`).
//!
//! Every closed form of the model lives here: Taylor terms, linearized stiffness, particular and
//! homogeneous constants, mode data, and segment evaluation. Nothing in it is typed by hand; the
//! checked-in copy `codegen/snapshot/coefficients.rs` shows each change in review. The paper's
//! symbols (ν = `nu`, η = `eta`, F = `f`, ε̂ = `ex`/`ey`, K̂ = `kxx`…) are used inside; see the
//! symbol table in `ARCHITECTURE.md`.
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
    /// The paper's symbols of `params` (ν, η, F, K̂, ε̂, μ, ρ_R, u).
    #[inline]
    pub fn of(params: &crate::params::Params) -> Self {
        ModelParams {
            nu: params.damping_ratio,
            eta: params.speed_ratio,
            f: params.forcing_amplitude(),
            kxx: params.k_xx,
            kxy: params.k_xy,
            kyx: params.k_yx,
            kyy: params.k_yy,
            ex: params.offset_x,
            ey: params.offset_y,
            mu: params.friction_coefficient,
            rho_r: params.radius_ratio,
            force_x: params.force_x,
            force_y: params.force_y,
        }
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
