//! One pass over a trajectory: switches, samples at chosen times and the propagation time, with
//! every switch charged to the command's work budget.

use std::time::{Duration, Instant};

use rotor_rub::{Event, EventKind, Options, Problem, Propagate, Propagator, Regime, Sample};

use crate::error::{CliError, Result};
use crate::limits::{Tracker, fits_memory, memory_limit, reserve};
use crate::watch::Stretches;

/// What a pass saw.
pub struct Pass {
    /// Every switch, in order (kept only when asked for).
    pub events: Vec<Event>,
    /// Number of switches.
    pub switches: u64,
    /// Number of switches of each kind, in [`EventKind::ALL`] order.
    pub kinds: [u64; EventKind::ALL.len()],
    /// Time spent free, slipping (or in frictionless contact) and rolling.
    pub time_in: [f64; 3],
    /// Fraction of the run spent in contact (slipping or rolling).
    pub contact_fraction: f64,
    /// The state at the end time.
    pub last: Sample,
    /// Time spent propagating (excludes what `on_sample` does).
    pub elapsed: Duration,
}

/// Build the propagator for `problem` (an invalid problem or option is an input error).
pub fn start(problem: &Problem, options: &Options) -> Result<Propagator> {
    Propagator::new(problem, options).map_err(|e| CliError::propagation("", e))
}

/// Advance to `time`, charging each switch to `tracker` and passing it to `on_event`, and return
/// the sample there. Stops with the budget's error as soon as the run exceeds it. Under a
/// watched budget the advance goes in stretches with a poll after each ([`crate::watch`]; the
/// same trajectory).
pub fn advance_to(
    propagator: &mut Propagator,
    time: f64,
    tracker: &mut Tracker<'_>,
    mut on_event: impl FnMut(&Event) -> Result<()>,
) -> Result<Sample> {
    let mut stretches = tracker.budget().watch().map(|_| Stretches::new(time));
    loop {
        let stop = stretches
            .as_mut()
            .map_or(time, |s| s.stop_after(propagator.time()));
        while let Some(event) = propagator.advance(stop)? {
            tracker.switch(event.time)?;
            on_event(&event)?;
        }
        match stretches.as_mut() {
            Some(s) if stop < time => {
                tracker.budget().check(stop)?;
                s.ended();
            }
            _ => break,
        }
    }
    Ok(Sample {
        time: propagator.time(),
        state: propagator.state(),
        regime: propagator.regime(),
    })
}

/// The Poincaré section: the states at the next `count` forcing-period boundaries.
pub fn section(
    propagator: &mut Propagator,
    speed_ratio: f64,
    count: usize,
    tracker: &mut Tracker<'_>,
) -> Result<Vec<Sample>> {
    let mut points = Vec::new();
    reserve(&mut points, count, "Poincaré points")?;
    for t in rotor_rub::poincare_times(propagator.time(), speed_ratio, count) {
        points.push(advance_to(propagator, t, tracker, |_| Ok(()))?);
    }
    Ok(points)
}

/// Propagate from the propagator's time to `end`, handing the sample at each of `times`
/// (non-decreasing, within the run) to `on_sample` and each switch to `on_event`, in time order
/// (a switch at a sample time comes before the sample). With `keep_events` the switches are also
/// kept in [`Pass::events`], as many as half of the command's memory share holds.
pub fn run(
    mut propagator: Propagator,
    end: f64,
    times: impl IntoIterator<Item = f64>,
    tracker: &mut Tracker<'_>,
    keep_events: bool,
    mut on_event: impl FnMut(&Event) -> Result<()>,
    mut on_sample: impl FnMut(&Sample) -> Result<()>,
) -> Result<Pass> {
    let start_time = propagator.time();
    let initial_regime = propagator.regime();
    let max_kept = memory_limit() / 2 / std::mem::size_of::<Event>() as u64;
    let mut elapsed = Duration::ZERO;
    let mut events = Vec::new();
    let mut switches = 0_u64;
    let mut kinds = [0_u64; EventKind::ALL.len()];
    let mut time_in = [0.0; 3];
    let (mut regime, mut since) = (initial_regime, start_time);
    let mut step = |propagator: &mut Propagator, t: f64| {
        let started = Instant::now();
        let sample = advance_to(propagator, t, tracker, |e| {
            switches += 1;
            if let Some(n) = EventKind::ALL
                .iter()
                .position(|k| *k == e.kind)
                .and_then(|i| kinds.get_mut(i))
            {
                *n += 1;
            }
            if let Some(spent) = time_in.get_mut(regime_index(regime)) {
                *spent += e.time - since;
            }
            (regime, since) = (e.kind.regime_after(), e.time);
            if keep_events {
                if switches > max_kept {
                    fits_memory("switches kept", switches, std::mem::size_of::<Event>())?;
                }
                reserve(&mut events, 1, "switches kept")?;
                events.push(*e);
            }
            on_event(e)
        });
        elapsed += started.elapsed();
        sample
    };
    for t in times {
        let sample = step(&mut propagator, t.min(end))?;
        on_sample(&sample)?;
    }
    let last = step(&mut propagator, end)?;
    if let Some(spent) = time_in.get_mut(regime_index(regime)) {
        *spent += end - since;
    }
    let [_, slipping, rolling] = time_in;
    let contact_fraction = if end > start_time {
        (slipping + rolling) / (end - start_time)
    } else {
        f64::from(u8::from(initial_regime.in_contact()))
    };
    Ok(Pass {
        events,
        switches,
        kinds,
        time_in,
        contact_fraction,
        last,
        elapsed,
    })
}

