//! Every generated coefficient formula (`rotor_rub::coefficients`, written by `codegen/`) against
//! an independent computation: finite-difference Jacobians of the contact function, nalgebra
//! LU solves and eigenvalues, matrix exponentials of the equations of motion as first-order
//! linear systems, and finite-difference residuals of the ODEs (`docs/MODEL.md` §2–§7).
//!
//! Property tests run over the random physical ensemble of [`support::any_case`] with a fixed
//! seed (set `PROPTEST_RNG_SEED` to explore others); the named tests cover each degenerate case
//! of `docs/MODEL.md` §6 and each paper erratum of §7. Each tolerance is justified where it is used.

#[path = "generated/support.rs"]
mod support;

#[path = "generated/linearization.rs"]
mod linearization;

#[path = "generated/particular.rs"]
mod particular;

#[path = "generated/modes.rs"]
mod modes;

#[path = "generated/homogeneous.rs"]
mod homogeneous;

#[path = "generated/segments.rs"]
mod segments;

#[path = "generated/errata.rs"]
mod errata;

#[path = "generated/field.rs"]
mod field;

#[path = "generated/bits.rs"]
mod bits;

#[path = "generated/friction.rs"]
mod friction;
