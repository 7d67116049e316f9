//! Issue 32 items 11 and 12 (command line): a value the command would ignore is refused, and an
//! input error names the flag the user typed, on the right line of the file it came from.

use std::fs;
use std::path::Path;

use crate::common::{bin, listing};

/// `args` in `dir` fails with exit 2 and one `error:` line holding every piece of `expected`
/// (and none of `absent`), writing nothing.
fn refused_in(dir: &Path, args: &[&str], expected: &[&str], absent: &[&str]) {
    let before = listing(dir);
    let out = bin().current_dir(dir).args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.starts_with("error: ") && err.lines().count() == 1,
        "{args:?}: {err}"
    );
    for piece in expected {
        assert!(err.contains(piece), "{args:?}: '{piece}' not in {err}");
    }
    for piece in absent {
        assert!(!err.contains(piece), "{args:?}: '{piece}' in {err}");
    }
    assert_eq!(listing(dir), before, "{args:?} wrote files");
}

fn refused(args: &[&str], expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    refused_in(dir.path(), args, expected, &["propagation failed"]);
}

#[test]
fn tolerances_and_steps_name_their_flag() {
    // `compare --reference-tol 0.5` said "propagation failed: tol = …".
    refused(
        &["compare", "--reference-tol", "0.5"],
        &["--reference-tol", "5e-1", "dop853", "[1e-14, 1e-3]"],
    );
    refused(
        &["compare", "--reference", "rk45", "--reference-tol", "1e-3"],
        &["--reference-tol", "rk45", "[1e-14, 1e-4]"],
    );
    refused(
        &["fig2", "--reference-tol", "0.5"],
        &["--reference-tol", "dop853"],
    );
    refused(
        &["--reference-tol", "1e-20", "--speeds", "1"],
        &["--reference-tol", "dop853"],
    );
    for command in [
        "simulate", "compare", "fig2", "sweep", "poincare", "spectrum",
    ] {
        refused(&[command, "--tol", "0.5"], &["--tol", "5e-1", "[1e-"]);
    }
    refused(&["friction", "--tol", "1"], &["--tol", "taylor"]);
    refused(&["runup", "--tol", "0.5"], &["--tol", "taylor"]);
    refused(
        &["simulate", "--step", "5"],
        &["--step", "5e0", "[1e-6, 1e-1]"],
    );
    refused(&["compare", "--step", "1e-9"], &["--step", "1e-9"]);
    refused(
        &["runup", "--method", "analytic", "--speed-holds", "99999"],
        &["--speed-holds", "9.9999e4", "[1e0, 4.096e3]"],
    );
}

#[test]
fn ramp_values_name_their_flag() {
    refused(
        &["runup", "--rate", "5"],
        &["--rate", "dη/dτ = 5", "(0, 1]"],
    );
    refused(
        &["runup", "--ramp-periods", "0.5"],
        &["--ramp-periods", "over 0.5 periods"],
    );
    refused(&["runup", "--settle", "-3"], &["--settle", "settle = -3"]);
    refused(&["runup", "--dwell", "-1"], &["--dwell", "dwell = -1"]);
    refused(&["runup", "--from", "0"], &["--from", "from = 0"]);
    refused(&["runup", "--to", "500"], &["--to", "to = 500"]);
}

#[test]
fn ignored_range_ends_are_refused() {
    // `sweep --from 1 --to 2 --steps 1` ran 1 and ignored --to.
    refused(
        &["sweep", "--from", "1", "--to", "2", "--steps", "1"],
        &["--steps 1", "--to 2"],
    );
    refused(
        &["sweep", "--from", "2", "--to", "2", "--steps", "3"],
        &["--steps 3", "--from", "--to"],
    );
    // --dwell holds at --to before running back: with --one-way there is no way back.
    refused(
        &["runup", "--one-way", "--dwell", "5"],
        &["--dwell", "--one-way"],
    );
    // compare plotted nothing (or everything) for a --plot-from outside the run.
    refused(
        &["compare", "--periods", "2", "--plot-from", "100"],
        &["--plot-from", "100", "[0, 2)"],
    );
    refused(
        &["compare", "--periods", "2", "--plot-from", "-3"],
        &["--plot-from", "-3"],
    );
    // fig2 compared switch times over periods the runs never reach.
    refused(
        &["fig2", "--match-periods", "1000", "--speeds", "1"],
        &["--match-periods", "1000", "300"],
    );
    // friction's sample count overflowed (a panic in debug builds).
    refused(
        &["friction", "--plot-to", "18446744073709551615"],
        &["--plot-to"],
    );
}

#[test]
fn a_single_value_sweep_runs_from_alone() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["--from", "2", "--steps", "1"][..],
        &["--from", "2", "--to", "2", "--steps", "1"],
    ] {
        let out = bin()
            .current_dir(dir.path())
            .args(["sweep", "--transient", "0", "--keep", "1", "--no-plot"])
            .args(["--out", "one.csv"])
            .args(args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = fs::read_to_string(dir.path().join("one.csv")).unwrap();
        let rows: Vec<&str> = text.lines().skip(1).collect();
        assert_eq!(rows.len(), 1, "{text}");
        assert!(rows[0].starts_with("2.0,"), "{text}");
    }
}

#[test]
fn toml_errors_name_the_right_line() {
    // A duplicate key was reported one line early.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (text, line, key) in [
        ("speed_ratio = 2\nspeed_ratio = 3\n", 2, "speed_ratio"),
        ("# c\n\nk_xx = 1\n\n\nk_xx = 2\n", 6, "k_xx"),
        ("speed_ratio = 2\r\nspeed_ratio = 3\r\n", 2, "speed_ratio"),
        ("speed_ratio = 2\nk_xx = \n", 2, ""),
        ("speed_ratio = = 2\n", 1, ""),
    ] {
        fs::write(d.join("c.toml"), text).unwrap();
        let expected = format!("(line {line})");
        refused_in(
            d,
            &["simulate", "--config", "c.toml"],
            &["--config c.toml", "not valid TOML", &expected, key],
            &[],
        );
    }
}