/// [`run`] keeping every switch and every sample (`count` of them, checked against memory).
pub fn run_collect(
    propagator: Propagator,
    end: f64,
    times: impl IntoIterator<Item = f64>,
    tracker: &mut Tracker<'_>,
) -> Result<(Pass, Vec<Sample>)> {
    let mut samples = Vec::new();
    let pass = run(
        propagator,
        end,
        times,
        tracker,
        true,
        |_| Ok(()),
        |s: &Sample| {
            reserve(&mut samples, 1, "samples kept")?;
            samples.push(*s);
            Ok(())
        },
    )?;
    Ok((pass, samples))
}

/// Number of [`dense_times`]: `per_period` per forcing period from `start` to `end`, plus one
/// (saturating: a count too large for memory is refused by the caller's check).
pub fn dense_count(start: f64, end: f64, period: f64, per_period: u64) -> u64 {
    let count = (((end - start) / period) * per_period as f64)
        .ceil()
        .max(1.0);
    (count as u64).saturating_add(1)
}

/// `per_period` samples per forcing period from `start` to `end` inclusive.
pub fn dense_times(
    start: f64,
    end: f64,
    period: f64,
    per_period: u64,
) -> impl Iterator<Item = f64> {
    let count = dense_count(start, end, period, per_period);
    uniform_times(start, end, usize::try_from(count).unwrap_or(usize::MAX))
}

/// `count` times spaced uniformly from `start` to `end` inclusive: t_i = start + (end − start)·i/(count − 1),
/// the last exactly `end` (one time, `start`, when `count` is 1).
pub fn uniform_times(start: f64, end: f64, count: usize) -> impl Iterator<Item = f64> {
    (0..count).map(move |i| uniform_at(start, end, count as u64, i as u64))
}

/// The `i`-th of [`uniform_times`] (computed alone, for any count).
pub fn uniform_at(start: f64, end: f64, count: u64, i: u64) -> f64 {
    let last = count.saturating_sub(1);
    if i == last && i > 0 {
        end
    } else if last == 0 {
        start
    } else {
        start + (end - start) * i as f64 / last as f64
    }
}

/// The times `k·period` for `count` periods k from `first_period` on (saturating at u64::MAX:
/// callers check the sum first).
pub fn period_times(first_period: u64, period: f64, count: u64) -> impl Iterator<Item = f64> {
    (first_period..first_period.saturating_add(count)).map(move |k| k as f64 * period)
}

/// The index of a regime in [`Pass::time_in`].
pub fn regime_index(regime: Regime) -> usize {
    match regime {
        Regime::Free => 0,
        Regime::Contact => 1,
        Regime::Rolling => 2,
    }
}

impl Pass {
    /// The number of switches of `kind`.
    pub fn count(&self, kind: EventKind) -> u64 {
        EventKind::ALL
            .iter()
            .position(|k| *k == kind)
            .and_then(|i| self.kinds.get(i))
            .copied()
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_times_hit_both_ends() {
        let t: Vec<f64> = uniform_times(0.0, 0.3, 4).collect();
        assert_eq!(t.len(), 4);
        assert_eq!(t[0], 0.0);
        assert_eq!(t[3], 0.3);
        assert_eq!(t[1], 0.3 * 1.0 / 3.0);
    }
}
