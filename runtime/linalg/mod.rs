//! Linear algebra for matrix models: exact free flight of any linear rotor
//! M q'' + (C + ηG) q' + K q = Re(F e^{iηs}) + u (n = 2 … 64 degrees of freedom), and rigorous
//! bounds of a rub station's motion for the switch search (`docs/MODEL.md`, "Linear algebra for
//! matrix models").
//!
//! `#![no_std]`, no heap, no panics: every type has a const-generic capacity CAP (the largest
//! first-order dimension m = 2n it holds) and works on a runtime size ≤ CAP; all are plain
//! `Clone` data. The embedded stepper uses CAP = 8 (n = 4); the CLI and Python box CAP = 128.
//!
//! - [`Complex`], [`Matrix`] (real [`RealMatrix`], complex [`ComplexMatrix`]) and [`Lu`]: the
//!   small dense kit (`complex.rs`, `dense.rs`, `lu.rs`).
//! - [`SecondOrder`]: the rotor's M, C, G, K, checked, and its first-order matrix A
//!   (`first_order.rs`).
//! - [`ModalExponential`]: e^{As} in a stable modal form A = S J S⁻¹ (`modal.rs`, built by
//!   `hessenberg.rs`, `schur.rs`, `cluster.rs`; block exponentials in `block.rs`), exact to
//!   rounding in every degenerate case (repeated, defective, near-defective, zero, growing,
//!   purely imaginary eigenvalues).
//! - [`ProjectedMotion`]: d(s) = B e^{As} y0 for a 2 × m B at O(m) per evaluation, with d', d''
//!   and bounds over an interval whose proof is in `projected.rs` (the bounds themselves in
//!   `projected_bound.rs`).
//! - [`HarmonicResponse`]: the particular solution for harmonic and constant forcing
//!   (`harmonic.rs`), and its projection [`ProjectedHarmonic`].
//! - [`eigenvalues`] (`eigen.rs`): the eigenvalues of any real matrix, sorted by modulus (Floquet
//!   multipliers of a monodromy matrix).

mod block;
mod cluster;
mod complex;
mod conjugate;
mod consistent;
mod dense;
mod eigen;
mod error;
mod first_order;
mod harmonic;
mod hessenberg;
mod lu;
mod modal;
mod projected;
mod projected_bound;
mod schur;

pub use cluster::{MAX_COUPLING, MERGE_DISTANCE};
pub use complex::Complex;
pub use dense::{ComplexMatrix, Matrix, RealMatrix, Scalar};
pub use eigen::eigenvalues;
pub use error::LinalgError;
pub use first_order::SecondOrder;
pub use harmonic::{HarmonicResponse, ProjectedHarmonic};
pub use lu::Lu;
pub use modal::{ModalExponential, ModalVector};
pub use projected::{BOUND_MARGIN, ProjectedBound, ProjectedMotion, ProjectedPoint};
