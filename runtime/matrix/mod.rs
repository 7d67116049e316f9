//! Rotors from matrices (`docs/MODEL.md` §17): any linear rotor
//! M q'' + (C + ηG) q' + K q = unbalance + u + B_rᵀ f_c − B_sᵀ f_c with a rub station where the
//! contact law of the planar model acts on the offset d = B_r q − B_s q − ε̂ of two points. The
//! model's size is a property of its statement ([`MatrixModel`], n ≤ CAP/2 in const-generic
//! storage, no heap), not of the runtime's types; the stator ring with mass is its n = 4
//! instance ([`ring_model`]).
//!
//! - `model.rs`: the statement, checked ([`MatrixModel`], [`Station`], [`Unbalance`]);
//!   `checks.rs`: its checks.
//! - `state.rs`: y = (q, q') ([`MatrixState`]).
//! - `linear.rs`: A's lower rows by their nonzero entries (the fields' linear part).
//! - `field.rs`: the regime fields and the station's quantities (generated station law).
//! - `system.rs`: the model as a [`crate::driver::System`] (start side, slip, divergence).
//! - `ring.rs`: the stator ring with mass from the parameter table.
//! - `free/`: exact free flight and its contact search ([`ExactFree`]).
//! - `error.rs`: [`MatrixError`].
//! - `switches.rs`: the switch functions with their rates ([`MatrixSwitches`]).
//! - `contact.rs`: `hybrid`'s contact and rolling by DOP853 with deferred dense output
//!   ([`Dop853Contact`]).
//! - `numerical.rs`: DOP853 and Dormand–Prince 5(4) on the whole system, every regime
//!   ([`NumericalSolver`]); the stand-in free flight ([`NumericalFree`]).
//! - `series.rs`, `taylor.rs`: Taylor series of the contact regimes, the station's law
//!   generated ([`MatrixExpansion`], [`TaylorContact`]).
//! - `methods.rs`: every method, and [`MatrixPropagator`] dispatching them by
//!   [`crate::Method`].

mod checks;
mod contact;
mod error;
mod field;
pub mod free;
mod linear;
mod methods;
mod model;
mod numerical;
mod ring;
mod series;
mod state;
mod switches;
mod system;
mod taylor;

pub use contact::Dop853Contact;
pub use error::MatrixError;
pub use field::StationMotion;
pub use free::{ExactFree, FreeWork};
pub use methods::{
    FreeFlight, HybridPropagator, MatrixPropagator, NumericalPropagator, Split, TaylorPropagator,
    numerical, split,
};
pub use model::{MatrixModel, Running, SPEED_RANGE, Station, Unbalance};
pub use numerical::{MatrixField, NumericalFree, NumericalSolver, STAND_IN_TOLERANCE, max_step};
pub use ring::{RING_CAPACITY, RingModel, ring_model, ring_start};
pub use series::{MatrixExpansion, Switch};
pub use state::MatrixState;
pub use switches::{Function, MatrixSwitches};
pub use taylor::TaylorContact;
