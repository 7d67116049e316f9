//! Issue 32 item 12: SIGTERM exits 143, SIGINT 130 and SIGHUP 129 (128 + the signal, what a
//! shell reports for a process killed by it), each removing the unfinished output files; a
//! signal the parent set to be ignored (`nohup`, a background job's SIGINT) stays ignored.

use std::fs;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::listing;

/// Temporary files left in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    listing(dir)
        .into_iter()
        .filter(|n| n.starts_with(".rotor-rub-"))
        .collect()
}

/// A sweep long enough to be interrupted while it writes, started through `sh -c` with
/// `prelude` (e.g. a `trap` that ignores a signal) before the `exec`.
fn long_sweep(dir: &Path, prelude: &str) -> Child {
    let child = Command::new("sh")
        .current_dir(dir)
        .arg("-c")
        .arg(format!(r#"{prelude} exec "$0" "$@""#))
        .arg(assert_cmd::cargo::cargo_bin!("rotor-rub"))
        .args([
            "sweep",
            "--method",
            "dop853",
            "--steps",
            "64",
            "--transient",
            "100000",
            "--keep",
            "2",
            "--out",
            "sw.csv",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let waited = Instant::now();
    while temporaries(dir).is_empty() && waited.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        !temporaries(dir).is_empty(),
        "the sweep never started writing"
    );
    child
}

/// Whether this process ignores signal `number` (and so its children inherit it ignored): bit
/// `number − 1` of the `SigIgn` mask in /proc/self/status.
fn inherited_ignored(number: u32) -> bool {
    let status = fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("SigIgn:"))
        .and_then(|mask| u64::from_str_radix(mask.trim(), 16).ok())
        .is_some_and(|mask| mask & (1 << (number - 1)) != 0)
}

fn send(child: &Child, signal: &str) {
    let pid = child.id().to_string();
    assert!(
        Command::new("kill")
            .args([&format!("-{signal}"), &pid])
            .status()
            .unwrap()
            .success()
    );
}

#[test]
fn each_signal_exits_with_its_own_status_and_removes_temporaries() {
    for (signal, number, code) in [("TERM", 15, 143), ("INT", 2, 130), ("HUP", 1, 129)] {
        if inherited_ignored(number) {
            // Started under `nohup` or as a background job: the child inherits the signal
            // ignored and keeps it so (`ignored_signals_stay_ignored`); nothing to test here.
            continue;
        }
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        fs::write(d.join("sw.csv"), "previous\n").unwrap();
        let mut child = long_sweep(d, "");
        send(&child, signal);
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(code), "SIG{signal}: {status:?}");
        assert_eq!(temporaries(d), Vec::<String>::new(), "SIG{signal}");
        assert_eq!(
            fs::read_to_string(d.join("sw.csv")).unwrap(),
            "previous\n",
            "SIG{signal}: no half result"
        );
    }
}

#[test]
fn ignored_signals_stay_ignored() {
    // A background job (SIGINT ignored) or `nohup` (SIGHUP ignored): those signals do not stop
    // the run; SIGTERM still ends it cleanly.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut child = long_sweep(d, "trap '' INT HUP;");
    send(&child, "INT");
    send(&child, "HUP");
    std::thread::sleep(Duration::from_millis(300));
    assert!(
        child.try_wait().unwrap().is_none(),
        "an ignored signal ended the run"
    );
    send(&child, "TERM");
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(143), "{status:?}");
    assert_eq!(temporaries(d), Vec::<String>::new());
    assert!(!d.join("sw.csv").exists());
}
