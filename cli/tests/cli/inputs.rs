//! Issue 32 item 10: an output path that names a file the command reads (its config, its speed
//! profile, a shard) is refused before anything is written, however it is spelled: the same
//! name, `./name`, a symlink to it, a hard link to it, or the plot beside an output.

use std::fs;
use std::path::Path;

use crate::common::{bin, listing};

const CONFIG: &str = "speed_ratio = 2\n";
const PROFILE: &str = "0,1\n60,1.1\n";

/// A directory holding the inputs and links to them.
fn inputs() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["c.toml", "compare.csv", "fig2.svg", "x.svg"] {
        fs::write(d.join(name), CONFIG).unwrap();
    }
    for name in ["p.csv", "r-events.csv"] {
        fs::write(d.join(name), PROFILE).unwrap();
    }
    std::os::unix::fs::symlink("c.toml", d.join("link.toml")).unwrap();
    fs::hard_link(d.join("c.toml"), d.join("hard.toml")).unwrap();
    std::os::unix::fs::symlink("p.csv", d.join("link.csv")).unwrap();
    fs::create_dir(d.join("sub")).unwrap();
    dir
}

/// `args` refused (exit 2, naming both flags and "same file"), every file as it was.
fn refused(d: &Path, args: &[&str], flags: &[&str]) {
    let before: Vec<(String, Vec<u8>)> = listing(d)
        .into_iter()
        .filter(|n| n != "sub")
        .map(|n| {
            let bytes = fs::read(d.join(&n)).unwrap();
            (n, bytes)
        })
        .collect();
    let out = bin().current_dir(d).args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains("same file"), "{args:?}: {err}");
    for flag in flags {
        assert!(err.contains(flag), "{args:?}: {flag} not in {err}");
    }
    let after: Vec<(String, Vec<u8>)> = listing(d)
        .into_iter()
        .filter(|n| n != "sub")
        .map(|n| {
            let bytes = fs::read(d.join(&n)).unwrap();
            (n, bytes)
        })
        .collect();
    assert_eq!(before, after, "{args:?} changed the files");
}

#[test]
fn outputs_onto_the_config_are_refused_in_every_command() {
    let dir = inputs();
    let d = dir.path();
    let config = ["--config", "c.toml"];
    let with = |tail: &[&'static str]| -> Vec<&'static str> {
        let mut v = vec![tail[0]];
        v.extend(config);
        v.extend(&tail[1..]);
        v
    };
    // The examples, then every command with a config and an output.
    refused(
        d,
        &with(&["simulate", "--events", "c.toml"]),
        &["--events", "--config"],
    );
    refused(
        d,
        &with(&["simulate", "--samples", "c.toml"]),
        &["--samples", "--config"],
    );
    refused(
        d,
        &with(&["simulate", "--events", "./sub/../c.toml"]),
        &["--events"],
    );
    refused(
        d,
        &with(&["simulate", "--events", "link.toml"]),
        &["--events"],
    );
    refused(
        d,
        &with(&["simulate", "--samples", "hard.toml"]),
        &["--samples"],
    );
    refused(
        d,
        &["simulate", "--config", "link.toml", "--events", "hard.toml"],
        &["--events"],
    );
    refused(
        d,
        &with(&["sweep", "--out", "c.toml"]),
        &["--out", "--config"],
    );
    refused(
        d,
        &["sweep", "--config", "x.svg", "--out", "x.csv"],
        &["the plot", "--config"],
    );
    refused(d, &with(&["poincare", "--out", "link.toml"]), &["--out"]);
    refused(d, &with(&["spectrum", "--out", "hard.toml"]), &["--out"]);
    refused(
        d,
        &["compare", "--config", "compare.csv", "--out-dir", "."],
        &["--out-dir", "--config"],
    );
    refused(
        d,
        &["fig2", "--config", "fig2.svg", "--out-dir", "."],
        &["--out-dir", "--config"],
    );
    refused(
        d,
        &[
            "--config",
            "fig2.svg",
            "--out-dir",
            "sub/..",
            "--speeds",
            "1",
        ],
        &["--out-dir", "--config"],
    );
    refused(
        d,
        &with(&["runup", "--out", "c.toml"]),
        &["--out", "--config"],
    );
    refused(
        d,
        &with(&["runup", "--events", "link.toml"]),
        &["--events", "--config"],
    );
}

#[test]
fn outputs_onto_the_speed_profile_are_refused() {
    let dir = inputs();
    let d = dir.path();
    refused(
        d,
        &["runup", "--profile", "p.csv", "--out", "p.csv"],
        &["--out", "--profile"],
    );
    refused(
        d,
        &["runup", "--profile", "p.csv", "--events", "link.csv"],
        &["--events", "--profile"],
    );
    // The events file named after --out is the profile.
    refused(
        d,
        &["runup", "--profile", "r-events.csv", "--out", "r.csv"],
        &["--events", "--profile"],
    );
}
