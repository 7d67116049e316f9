//! A caller's watch over a command's runs, for embedders that must stay responsive while a long
//! run goes on (the Python package: Ctrl-C and progress bars). A [`Watch`] attached to a
//! [`crate::limits::Budget`] is polled by every run charged to that budget: at each switch, after
//! each stretch of propagation ([`Stretches`]: ~1–20 ms of work) and between the intervals of a
//! Lyapunov estimate. Once stopped, every run ends at its next poll with
//! [`CliError::interrupted`].
//!
//! The stretches stop a propagation at extra times, which changes no trajectory (sampling never
//! does: the runtime's invariant), so a watched run gives the same bits as an unwatched one.
//! Without a watch (the command line) nothing of this runs.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use crate::error::{CliError, Result};

/// Exit code of an interrupted command (128 + SIGINT).
pub const EXIT_INTERRUPTED: u8 = 130;

impl CliError {
    /// A run stopped by its [`Watch`].
    pub fn interrupted() -> Self {
        Self {
            code: EXIT_INTERRUPTED,
            message: "interrupted".into(),
        }
    }
}

/// What a watch calls at every poll (from the thread that polls): `false` stops the runs.
pub type Hook = Box<dyn Fn(&Watch) -> bool + Send + Sync>;

/// A stop flag and the latest time a run reported, shared by the runs of one command (see the
/// module documentation).
pub struct Watch {
    stop: AtomicBool,
    reached: AtomicU64,
    hook: Option<Hook>,
}

impl std::fmt::Debug for Watch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Watch")
            .field("stopped", &self.is_stopped())
            .field("reached", &self.reached())
            .finish_non_exhaustive()
    }
}

impl Default for Watch {
    fn default() -> Self {
        Self::new()
    }
}

impl Watch {
    /// A watch that only stops when [`Watch::stop`] is called (from another thread).
    pub fn new() -> Self {
        Watch {
            stop: AtomicBool::new(false),
            reached: AtomicU64::new(f64::NAN.to_bits()),
            hook: None,
        }
    }

    /// A watch that also calls `hook` at every poll (it rate-limits itself): a caller running
    /// the work on its own thread checks for signals and reports progress there.
    pub fn with_hook(hook: Hook) -> Self {
        Watch {
            hook: Some(hook),
            ..Watch::new()
        }
    }

    /// Stop every run at its next poll.
    pub fn stop(&self) {
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Whether [`Watch::stop`] was called (or the hook said stop).
    pub fn is_stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// The time the latest poll reported (NaN before the first).
    pub fn reached(&self) -> f64 {
        f64::from_bits(self.reached.load(Ordering::Relaxed))
    }

    /// A run got to `time`: record it, call the hook, and fail once stopped.
    pub fn poll(&self, time: f64) -> Result<()> {
        self.reached.store(time.to_bits(), Ordering::Relaxed);
        if let Some(hook) = &self.hook
            && !hook(self)
        {
            self.stop();
        }
        if self.is_stopped() {
            return Err(CliError::interrupted());
        }
        Ok(())
    }
}

/// The stop times of one watched advance to `end`: stretches whose length adapts so that each
/// takes about [`Stretches::SHORT`] to [`Stretches::LONG`] of wall time. The clock is read only
/// once a stretch stops short of `end` (an advance within one stretch costs nothing more).
pub struct Stretches {
    end: f64,
    length: f64,
    started: Option<Instant>,
}

impl Stretches {
    /// The first stretch's length (time units; about a forcing period).
    pub const FIRST: f64 = 8.0;
    /// A stretch done faster than this doubles the next.
    pub const SHORT: Duration = Duration::from_millis(1);
    /// A stretch that took longer than this halves the next.
    pub const LONG: Duration = Duration::from_millis(20);

    /// Stretches up to `end`.
    pub fn new(end: f64) -> Self {
        Stretches {
            end,
            length: Self::FIRST,
            started: None,
        }
    }

    /// Where the stretch from `now` stops: `end` when it is within reach, never past it.
    pub fn stop_after(&mut self, now: f64) -> f64 {
        let stop = now + self.length;
        if stop < self.end {
            self.started.get_or_insert_with(Instant::now);
            stop
        } else {
            self.end
        }
    }

    /// A stretch ended short of the end: adapt the next one's length to the wall time this one
    /// took.
    pub fn ended(&mut self) {
        let now = Instant::now();
        let took = self.started.map_or(Duration::ZERO, |s| now - s);
        if took < Self::SHORT {
            self.length *= 2.0;
        } else if took > Self::LONG {
            self.length = (self.length * 0.5).max(f64::MIN_POSITIVE);
        }
        self.started = Some(now);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use std::sync::atomic::AtomicU32;

    #[test]
    fn a_stopped_watch_fails_its_polls() {
        let watch = Watch::new();
        assert!(watch.poll(1.0).is_ok());
        assert_eq!(watch.reached(), 1.0);
        watch.stop();
        let e = watch.poll(2.0).unwrap_err();
        assert_eq!(e.code, EXIT_INTERRUPTED);
    }

    #[test]
    fn the_hook_runs_at_every_poll_and_can_stop() {
        let calls = Arc::new(AtomicU32::new(0));
        let seen = Arc::clone(&calls);
        let watch = Watch::with_hook(Box::new(move |_| seen.fetch_add(1, Ordering::Relaxed) < 2));
        assert!(watch.poll(0.0).is_ok() && watch.poll(0.5).is_ok());
        assert!(watch.poll(1.0).is_err());
        assert_eq!(calls.load(Ordering::Relaxed), 3);
    }

    #[test]
    fn stretches_end_at_the_end_and_grow_when_quick() {
        let mut s = Stretches::new(100.0);
        assert_eq!(s.stop_after(0.0), Stretches::FIRST);
        s.ended();
        assert_eq!(s.stop_after(0.0), 2.0 * Stretches::FIRST);
        assert_eq!(s.stop_after(99.0), 100.0);
    }
}
