//! Issue 32's runtime items as the commands show them: `compare` calls no contact unmatched
//! that lies below what both runs resolve (the exactly grazing orbit, item 4) and finds every
//! switch of the stiff dry whip in both runs (item 1); the Lyapunov estimate continues section
//! states faster than the start ranges allow (a runaway dry whip).

use std::path::Path;

use crate::common::bin;

/// Run in `dir`, expect success, return stdout.
fn run_ok(dir: &Path, args: &[&str]) -> String {
    let out = bin().current_dir(dir).args(args).output().unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    );
    assert!(out.status.success(), "{args:?}: {stderr}");
    stdout
}

/// The number after `unmatched` in compare's summary.
fn unmatched(report: &str) -> usize {
    let line = report
        .lines()
        .find(|l| l.starts_with("switches:"))
        .unwrap_or_else(|| panic!("no summary in {report}"));
    line.rsplit("unmatched ")
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

/// The orbit z ≡ 1 (ε = 0, start (1, 0, 0, 1), ν = 0, no unbalance to speak of): the analytic
/// method follows it without contact; dop853 and rk45 leave it by their truncation error and
/// touch the stator thousands of times, each contact shallower than they resolve (before:
/// 2306 unmatched with dop853 at its default tolerance).
#[test]
fn compare_sets_aside_contacts_below_the_resolution() {
    let dir = tempfile::tempdir().unwrap();
    let grazing = [
        "compare",
        "--set",
        "offset_x=0",
        "--set",
        "offset_y=0",
        "--set",
        "x0=1",
        "--set",
        "y0=0",
        "--set",
        "vx0=0",
        "--set",
        "vy0=1",
        "--set",
        "damping_ratio=0",
        "--set",
        "mass_ratio=1e-300",
    ];
    for extra in [
        &["--reference", "dop853"][..],
        &["--reference", "dop853", "--reference-tol", "1e-6"],
        &["--reference", "rk45", "--reference-tol", "1e-6"],
    ] {
        let args: Vec<&str> = grazing.iter().chain(extra).copied().collect();
        let report = run_ok(dir.path(), &args);
        assert_eq!(unmatched(&report), 0, "{extra:?}: {report}");
        assert!(report.contains("set aside: "), "{extra:?}: {report}");
    }
}

/// The stiff dry whip of item 1: both runs find the same switches (before: 12 unmatched, the
/// reference's zero-length `roll`/`slip` pairs).
#[test]
fn compare_matches_every_switch_of_the_stiff_dry_whip() {
    let dir = tempfile::tempdir().unwrap();
    let report = run_ok(
        dir.path(),
        &[
            "compare",
            "--preset",
            "dry-whip",
            "--set",
            "k_xx=1e5",
            "--set",
            "k_yy=1e5",
            "--periods",
            "10",
        ],
    );
    assert_eq!(unmatched(&report), 0, "{report}");
    assert!(!report.contains("set aside"), "{report}");
}

/// A runaway dry whip (the `friction` preset with μ = 0.6) whirls faster than 100 clearances
/// per unit τ: the Lyapunov estimate continues from its section states (before: "invalid
/// problem: vx0 = 134.9 is out of range").
#[test]
fn lyapunov_continues_states_beyond_the_start_ranges() {
    let dir = tempfile::tempdir().unwrap();
    let report = run_ok(
        dir.path(),
        &[
            "poincare",
            "--preset",
            "friction",
            "--set",
            "friction_coefficient=0.6",
            "--method",
            "dop853",
            "--lyapunov",
            "--transient",
            "50",
            "--keep",
            "20",
            "--out",
            "p.csv",
        ],
    );
    assert!(report.contains("largest Lyapunov exponent"), "{report}");
    let csv = std::fs::read_to_string(dir.path().join("p.csv")).unwrap();
    let fastest = csv
        .lines()
        .skip(1)
        .flat_map(|l| {
            l.split(',')
                .skip(3)
                .map(|v| v.parse::<f64>().unwrap().abs())
        })
        .fold(0.0, f64::max);
    assert!(
        fastest > 100.0,
        "the section stays within the start ranges: {fastest}"
    );
}
