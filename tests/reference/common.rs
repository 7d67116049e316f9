//! Helpers shared by the reference-integrator tests.

use rotor_rub::{Event, Preset, Problem, Propagate, PropagationError, events};

/// The paper preset at speed ratio `eta`.
pub fn paper(eta: f64) -> Problem {
    let mut p = Preset::Paper.problem();
    p.params.speed_ratio = eta;
    p
}

/// Every switch of `prop` up to `end`, or the first error.
pub fn run_events<P: Propagate>(prop: &mut P, end: f64) -> Result<Vec<Event>, PropagationError> {
    events(prop, end).collect()
}
