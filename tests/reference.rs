//! Integration tests of the numerical reference integrators (issue 4) and of the event
//! comparison utilities.

#[path = "reference/common.rs"]
mod common;

#[path = "reference/schemes.rs"]
mod schemes;

#[path = "reference/free_flight.rs"]
mod free_flight;

#[path = "reference/switching.rs"]
mod switching;

#[path = "reference/convergence.rs"]
mod convergence;

#[path = "reference/compare.rs"]
mod compare;

#[path = "reference/robustness.rs"]
mod robustness;
