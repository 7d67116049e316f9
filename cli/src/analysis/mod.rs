//! Analyses of trajectories: switch matching, response classification, Lyapunov exponents,
//! spectra.

pub mod classify;
pub mod lyapunov;
pub mod spectrum;
pub mod switches;
