//! The temporary files of unfinished outputs, removed on SIGINT, SIGTERM or SIGHUP.
//!
//! Every temporary file is created, renamed into place and removed while holding one lock, and
//! the signal handler takes the same lock before it removes what is listed and exits: a file is
//! either listed (and removed by the handler) or not yet created or already in place.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// Exit status after an interrupt: 128 + SIGINT, as a shell reports a process killed by it.
pub const EXIT_INTERRUPTED: i32 = 130;

static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The list of live temporary files, locked (a panic elsewhere does not disable cleaning).
pub fn lock() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Stop listing `path` (it was renamed into place or removed); call with the lock held.
pub fn forget(live: &mut Vec<PathBuf>, path: &Path) {
    live.retain(|p| p != path);
}

/// Install the handler: on an interrupt, remove every live temporary file and exit with
/// [`EXIT_INTERRUPTED`]. Output files already in place are complete; none is half-written.
pub fn install_handler() {
    // Failing to install (a handler already set) leaves the default behaviour; not fatal.
    let _ = ctrlc::set_handler(|| {
        let live = lock();
        for path in live.iter() {
            let _ = std::fs::remove_file(path);
        }
        crate::stdio::note("interrupted: unfinished output files removed");
        // Exit with the lock held, so no other thread creates or renames a file meanwhile.
        std::process::exit(EXIT_INTERRUPTED);
    });
}
