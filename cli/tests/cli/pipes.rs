//! Issue 34: a closed pipe on stdout or stderr ends every command quietly (exit 141, the status
//! of a Unix tool killed by SIGPIPE; 0 when everything fit in the pipe before it closed), never
//! with a panic. `rotor-rub presets | head -c 10` panicked in 20 of 30 runs.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};

/// Short runs of every subcommand (and of the default job), each cheap enough to repeat.
const COMMANDS: &[&[&str]] = &[
    &[
        "--speeds",
        "1",
        "--plot-from",
        "0",
        "--plot-to",
        "1",
        "--section",
        "1",
        "--lyapunov",
        "1",
        "--match-periods",
        "1",
    ],
    &[
        "fig2",
        "--speeds",
        "1",
        "--plot-from",
        "0",
        "--plot-to",
        "1",
        "--section",
        "1",
        "--lyapunov",
        "1",
        "--match-periods",
        "1",
    ],
    &["simulate", "--periods", "1", "--events", "e.csv"],
    &["compare", "--periods", "1"],
    &[
        "sweep",
        "--steps",
        "2",
        "--transient",
        "0",
        "--keep",
        "1",
        "--no-plot",
    ],
    &["merge", "m.csv", "shard.csv", "--no-plot"],
    &["poincare", "--transient", "0", "--keep", "2"],
    &[
        "spectrum",
        "--transient",
        "0",
        "--periods",
        "1",
        "--samples-per-period",
        "8",
    ],
    &["friction", "--plot-to", "1"],
    &[
        "runup",
        "--from",
        "1",
        "--to",
        "1.2",
        "--rate",
        "0.01",
        "--settle",
        "0",
        "--one-way",
        "--no-plot",
    ],
    &["orbit", "--set", "speed_ratio=3", "--start", "free"],
    &[
        "continue",
        "--from",
        "3",
        "--to",
        "2.9",
        "--start",
        "free",
        "--max-period",
        "1",
        "--no-plot",
    ],
    &["presets"],
    &["params"],
];

const SUBCOMMANDS: [&str; 13] = [
    "fig2", "simulate", "compare", "sweep", "merge", "poincare", "spectrum", "friction", "runup",
    "orbit", "continue", "presets", "params",
];

/// What the command printed on stderr and its exit status, with stdout a pipe whose reader
/// reads `keep` bytes (none: the reader is gone before the command starts) and then closes it.
fn closed_stdout(dir: &Path, args: &[&str], keep: Option<usize>) -> (Option<i32>, String) {
    let (mut reader, writer) = std::io::pipe().unwrap();
    let mut command = Command::new(assert_cmd::cargo::cargo_bin!("rotor-rub"));
    command
        .current_dir(dir)
        .args(args)
        .env("RUST_BACKTRACE", "1")
        .stdin(Stdio::null())
        .stdout(writer)
        .stderr(Stdio::piped());
    let child = match keep {
        None => {
            drop(reader);
            command.spawn().unwrap()
        }
        Some(n) => {
            let child = command.spawn().unwrap();
            // The parent's copy of the write end went with `command`'s drop below.
            drop(command);
            let mut first = vec![0; n];
            let _ = reader.read_exact(&mut first);
            drop(reader);
            child
        }
    };
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn no_panic(args: &[&str], code: Option<i32>, stderr: &str) {
    for sign in ["panicked", "backtrace", "RUST_BACKTRACE", "Broken pipe"] {
        assert!(!stderr.contains(sign), "{args:?}: {sign} in: {stderr}");
    }
    assert!(
        matches!(code, Some(0 | 141)),
        "{args:?}: exit {code:?} (want 0, or 141 after a closed pipe): {stderr}"
    );
}

/// A shard file for `merge`.
fn prepare(dir: &Path) {
    let status = Command::new(assert_cmd::cargo::cargo_bin!("rotor-rub"))
        .current_dir(dir)
        .args(SHARD)
        .stdout(Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
}

const SHARD: [&str; 12] = [
    "sweep",
    "--steps",
    "2",
    "--transient",
    "0",
    "--keep",
    "1",
    "--shard",
    "0/1",
    "--out",
    "shard.csv",
    "--no-plot",
];

#[test]
fn every_command_ends_quietly_on_a_closed_stdout() {
    let dir = tempfile::tempdir().unwrap();
    prepare(dir.path());
    for args in COMMANDS {
        // The reader gone before the first byte: every write fails, deterministically.
        let (code, stderr) = closed_stdout(dir.path(), args, None);
        no_panic(args, code, &stderr);
        assert_eq!(code, Some(141), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
        // The reader leaves after a few bytes, racing the writer (the issue's `head -c 10`).
        let cheap = matches!(args[0], "presets" | "params");
        for _ in 0..if cheap { 30 } else { 5 } {
            let (code, stderr) = closed_stdout(dir.path(), args, Some(10));
            no_panic(args, code, &stderr);
        }
    }
}

#[test]
fn help_and_version_end_quietly_on_a_closed_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let mut cases: Vec<Vec<&str>> =
        vec![vec!["--help"], vec!["-h"], vec!["--version"], vec!["help"]];
    for sub in SUBCOMMANDS {
        cases.extend([vec![sub, "--help"], vec![sub, "-h"], vec!["help", sub]]);
    }
    for args in &cases {
        let (code, stderr) = closed_stdout(dir.path(), args, None);
        no_panic(args, code, &stderr);
        assert_eq!(code, Some(141), "{args:?}: {stderr}");
        for _ in 0..10 {
            let (code, stderr) = closed_stdout(dir.path(), args, Some(10));
            no_panic(args, code, &stderr);
        }
    }
}

#[test]
fn a_closed_stderr_keeps_the_exit_code() {
    // Usage errors, invalid input and warnings go to stderr; with stderr closed the command still
    // exits with its own code and does not panic.
    let dir = tempfile::tempdir().unwrap();
    for (args, expected) in [
        (&["simulate", "--bogus"][..], 2),
        (&["simulate", "--tol", "5"], 2),
        (&["sweep", "--steps", "0"], 2),
        (&["merge"], 2),
        (&["simulate", "--periods", "1"], 0),
    ] {
        for _ in 0..5 {
            let (reader, writer) = std::io::pipe().unwrap();
            drop(reader);
            let status = Command::new(assert_cmd::cargo::cargo_bin!("rotor-rub"))
                .current_dir(dir.path())
                .args(args)
                .stdout(Stdio::null())
                .stderr(writer)
                .status()
                .unwrap();
            assert_eq!(status.code(), Some(expected), "{args:?}: {status:?}");
        }
    }
}
