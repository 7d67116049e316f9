//! Limits checked before a run starts or while it runs: counts held in memory (by what this
//! process may hold: `memory`) and the work of a run (`--max-work`), so that a request that
//! would take days or exhaust memory is refused with a clear message instead of hanging or
//! aborting.

mod memory;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

pub use memory::{MemoryShare, reserve, share as memory_share};

use crate::error::{CliError, Result, num};
use crate::watch::Watch;

/// Switches after which a run's switch rate is extrapolated to its end (the early refusal of a
/// contact-heavy run that would take days): a hundredth of the limit, from 100 to 1e5.
const PILOT_SWITCHES: u64 = 100_000;

fn pilot(limit: u64) -> u64 {
    (limit / 100).clamp(100, PILOT_SWITCHES)
}

/// `--max-work`: an integer >= 1, also in exponent form (`1e12`).
pub fn parse_work(text: &str) -> Result<u64, String> {
    let bad = || format!("'{text}' is not an integer from 1 to 1e18");
    let value: f64 = text.trim().parse().map_err(|_| bad())?;
    work(value).ok_or_else(bad)
}

/// A work limit given as a number: an integer from 1 to 1e18 (what [`parse_work`] checks once
/// the text is a number).
pub fn work(value: f64) -> Option<u64> {
    ((1.0..=1e18).contains(&value) && value.fract() == 0.0).then_some(value as u64)
}

/// The run-length limit shared by the commands that propagate.
#[derive(clap::Args, Debug, Clone)]
pub struct LimitArgs {
    /// Work limit of the command: samples and Poincaré points plus contact switches located. A
    /// run that needs more is refused (up front when its length or sample count says so, else
    /// once its switch rate does); raise it to run such a run anyway. The default, 1e9, is
    /// about an hour of work
    #[arg(long, value_name = "N", default_value = "1e9", value_parser = parse_work)]
    pub max_work: u64,
}

impl LimitArgs {
    /// A fresh budget of `--max-work` units.
    pub fn budget(&self) -> Budget {
        Budget {
            limit: self.max_work,
            used: AtomicU64::new(0),
            name: "--max-work",
            watch: None,
        }
    }
}

/// The work a command may still do, shared by its parallel runs.
#[derive(Debug)]
pub struct Budget {
    limit: u64,
    used: AtomicU64,
    /// How messages name the limit (`--max-work`; the Python keyword `max_work`).
    name: &'static str,
    watch: Option<Arc<Watch>>,
}

/// The refusal of a run over the limit `name` = `limit`; `time` the run's estimated length when
/// it was measured.
fn too_much(what: String, name: &str, limit: u64, time: Option<f64>) -> CliError {
    let time = time.map_or(String::new(), |s| {
        format!(" (about {} of work)", duration(s))
    });
    CliError::input(format!(
        "{what}, more than {name} {}{time}; shorten the run or raise {name} to run it anyway",
        num(limit as f64)
    ))
}

/// A duration for a message, in the largest unit that keeps it >= 1: `40 ms`, `3 s`, `12 min`,
/// `5 h`, `3 days`.
pub fn duration(seconds: f64) -> String {
    let units = [
        (86_400.0, "days"),
        (3_600.0, "h"),
        (60.0, "min"),
        (1.0, "s"),
    ];
    for (size, unit) in units {
        if seconds >= size {
            return format!("{:.0} {unit}", seconds / size);
        }
    }
    format!("{:.0} ms", (seconds * 1e3).max(1.0))
}

impl Budget {
    /// Reserve `count` units before running (samples or points `what` asks for).
    pub fn plan(&self, what: &str, count: u64) -> Result<()> {
        let used = self.add(count);
        if used > self.limit {
            return Err(too_much(
                format!("{what} asks for {count} samples and points"),
                self.name,
                self.limit,
                None,
            ));
        }
        Ok(())
    }

    fn add(&self, count: u64) -> u64 {
        let before = self.used.fetch_add(count, Ordering::Relaxed);
        before.saturating_add(count)
    }

    /// A tracker of one run from `start` to `end` charging this budget.
    pub fn run(&self, start: f64, end: f64) -> Tracker<'_> {
        Tracker {
            budget: self,
            start,
            end,
            switches: 0,
            started: Instant::now(),
        }
    }

    /// The same budget with its messages naming the limit `name` (a caller's own name for
    /// `--max-work`).
    pub fn named(self, name: &'static str) -> Self {
        Budget { name, ..self }
    }

    /// The same budget with `watch` polled by every run charged to it ([`crate::watch`]).
    pub fn watched(self, watch: Arc<Watch>) -> Self {
        Budget {
            watch: Some(watch),
            ..self
        }
    }

    /// The watch on this budget's runs, if any.
    pub fn watch(&self) -> Option<&Watch> {
        self.watch.as_deref()
    }

    /// A run got to `time`: polls the watch (an error once it is stopped); nothing without one.
    pub fn check(&self, time: f64) -> Result<()> {
        match &self.watch {
            Some(watch) => watch.poll(time),
            None => Ok(()),
        }
    }
}

