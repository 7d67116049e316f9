//! Faults and abuse (issue 13): huge counts, stdout failures, special output files, name
//! collisions, broken shard sets, interrupts and runs too long to finish. Each test names the
//! example it keeps fixed.

use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{bin, listing};

/// Run in `dir`; return (exit code, stdout, stderr).
fn run_in(dir: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let out = bin().current_dir(dir).args(args).output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The longest run of digits in `text`.
fn longest_digits(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

/// Refused as invalid input (exit 2) with one clear line naming `names`, no panic, nothing
/// written.
fn refused(args: &[&str], names: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let (code, _, err) = run_in(dir.path(), args);
    assert_eq!(code, Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(
        err.starts_with("error: ") && err.lines().count() == 1,
        "{args:?}: {err}"
    );
    for name in names {
        assert!(err.contains(name), "{args:?}: '{name}' not in {err}");
    }
    assert!(
        longest_digits(&err) <= 20,
        "{args:?}: a long number in {err}"
    );
    assert!(
        listing(dir.path()).is_empty(),
        "{args:?} wrote {:?}",
        listing(dir.path())
    );
}

const MAX: &str = "18446744073709551615";

#[test]
fn huge_counts_are_refused_before_allocating() {
    refused(
        &["sweep", "--steps", MAX, "--no-plot"],
        &["--steps", "memory"],
    );
    refused(
        &["sweep", "--transient", MAX, "--keep", "2"],
        &["--transient", "--keep"],
    );
    refused(
        &["sweep", "--steps", "1000000", "--keep", "1000000"],
        &["--keep"],
    );
    refused(&["spectrum", "--periods", MAX], &["--periods"]);
    refused(
        &[
            "spectrum",
            "--periods",
            "1000000000",
            "--samples-per-period",
            "1000",
        ],
        &["--periods"],
    );
    refused(
        &["poincare", "--transient", MAX, "--keep", "2"],
        &["--transient", "--keep"],
    );
    refused(&["poincare", "--keep", "1000000000000"], &["--keep"]);
    refused(
        &[
            "simulate",
            "--samples",
            "s.csv",
            "--sample-count",
            "1000000000000",
        ],
        &["--sample-count", "--max-work"],
    );
    refused(&["compare", "--periods", "1e12"], &["orbit samples"]);
    refused(&["fig2", "--plot-to", MAX], &["orbit samples"]);
    refused(
        &["fig2", "--plot-from", "1", "--section", MAX],
        &["--section"],
    );
    refused(&["fig2", "--lyapunov", MAX], &["--lyapunov"]);
}

#[test]
fn numbers_in_messages_are_short() {
    // `--step 1e300` printed a 301-digit number.
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["simulate", "--contact-scheme", "exprb2", "--step", "1e300"][..],
        &["simulate", "--t-end", "1e300", "--max-work", "1000"],
    ] {
        let (code, _, err) = run_in(dir.path(), args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(longest_digits(&err) <= 20, "{args:?}: {err}");
    }
}

/// A run too long to finish is refused with the option to raise the limit; a long but cheap run
/// (contact-free after the transient) still runs.
#[test]
fn run_length_cap() {
    // 1e15 periods with dense samples: refused up front.
    refused(
        &[
            "simulate",
            "--periods",
            "1e15",
            "--samples",
            "s.csv",
            "--sample-count",
            "1000000000000",
        ],
        &["--max-work"],
    );
    // Contact-heavy, 1e12 periods: refused once its switch rate is known (a small --max-work
    // keeps the test short; the default refuses after 1e5 switches in the same way).
    let dir = tempfile::tempdir().unwrap();
    let (code, _, err) = run_in(
        dir.path(),
        &[
            "simulate",
            "--periods",
            "1e12",
            "--max-work",
            "20000",
            "--events",
            "e.csv",
        ],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("would locate about") && err.contains("--max-work"),
        "{err}"
    );
    assert!(listing(dir.path()).is_empty());
    // Contact-free: 1e17 periods run as before.
    let (code, out, err) = run_in(
        dir.path(),
        &[
            "simulate",
            "--periods",
            "1e17",
            "--set",
            "eccentricity_ratio=0.1",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("1e17 forcing periods"), "{out}");
    // Raising the limit lets a refused run go on.
    let (code, _, err) = run_in(
        dir.path(),
        &["simulate", "--periods", "10", "--max-work", "5"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("contact switches by τ"), "{err}");
    let (code, _, err) = run_in(
        dir.path(),
        &["simulate", "--periods", "10", "--max-work", "1e6"],
    );
    assert_eq!(code, Some(0), "{err}");
}

#[test]
fn full_stdout_fails_cleanly_after_complete_files() {
    // `simulate > /dev/full` panicked after replacing the output files.
    let dir = tempfile::tempdir().unwrap();
    let full = fs::File::options().write(true).open("/dev/full").unwrap();
    let out = Command::new(assert_cmd::cargo::cargo_bin!("rotor-rub"))
        .current_dir(dir.path())
        .args(["simulate", "--periods", "2", "--events", "e.csv"])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("standard output") && !err.contains("panicked"),
        "{err}"
    );
    assert_eq!(
        listing(dir.path()),
        ["e.csv"],
        "complete output, no temporary file"
    );
    let text = fs::read_to_string(dir.path().join("e.csv")).unwrap();
    assert!(text.starts_with("tau,kind,x,y,vx,vy\n") && text.lines().count() > 1);
}

#[test]
fn closed_pipe_ends_quietly() {
    // `simulate | head -1` panicked on the broken pipe.
    let dir = tempfile::tempdir().unwrap();
    // The reader is gone before the child starts (dropping it after the spawn would race with
    // the child's first write, which the pipe's buffer would accept).
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(assert_cmd::cargo::cargo_bin!("rotor-rub"))
        .current_dir(dir.path())
        .args(["simulate", "--periods", "2", "--events", "e.csv"])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(141),
        "128 + SIGPIPE, as a Unix tool"
    );
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(listing(dir.path()), ["e.csv"]);
}

#[test]
fn special_files_are_written_through_and_symlinks_kept() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A symlink stays a symlink; its target gets the output.
    fs::write(d.join("old.csv"), "old\n").unwrap();
    std::os::unix::fs::symlink("old.csv", d.join("link.csv")).unwrap();
    // A dangling symlink: its target is created.
    std::os::unix::fs::symlink("sub/new.csv", d.join("dangling.csv")).unwrap();
    fs::create_dir(d.join("sub")).unwrap();
    let (code, _, err) = run_in(
        d,
        &[
            "simulate",
            "--periods",
            "1",
            "--events",
            "link.csv",
            "--samples",
            "dangling.csv",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(
        fs::symlink_metadata(d.join("link.csv"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        fs::read_to_string(d.join("old.csv"))
            .unwrap()
            .starts_with("tau,kind")
    );
    assert!(
        fs::symlink_metadata(d.join("dangling.csv"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        fs::read_to_string(d.join("sub/new.csv"))
            .unwrap()
            .starts_with("tau,x")
    );

    // `--events /dev/null` works and leaves /dev/null a device.
    let (code, _, err) = run_in(d, &["simulate", "--periods", "1", "--events", "/dev/null"]);
    assert_eq!(code, Some(0), "{err}");
    use std::os::unix::fs::FileTypeExt;
    assert!(
        fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );

    // A FIFO gets the whole output and stays a FIFO.
    let fifo = d.join("pipe.csv");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || fs::read_to_string(fifo).unwrap())
    };
    let (code, _, err) = run_in(d, &["simulate", "--periods", "1", "--events", "pipe.csv"]);
    assert_eq!(code, Some(0), "{err}");
    let text = reader.join().unwrap();
    assert!(
        text.starts_with("tau,kind,x,y,vx,vy\n") && text.lines().count() > 1,
        "{text}"
    );
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());

    // A directory is refused.
    let (code, _, err) = run_in(d, &["simulate", "--events", "sub"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("directory"), "{err}");
}

#[test]
fn output_name_collisions_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("a.csv"), "keep\n").unwrap();
    std::os::unix::fs::symlink("a.csv", d.join("l.csv")).unwrap();
    fs::hard_link(d.join("a.csv"), d.join("h.csv")).unwrap();
    fs::create_dir(d.join("sub")).unwrap();
    for (events, samples) in [
        ("a.csv", "a.csv"),
        ("a.csv", "./a.csv"),
        ("a.csv", "sub/../a.csv"),
        ("a.csv", "l.csv"),
        ("a.csv", "h.csv"),
        ("new.csv", "./new.csv"),
        ("sub/x.csv", "sub/../sub/x.csv"),
    ] {
        let (code, _, err) = run_in(d, &["simulate", "--events", events, "--samples", samples]);
        assert_eq!(code, Some(2), "{events} {samples}: {err}");
        assert!(err.contains("same file"), "{err}");
    }
    assert_eq!(fs::read_to_string(d.join("a.csv")).unwrap(), "keep\n");
    // The plot beside --out: `spectrum --out x.svg` would overwrite its own CSV.
    let (code, _, err) = run_in(d, &["spectrum", "--out", "x.svg"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("same file"), "{err}");
    // The merged file over one of its shards.
    let (code, _, err) = run_in(d, &["merge", "a.csv", "l.csv", "--no-plot"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("same file"), "{err}");
    assert_eq!(listing(d), ["a.csv", "h.csv", "l.csv", "sub"]);
}

const SWEEP: [&str; 11] = [
    "sweep",
    "--method",
    "dop853",
    "--from",
    "1",
    "--to",
    "3",
    "--steps",
    "5",
    "--transient",
    "2",
];

#[test]
fn merge_refuses_incomplete_or_inconsistent_shards() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sweep = |extra: &[&str]| {
        let mut args: Vec<&str> = SWEEP.to_vec();
        args.extend(["--keep", "3"]);
        args.extend(extra);
        let (code, _, err) = run_in(d, &args);
        assert_eq!(code, Some(0), "{err}");
    };
    sweep(&["--out", "full.csv", "--no-plot"]);
    for i in 0..3 {
        sweep(&["--shard", &format!("{i}/3"), "--out", &format!("s{i}.csv")]);
    }
    sweep(&[
        "--shard",
        "1/3",
        "--out",
        "other.csv",
        "--set",
        "damping_ratio=0.2",
    ]);
    sweep(&["--shard", "1/2", "--out", "half.csv"]);
    let body = fs::read_to_string(d.join("s2.csv")).unwrap();
    fs::write(d.join("cut.csv"), &body[..body.len() - 7]).unwrap();
    fs::write(d.join("edited.csv"), body.replacen(",2,", ",3,", 1)).unwrap();

    let merge = |shards: &[&str], expected: &str| {
        let mut args = vec!["merge", "m.csv", "--no-plot"];
        args.extend(shards);
        let (code, _, err) = run_in(d, &args);
        assert_eq!(code, Some(2), "{shards:?}: {err}");
        assert!(
            err.contains(expected),
            "{shards:?}: '{expected}' not in {err}"
        );
        assert!(!d.join("m.csv").exists());
    };
    merge(&["s0.csv", "s2.csv"], "missing shard 1/3");
    merge(&["s0.csv", "s1.csv", "s1.csv", "s2.csv"], "given twice");
    merge(&["s0.csv", "s1.csv", "s2.csv", "s2.csv"], "given twice");
    merge(&["s0.csv", "other.csv", "s2.csv"], "different sweeps");
    merge(&["s0.csv", "s1.csv", "half.csv"], "differently sharded");
    merge(&["s0.csv", "s1.csv", "cut.csv"], "truncated");
    merge(&["s0.csv", "s1.csv", "edited.csv"], "checksum");
    merge(&["full.csv"], "metadata");

    // The complete set, in any order, is the unsharded sweep byte for byte.
    let (code, _, err) = run_in(
        d,
        &["merge", "m.csv", "--no-plot", "s2.csv", "s0.csv", "s1.csv"],
    );
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        fs::read(d.join("m.csv")).unwrap(),
        fs::read(d.join("full.csv")).unwrap()
    );
}

/// Temporary files left in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    listing(dir)
        .into_iter()
        .filter(|n| n.starts_with(".rotor-rub-"))
        .collect()
}

#[test]
fn interrupted_sweep_leaves_nothing_and_reruns() {
    // SIGINT left `.rotor-rub-*` files behind.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("sw.csv"), "previous\n").unwrap();
    let long = [
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
    ];
    let mut child = Command::new(assert_cmd::cargo::cargo_bin!("rotor-rub"))
        .current_dir(d)
        .args(long)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait (without a deadline on the run itself) until the sweep is writing.
    let waited = Instant::now();
    while temporaries(d).is_empty() && waited.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        !temporaries(d).is_empty(),
        "the sweep never started writing"
    );
    let pid = child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-INT", &pid])
            .status()
            .unwrap()
            .success()
    );
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{status:?}");
    assert_eq!(temporaries(d), Vec::<String>::new());
    assert_eq!(
        fs::read_to_string(d.join("sw.csv")).unwrap(),
        "previous\n",
        "no half result"
    );

    // The rerun completes.
    let mut rerun: Vec<&str> = long.to_vec();
    rerun[6] = "2"; // a short transient this time
    let (code, _, err) = run_in(d, &rerun);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        fs::read_to_string(d.join("sw.csv"))
            .unwrap()
            .starts_with("value,period")
    );
    assert_eq!(temporaries(d), Vec::<String>::new());
}
