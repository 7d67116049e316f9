//! `rotor-rub orbit` and `rotor-rub continue` (issue 30): the report, the branch file and the
//! plot, and bad input refused with exit 2 naming the value, leaving no file behind.

use std::fs;
use std::path::Path;

use crate::common::{bin, listing, num, read_csv};

/// Run `args` in `dir`; its stdout.
fn runs_in(dir: &Path, args: &[&str]) -> String {
    let out = bin().current_dir(dir).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Run `args` in a fresh directory holding `files`: exit `code`, one error line holding every
/// `expected` piece, no file created.
fn fails(code: i32, args: &[&str], files: &[(&str, &[u8])], expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        fs::write(dir.path().join(name), bytes).unwrap();
    }
    let before = listing(dir.path());
    let out = bin().current_dir(dir.path()).args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "{args:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    for piece in expected {
        assert!(
            stderr.contains(piece),
            "{args:?}: '{piece}' missing from {stderr}"
        );
    }
    assert!(out.stdout.is_empty());
    assert_eq!(listing(dir.path()), before, "{args:?}: files changed");
}

#[test]
fn orbit_reports_the_orbit_its_multipliers_and_newtons_residuals() {
    let dir = tempfile::tempdir().unwrap();
    let report = runs_in(
        dir.path(),
        &[
            "orbit",
            "--set",
            "speed_ratio=2.2",
            "--start",
            "2.1,-1.2,0.5,-5.6",
            "--samples",
            "orbit.csv",
            "--sample-count",
            "11",
        ],
    );
    for piece in [
        "Newton: residual",
        "orbit: period-1 (k = 1) at speed_ratio = 2.2",
        "x = 2.11022788210",
        "multipliers:",
        "(|λ| 0.699773)",
        "stable: yes",
        "contact fraction 1.0000",
        "wrote orbit.csv",
    ] {
        assert!(report.contains(piece), "'{piece}' missing from {report}");
    }
    let (header, rows) = read_csv(&dir.path().join("orbit.csv"));
    assert_eq!(header, ["tau", "x", "y", "vx", "vy", "regime"]);
    assert_eq!(rows.len(), 11);
    // One forcing period: the last sample is the first (the orbit closes).
    let (first, last) = (&rows[0], &rows[10]);
    for c in 1..5 {
        assert!(
            (num(&first[c]) - num(&last[c])).abs() < 1e-8,
            "{first:?} {last:?}"
        );
    }
    assert!(rows.iter().all(|r| r[5] == "contact"));
}

#[test]
fn orbit_finds_the_period_two_orbit_the_simulation_settles_on() {
    let dir = tempfile::tempdir().unwrap();
    let report = runs_in(
        dir.path(),
        &["orbit", "--set", "speed_ratio=3", "--period", "2"],
    );
    assert!(report.contains("orbit: period-2 (k = 2)"), "{report}");
    assert!(report.contains("stable: yes"), "{report}");
    // The same orbit asked as period 1 is not one: Newton finds the unstable period-1 orbit.
    let report = runs_in(dir.path(), &["orbit", "--set", "speed_ratio=3"]);
    assert!(report.contains("orbit: period-1"), "{report}");
    assert!(report.contains("stable: no"), "{report}");
    // The free orbit: one Newton step from its closed form.
    let report = runs_in(
        dir.path(),
        &["orbit", "--set", "speed_ratio=3", "--start", "free"],
    );
    assert!(report.contains("0 entries over the orbit"), "{report}");
}

#[test]
fn orbit_refuses_bad_input() {
    fails(
        2,
        &["orbit", "--period", "0"],
        &[],
        &["--period", "0", ">= 1"],
    );
    fails(2, &["orbit", "--period", "33"], &[], &["33", "[1, 32]"]);
    fails(
        2,
        &["orbit", "--start", "1,2,3"],
        &[],
        &["--start", "3 numbers", "x,y,vx,vy"],
    );
    fails(
        2,
        &["orbit", "--start", "somewhere"],
        &[],
        &["--start", "somewhere"],
    );
    fails(
        2,
        &["orbit", "--start", "free@2"],
        &[],
        &["@VALUE", "--set"],
    );
    fails(
        2,
        &["orbit", "--newton-tol", "0.5"],
        &[],
        &["tolerance = 5e-1", "[1e-14, 1e-3]"],
    );
    fails(
        2,
        &["orbit", "--set", "speed_ratio=0"],
        &[],
        &["speed_ratio", "0"],
    );
    // No orbit near a start: a failed run (exit 1) that says so.
    fails(
        1,
        &["orbit", "--preset", "friction", "--set", "speed_ratio=1.5"],
        &[],
        &["did not converge"],
    );
}