/// Charges the switches of one run to a [`Budget`] and refuses the run once it exceeds it, or once
/// its switch rate extrapolated to the end does.
#[derive(Debug)]
pub struct Tracker<'a> {
    budget: &'a Budget,
    start: f64,
    end: f64,
    switches: u64,
    started: Instant,
}

impl Tracker<'_> {
    /// The budget this run charges.
    pub fn budget(&self) -> &Budget {
        self.budget
    }

    /// Count a switch at `time`.
    pub fn switch(&mut self, time: f64) -> Result<()> {
        self.budget.check(time)?;
        self.switches += 1;
        let used = self.budget.add(1);
        let limit = self.budget.limit;
        let elapsed = time - self.start;
        let seconds = self.started.elapsed().as_secs_f64();
        if used > limit {
            // The whole run at the pace so far (in simulated time).
            let estimate = (elapsed > 0.0).then(|| seconds / elapsed * (self.end - self.start));
            return Err(too_much(
                format!(
                    "the run located {} contact switches by τ = {} of {}",
                    num(self.switches as f64),
                    num(time),
                    num(self.end)
                ),
                self.budget.name,
                limit,
                estimate,
            ));
        }
        if self.switches == pilot(limit) && elapsed > 0.0 {
            let projected = self.switches as f64 / elapsed * (self.end - self.start);
            if projected > limit as f64 {
                let estimate = seconds / self.switches as f64 * projected;
                return Err(too_much(
                    format!(
                        "at the rate of its first {} contact switches (up to τ = {}), the run \
                         to τ = {} would locate about {} switches",
                        num(self.switches as f64),
                        num(time),
                        num(self.end),
                        num(projected.round())
                    ),
                    self.budget.name,
                    limit,
                    Some(estimate),
                ));
            }
        }
        Ok(())
    }
}

/// Bytes a command may fill with the data it keeps ([`memory::share`]: half of the least of the
/// physical memory, the cgroup's limit and what `ulimit -v`/`-d` leave), read once per process.
pub fn memory_limit() -> u64 {
    memory::share().bytes
}

/// Check that `count` items of `bytes_each` bytes, kept in memory for `what`, fit this process's
/// share: the count as a `usize`, or an input error naming the value, the limit and what sets
/// it.
pub fn fits_memory(what: &str, count: u64, bytes_each: usize) -> Result<usize> {
    let share = memory::share();
    let bytes = count.checked_mul(bytes_each as u64);
    match (bytes, usize::try_from(count)) {
        (Some(bytes), Ok(n)) if bytes <= share.bytes => Ok(n),
        _ => Err(CliError::input(format!(
            "{what} = {count} would keep {} bytes in memory, more than the {} bytes ({}) this \
             command may use; ask for fewer",
            num(count as f64 * bytes_each as f64),
            num(share.bytes as f64),
            share.reason
        ))),
    }
}

/// `a + b` for counts from the command line, an input error naming both when it overflows.
pub fn add_counts(a: (&str, u64), b: (&str, u64)) -> Result<u64> {
    a.1.checked_add(b.1).ok_or_else(|| {
        CliError::input(format!(
            "{} {} plus {} {} is more than {}: use smaller counts",
            a.0,
            a.1,
            b.0,
            b.1,
            u64::MAX
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_parser() {
        assert_eq!(parse_work("1e12"), Ok(1_000_000_000_000));
        assert_eq!(parse_work("7"), Ok(7));
        assert!(parse_work("0").is_err());
        assert!(parse_work("1.5").is_err());
        assert!(parse_work("1e30").is_err());
        assert!(parse_work("nan").is_err());
    }

    #[test]
    fn memory_check_refuses_overflow_and_huge_counts() {
        assert!(fits_memory("n", u64::MAX, 16).is_err());
        assert!(fits_memory("n", 1_000_000_000_000, 16).is_err());
        assert_eq!(fits_memory("n", 1000, 16).ok(), Some(1000));
    }

    #[test]
    fn budget_refuses_past_the_limit_and_projects_the_rate() {
        let limits = LimitArgs { max_work: 10 };
        let budget = limits.budget();
        assert!(budget.plan("a", 8).is_ok());
        let mut run = budget.run(0.0, 1.0);
        assert!(run.switch(0.1).is_ok());
        assert!(run.switch(0.2).is_ok());
        assert_eq!(run.switch(0.3).map_err(|e| e.code).err(), Some(2));

        let budget = LimitArgs {
            max_work: 1_000_000,
        }
        .budget();
        let mut run = budget.run(0.0, 1e9);
        let refused = (1..=pilot(1_000_000)).try_for_each(|k| run.switch(k as f64));
        assert!(refused.is_err_and(|e| e.message.contains("would locate about")));
    }
}
