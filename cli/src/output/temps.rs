//! The temporary files of unfinished outputs, removed on SIGINT, SIGTERM or SIGHUP.
//!
//! Every temporary file is created, renamed into place and removed while holding one lock, and
//! the signal handler takes the same lock before it removes what is listed and exits: a file is
//! either listed (and removed by the handler) or not yet created or already in place.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// The signals that stop a command, with their names: each exits with 128 + its number (130,
/// 143, 129), what a shell reports for a process killed by it.
const STOPPING: [(i32, &str); 3] = [(SIGINT, "SIGINT"), (SIGTERM, "SIGTERM"), (SIGHUP, "SIGHUP")];

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

/// Install the handler: on SIGINT, SIGTERM or SIGHUP, remove every live temporary file and exit
/// with 128 + the signal's number. Output files already in place are complete; none is
/// half-written. A signal the parent left ignored (`nohup`'s SIGHUP, a background job's SIGINT)
/// stays ignored.
pub fn install_handler() {
    let ignored = ignored_signals();
    let handled: Vec<i32> = STOPPING
        .iter()
        .map(|&(signal, _)| signal)
        .filter(|signal| !ignored.contains(signal))
        .collect();
    // Failing to install leaves the default behaviour (the signal ends the process); not fatal.
    let Ok(mut signals) = Signals::new(&handled) else {
        return;
    };
    let _ = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                let live = lock();
                for path in live.iter() {
                    let _ = std::fs::remove_file(path);
                }
                let name = STOPPING
                    .iter()
                    .find(|(s, _)| *s == signal)
                    .map_or("a signal", |(_, name)| name);
                crate::stdio::note(&format!(
                    "stopped by {name}: unfinished output files removed"
                ));
                // Exit with the lock held, so no other thread creates or renames a file meanwhile.
                std::process::exit(128 + signal);
            }
        });
}

/// The signals this process ignores (inherited from its parent), from the `SigIgn` mask of
/// /proc/self/status; none where that is unknown.
fn ignored_signals() -> Vec<i32> {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| parse_sig_ign(&status))
        .unwrap_or_default()
}

/// The signal numbers set in the `SigIgn:` line (a hexadecimal mask, bit n − 1 for signal n).
fn parse_sig_ign(status: &str) -> Option<Vec<i32>> {
    let mask = status
        .lines()
        .find_map(|line| line.strip_prefix("SigIgn:"))?
        .trim();
    let mask = u64::from_str_radix(mask, 16).ok()?;
    Some((1..=64).filter(|n| (mask >> (n - 1)) & 1 == 1).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ignored_mask_is_read_bit_by_bit() {
        let status = "Name:\trotor-rub\nSigBlk:\t0000000000000000\nSigIgn:\t0000000000000003\n";
        assert_eq!(parse_sig_ign(status), Some(vec![1, 2]));
        assert_eq!(parse_sig_ign("SigIgn:\t0000000000004000\n"), Some(vec![15]));
        assert_eq!(parse_sig_ign("SigCgt:\t0\n"), None);
    }
}