#[test]
fn continue_writes_the_branch_file_and_plot_and_reports_the_bifurcations() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("sweep.csv"),
        "value,period,x,y,vx,vy\n1.5,200,0.1,0.2,0.3,0.4\n1.6,200,0.2,0.1,0.0,0.0\n",
    )
    .unwrap();
    let report = runs_in(
        dir.path(),
        &[
            "continue",
            "--from",
            "1.8",
            "--to",
            "1.4",
            "--start",
            "free",
            "--max-period",
            "1",
            "--out",
            "branch.csv",
            "--behind",
            "sweep.csv",
        ],
    );
    for piece in [
        "branch 0: period-1",
        // The free orbit grazes, rubs lightly down to a fold and turns back up, unstable.
        "ended: it left the range at speed_ratio = 1.8",
        "grazing          speed_ratio = 1.4421330590",
        "fold             speed_ratio = 1.4328",
        "wrote branch.csv, branch.svg, branch.png",
    ] {
        assert!(report.contains(piece), "'{piece}' missing from {report}");
    }
    let (header, rows) = read_csv(&dir.path().join("branch.csv"));
    assert_eq!(
        header[..11],
        [
            "value",
            "period",
            "max_radius",
            "min_radius",
            "contact_fraction",
            "modulus_1",
            "modulus_2",
            "modulus_3",
            "modulus_4",
            "stable",
            "bifurcation"
        ]
    );
    assert_eq!(header.len(), 25);
    assert!(rows.iter().all(|r| r.len() == 25));
    assert_eq!(num(&rows[0][0]), 1.8);
    assert_eq!(rows[0][9], "true");
    assert_eq!(num(&rows.last().unwrap()[0]), 1.8);
    assert_eq!(rows.last().unwrap()[9], "false");
    let grazing = rows
        .iter()
        .find(|r| r[10] == "grazing")
        .expect("a grazing row");
    assert!((num(&grazing[0]) - 1.442_133_059).abs() < 1e-8);
    // Stable rows have every modulus below 1; unstable ones one above.
    for r in &rows {
        let largest = (5..9).map(|i| num(&r[i])).fold(0.0, f64::max);
        assert_eq!(r[9] == "true", largest < 1.0, "{r:?}");
    }
    for plot in ["branch.svg", "branch.png"] {
        assert!(fs::metadata(dir.path().join(plot)).unwrap().len() > 1000);
    }
}

#[test]
fn continue_refuses_bad_input() {
    fails(
        2,
        &["continue", "--from", "1", "--to", "1"],
        &[],
        &["--to = 1 equals --from"],
    );
    fails(
        2,
        &["continue", "--param", "x0", "--from", "0", "--to", "1"],
        &[],
        &["--param x0", "model parameter"],
    );
    fails(
        2,
        &["continue", "--from", "0", "--to", "1"],
        &[],
        &["--from = 0", "speed_ratio", "[0.001, 100]"],
    );
    fails(
        2,
        &["continue", "--from", "1", "--to", "2", "--start", "free@5"],
        &[],
        &["@5", "[1, 2]"],
    );
    fails(
        2,
        &[
            "continue",
            "--from",
            "1",
            "--to",
            "2",
            "--behind",
            "nothing.csv",
        ],
        &[],
        &["--behind", "nothing.csv"],
    );
    fails(
        2,
        &[
            "continue", "--from", "1", "--to", "2", "--behind", "bad.csv",
        ],
        &[("bad.csv", b"a,b\n1,2\n")],
        &["not a sweep file", "value and x"],
    );
    fails(
        2,
        &[
            "continue",
            "--from",
            "1",
            "--to",
            "2",
            "--newton-tol",
            "1e-20",
        ],
        &[],
        &["--newton-tol = 1e-20", "[1e-14, 1e-3]"],
    );
    fails(
        2,
        &["continue", "--from", "1", "--to", "2", "--sweep", "1"],
        &[],
        &["--sweep"],
    );
}
