//! Long calls that stay responsive: the work runs with the GIL released under a CLI
//! [`Watch`], and about every [`POLL`] of work the calling thread checks for signals (Ctrl-C →
//! KeyboardInterrupt, Jupyter's interrupt) and reports progress (`progress(done, total)`). The
//! first exception either raises stops the work at its next poll and is raised once the work
//! has ended — never a panic, never work left running.
//!
//! [`on_this_thread`]: the work polls the watch itself (one run on the calling thread: no thread
//! started, no cost beyond a clock read per poll). [`beside`]: the work runs on a scoped thread
//! (a sweep's thread pool) while the calling thread keeps watch.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use pyo3::prelude::*;
use pyo3::types::PyAny;
use rotor_rub_cli::error::CliError;
use rotor_rub_cli::watch::{EXIT_INTERRUPTED, Watch};

/// How much work goes between two checks for signals and progress reports.
pub const POLL: Duration = Duration::from_millis(50);

/// What a poll reports as done, from the watch (e.g. forcing periods from the time reached).
pub type Done = Box<dyn Fn(&Watch) -> f64 + Send + Sync>;

/// The progress callback of a call and its total, in the call's unit.
pub struct Progress {
    callback: Option<Py<PyAny>>,
    total: f64,
}

impl Progress {
    /// `callback(done, total)` (None: no report).
    pub fn new(callback: Option<&Bound<'_, PyAny>>, total: f64) -> Self {
        Progress {
            callback: callback
                .filter(|c| !c.is_none())
                .map(|c| c.clone().unbind()),
            total,
        }
    }

    fn report(&self, py: Python<'_>, done: f64) -> PyResult<()> {
        match &self.callback {
            Some(callback) => callback
                .call1(py, (done.clamp(0.0, self.total), self.total))
                .map(drop),
            None => Ok(()),
        }
    }

    /// The final report, once the work is done.
    pub fn finish(&self, py: Python<'_>) -> PyResult<()> {
        self.report(py, self.total)
    }
}

/// One check: signals, then progress.
fn check(py: Python<'_>, progress: &Progress, done: f64) -> PyResult<()> {
    py.check_signals()?;
    progress.report(py, done)
}

/// The error that stopped the work, kept until the work has ended.
type Failure = Arc<Mutex<Option<PyErr>>>;

fn take(failure: &Failure) -> Option<PyErr> {
    failure.lock().ok().and_then(|mut f| f.take())
}

/// The work's error as a Python exception: the check's exception when the watch stopped it.
fn outcome<R>(result: Result<R, CliError>, failure: &Failure) -> PyResult<R> {
    match (result, take(failure)) {
        (_, Some(e)) => Err(e),
        (Err(e), None) if e.code == EXIT_INTERRUPTED => Err(
            pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted"),
        ),
        (Err(e), None) => Err(crate::errors::cli(e)),
        (Ok(r), None) => Ok(r),
    }
}

/// Run `work` on this thread with the GIL released, under a watch whose polls check for
/// signals and report `done(watch)` of `progress` every [`POLL`].
pub fn on_this_thread<R: Send>(
    py: Python<'_>,
    progress: Progress,
    done: Done,
    work: impl FnOnce(Arc<Watch>) -> Result<R, CliError> + Send,
) -> PyResult<R> {
    let failure: Failure = Arc::new(Mutex::new(None));
    let progress = Arc::new(progress);
    let origin = Instant::now();
    let next = AtomicU64::new(POLL.as_nanos() as u64);
    let hook = {
        let (failure, progress) = (Arc::clone(&failure), Arc::clone(&progress));
        move |watch: &Watch| -> bool {
            let now = origin.elapsed().as_nanos() as u64;
            if now < next.load(Ordering::Relaxed) {
                return true;
            }
            next.store(now + POLL.as_nanos() as u64, Ordering::Relaxed);
            let done = done(watch);
            match Python::attach(|py| check(py, &progress, done)) {
                Ok(()) => true,
                Err(e) => {
                    if let Ok(mut slot) = failure.lock() {
                        slot.get_or_insert(e);
                    }
                    false
                }
            }
        }
    };
    let watch = Arc::new(Watch::with_hook(Box::new(hook)));
    let result = py.detach(|| work(watch));
    // A signal that arrived during the last stretch is raised now, before any result is built.
    if let Err(e) = py.check_signals()
        && let Ok(mut slot) = failure.lock()
    {
        slot.get_or_insert(e);
    }
    let r = outcome(result, &failure)?;
    progress.finish(py)?;
    Ok(r)
}

/// Run `work` on a scoped thread with the GIL released while this thread checks for signals
/// and reports `done()` of `progress` every [`POLL`]; on an exception the watch is stopped and
/// the work waited for.
pub fn beside<R: Send>(
    py: Python<'_>,
    progress: Progress,
    done: impl Fn() -> f64 + Sync,
    work: impl FnOnce(Arc<Watch>) -> Result<R, CliError> + Send,
) -> PyResult<R> {
    let failure: Failure = Arc::new(Mutex::new(None));
    let watch = Arc::new(Watch::new());
    let result = py.detach(|| {
        std::thread::scope(|scope| {
            let (sender, receiver) = mpsc::channel::<()>();
            let worker_watch = Arc::clone(&watch);
            let worker = scope.spawn(move || {
                let r = work(worker_watch);
                let _ = sender.send(());
                r
            });
            while let Err(mpsc::RecvTimeoutError::Timeout) = receiver.recv_timeout(POLL) {
                if watch.is_stopped() {
                    continue;
                }
                let done = done();
                if let Err(e) = Python::attach(|py| check(py, &progress, done)) {
                    if let Ok(mut slot) = failure.lock() {
                        slot.get_or_insert(e);
                    }
                    watch.stop();
                }
            }
            worker
                .join()
                .unwrap_or_else(|_| Err(CliError::failure("a worker thread panicked")))
        })
    });
    if let Err(e) = py.check_signals()
        && let Ok(mut slot) = failure.lock()
    {
        slot.get_or_insert(e);
    }
    let r = outcome(result, &failure)?;
    progress.finish(py)?;
    Ok(r)
}

/// Progress in forcing periods of length `period` from the times the runs reach (from `start`):
/// the distance covered forward, so a run that starts again from an earlier time (a Lyapunov
/// estimate after its section) keeps counting up.
pub fn periods_from(start: f64, period: f64) -> Done {
    let last = Mutex::new((start, 0.0_f64));
    Box::new(move |watch: &Watch| {
        let reached = watch.reached();
        let Ok(mut last) = last.lock() else {
            return 0.0;
        };
        if reached.is_finite() {
            if reached > last.0 {
                last.1 += reached - last.0;
            }
            last.0 = reached;
        }
        last.1 / period
    })
}
