//! The linear algebra for matrix models (`rotor_rub::linalg`) against independent references:
//! closed forms of every degenerate case, nalgebra's matrix exponential (Al-Mohy & Higham's
//! scaling and squaring), eigenvalues, LU and complex solves. Accuracy is measured as
//! ‖ours − reference‖₂ / ‖reference‖₂ of the state e^{As} y0.

#[path = "linalg/common.rs"]
mod common;

#[path = "linalg/exponential.rs"]
mod exponential;

#[path = "linalg/projected.rs"]
mod projected;

#[path = "linalg/solves.rs"]
mod solves;

#[path = "linalg/no_alloc.rs"]
mod no_alloc;
