//! Exact free flight of rotors from matrices and its contact search (`rotor_rub::matrix::
//! ExactFree`, issues 28 and 29) against references that need no trust in the code: a 30-digit
//! mpmath and scipy's matrix exponential of the augmented system (`scripts/matrix_expm.py`,
//! `tests/data/matrix_free/`), nalgebra's exponential, and the planar model's 30-digit switch
//! list. No allocation while it runs.

#[path = "matrix_free/common.rs"]
mod common;

#[path = "matrix_free/accuracy.rs"]
mod accuracy;

#[path = "matrix_free/contacts.rs"]
mod contacts;

#[path = "matrix_free/sampling.rs"]
mod sampling;

#[path = "matrix_free/degenerate.rs"]
mod degenerate;

#[path = "matrix_free/properties.rs"]
mod properties;

#[path = "matrix_free/no_alloc.rs"]
mod no_alloc;
