//! One pass over a trajectory: switches, samples at chosen times and the propagation time.

use std::time::{Duration, Instant};

use rotor_rub::{
    Event, Options, Problem, Propagate, PropagationError, Propagator, Regime, Sample, advance_to,
};

use crate::error::CliError;

/// What a pass saw.
pub struct Pass {
    /// The regime at the start.
    pub initial_regime: Regime,
    /// Every switch, in order.
    pub events: Vec<Event>,
    /// The state at the end time.
    pub last: Sample,
    /// Time spent propagating (excludes what `on_sample` does).
    pub elapsed: Duration,
}

/// Build the propagator for `problem` (an invalid problem or option is an input error).
pub fn start(problem: &Problem, options: &Options) -> Result<Propagator, CliError> {
    Propagator::new(problem, options).map_err(|e| CliError::propagation("", e))
}

/// Propagate from the propagator's time to `end`, handing the sample at each of `times`
/// (non-decreasing, within the run) to `on_sample` and each switch to `on_event`, in time order
/// (a switch at a sample time comes before the sample).
pub fn run<E>(
    mut propagator: Propagator,
    end: f64,
    times: impl IntoIterator<Item = f64>,
    mut on_event: impl FnMut(&Event) -> Result<(), E>,
    mut on_sample: impl FnMut(&Sample) -> Result<(), E>,
) -> Result<Pass, E>
where
    E: From<PropagationError>,
{
    let mut elapsed = Duration::ZERO;
    let initial_regime = propagator.regime();
    let mut events = Vec::new();
    let mut emitted = 0;
    let mut step = |propagator: &mut Propagator, t: f64, events: &mut Vec<Event>| {
        let started = Instant::now();
        let sample = advance_to(propagator, t, |e| events.push(*e));
        elapsed += started.elapsed();
        sample
    };
    for t in times {
        let sample = step(&mut propagator, t.min(end), &mut events)?;
        for e in &events[emitted..] {
            on_event(e)?;
        }
        emitted = events.len();
        on_sample(&sample)?;
    }
    let last = step(&mut propagator, end, &mut events)?;
    for e in &events[emitted..] {
        on_event(e)?;
    }
    Ok(Pass {
        initial_regime,
        events,
        last,
        elapsed,
    })
}

/// [`run`] keeping every sample.
pub fn run_collect(
    propagator: Propagator,
    end: f64,
    times: impl IntoIterator<Item = f64>,
) -> Result<(Pass, Vec<Sample>), CliError> {
    let mut samples = Vec::new();
    let pass = run(
        propagator,
        end,
        times,
        |_| Ok(()),
        |s: &Sample| {
            samples.push(*s);
            Ok::<(), CliError>(())
        },
    )?;
    Ok((pass, samples))
}

/// `per_period` samples per forcing period from `start` to `end` inclusive.
pub fn dense_times(
    start: f64,
    end: f64,
    period: f64,
    per_period: usize,
) -> impl Iterator<Item = f64> {
    let count = (((end - start) / period) * per_period as f64)
        .ceil()
        .max(1.0) as usize
        + 1;
    uniform_times(start, end, count)
}

/// `count` times spaced uniformly from `start` to `end` inclusive: t_i = start + (end − start)·i/(count − 1),
/// the last exactly `end` (one time, `start`, when `count` is 1).
pub fn uniform_times(start: f64, end: f64, count: usize) -> impl Iterator<Item = f64> {
    let span = end - start;
    let last = count.saturating_sub(1);
    (0..count).map(move |i| {
        if i == last && i > 0 {
            end
        } else if last == 0 {
            start
        } else {
            start + span * i as f64 / last as f64
        }
    })
}

/// The times `start + k·period` for k in `0..count`: forcing-period boundaries when `start` is one.
pub fn period_times(first_period: u64, period: f64, count: u64) -> impl Iterator<Item = f64> {
    (first_period..first_period + count).map(move |k| k as f64 * period)
}

/// Fraction of [start, end] spent in contact, from the regime at `start` and the switches.
pub fn contact_fraction(initial: Regime, events: &[Event], start: f64, end: f64) -> f64 {
    if end <= start {
        return if initial == Regime::Contact { 1.0 } else { 0.0 };
    }
    let mut in_contact = initial == Regime::Contact;
    let mut since = start;
    let mut total = 0.0;
    for e in events {
        if in_contact {
            total += e.time - since;
        }
        in_contact = e.kind.regime_after() == Regime::Contact;
        since = e.time;
    }
    if in_contact {
        total += end - since;
    }
    total / (end - start)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rotor_rub::{EventKind, State};

    #[test]
    fn uniform_times_hit_both_ends() {
        let t: Vec<f64> = uniform_times(0.0, 0.3, 4).collect();
        assert_eq!(t.len(), 4);
        assert_eq!(t[0], 0.0);
        assert_eq!(t[3], 0.3);
        assert_eq!(t[1], 0.3 * 1.0 / 3.0);
    }

    #[test]
    fn contact_fraction_from_events() {
        let ev = |time, kind| Event {
            time,
            kind,
            state: State::default(),
        };
        let events = [ev(1.0, EventKind::Enter), ev(3.0, EventKind::Exit)];
        assert_eq!(contact_fraction(Regime::Free, &events, 0.0, 4.0), 0.5);
        let events = [ev(1.0, EventKind::Exit)];
        assert_eq!(contact_fraction(Regime::Contact, &events, 0.0, 4.0), 0.25);
    }
}
