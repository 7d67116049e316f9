//! Issue 32 item 6: under an address-space limit (`ulimit -v`, as on SLURM and Kubernetes
//! workers) a request for more memory than the process may have is refused with the usual
//! message (exit 2), not aborted by a failed allocation; a request that needs no memory runs.

use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common::listing;

/// The address space the limited runs get, in KiB: far more than a short run needs (about
/// 100 MiB), far less than the machine's memory.
const LIMIT_KIB: u64 = 500_000;

fn limited(dir: &Path, args: &[&str]) -> Command {
    let mut command = Command::new("sh");
    command
        .current_dir(dir)
        .arg("-c")
        .arg(format!(r#"ulimit -v {LIMIT_KIB} && exec "$0" "$@""#))
        .arg(assert_cmd::cargo::cargo_bin!("rotor-rub"))
        .args(args)
        .env("RUST_BACKTRACE", "1");
    command
}

/// The output of `args` run under the limit, killed (and failing the test) past `deadline`.
fn run_limited(dir: &Path, args: &[&str], deadline: Duration) -> Output {
    let mut child = limited(dir, args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?} still running after {deadline:?} under ulimit -v");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[test]
fn requests_beyond_the_address_space_limit_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &[
            "spectrum",
            "--transient",
            "0",
            "--periods",
            "1000000",
            "--samples-per-period",
            "40",
        ][..],
        &["poincare", "--transient", "0", "--keep", "30000000"],
        &[
            "sweep",
            "--steps",
            "300",
            "--keep",
            "100000",
            "--transient",
            "0",
        ],
        &["compare", "--periods", "200000"],
        &[
            "fig2",
            "--plot-from",
            "0",
            "--plot-to",
            "200000",
            "--speeds",
            "1",
        ],
        &["friction", "--plot-to", "500000"],
    ] {
        let out = run_limited(dir.path(), args, Duration::from_secs(20));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.lines().count() == 1,
            "{args:?}: {err}"
        );
        assert!(
            err.contains("bytes in memory") && err.contains("ulimit -v"),
            "{args:?}: {err}"
        );
        assert!(listing(dir.path()).is_empty(), "{args:?}");
    }
}

/// Wait until `child` has run for `time` (failing if it ended before), then end it with SIGTERM.
fn still_running_then_terminate(child: &mut Child, time: Duration) -> Option<i32> {
    let started = Instant::now();
    while started.elapsed() < time {
        if let Some(status) = child.try_wait().unwrap() {
            let mut err = String::new();
            if let Some(mut e) = child.stderr.take() {
                use std::io::Read;
                let _ = e.read_to_string(&mut err);
            }
            panic!("ended early with {status:?}: {err}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let pid = child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-TERM", &pid])
            .status()
            .unwrap()
            .success()
    );
    child.wait().unwrap().code()
}

#[test]
fn samples_streamed_to_a_file_need_no_memory() {
    // `simulate --sample-count 1e8` kept every sample time in memory (2.4 GB) and aborted under
    // `ulimit -v`; the samples go straight to the file, so the run proceeds.
    let dir = tempfile::tempdir().unwrap();
    let mut child = limited(
        dir.path(),
        &[
            "simulate",
            "--samples",
            "s.csv",
            "--sample-count",
            "1e8",
            "--set",
            "friction_coefficient=0.1",
        ],
    )
    .stdout(Stdio::null())
    .stderr(Stdio::piped())
    .spawn()
    .unwrap();
    let code = still_running_then_terminate(&mut child, Duration::from_millis(1500));
    assert_eq!(code, Some(143), "SIGTERM: 128 + 15");
    assert!(listing(dir.path()).is_empty(), "{:?}", listing(dir.path()));
}
