//! Runs shared by the reliability tests.

use rotor_rub::{Event, EventKind, Method, Options, Preset, Problem, Propagator, advance_to};

/// The `dry-whip` preset (isotropic stator, sustained rolling) with the stator stiffness `k`.
pub fn dry_whip(k: f64) -> Problem {
    let mut p = Preset::DryWhip.problem();
    p.params.k_xx = k;
    p.params.k_yy = k;
    p
}

/// Every switch of `method` at `tol` up to `end`.
pub fn switches(problem: &Problem, method: Method, tol: f64, end: f64) -> Vec<Event> {
    let options = Options {
        tol: Some(tol),
        ..Options::with_method(method)
    };
    let mut p = Propagator::new(problem, &options).expect("valid problem");
    let mut out = Vec::new();
    advance_to(&mut p, end, |e| out.push(*e)).expect("propagates");
    out
}

/// The number of switches of each kind, in the order of [`EventKind::ALL`].
pub fn counts(events: &[Event]) -> [usize; 5] {
    let mut out = [0; 5];
    for e in events {
        let i = EventKind::ALL.iter().position(|k| *k == e.kind).unwrap();
        out[i] += 1;
    }
    out
}

/// The shortest time between two consecutive switches (∞ for fewer than two).
pub fn shortest_gap(events: &[Event]) -> (f64, usize) {
    events
        .windows(2)
        .enumerate()
        .map(|(i, w)| (w[1].time - w[0].time, i))
        .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
}
