//! `rotor-rub runup` (issue 17): the run-up program's files and report, a speed profile from a
//! file, one-way runs, and bad input refused with exit 2, naming the value and its range,
//! leaving no file behind.

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

/// Run `args` in a fresh directory holding `files`: exit 2, one error line holding every
/// `expected` piece, no file created.
fn refused(args: &[&str], files: &[(&str, &[u8])], expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        fs::write(dir.path().join(name), bytes).unwrap();
    }
    let before = listing(dir.path());
    let out = bin().current_dir(dir.path()).args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
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
fn the_default_program_draws_the_hysteresis_loop_of_the_paper_rotor() {
    let dir = tempfile::tempdir().unwrap();
    let report = runs_in(dir.path(), &["runup"]);
    let out = dir.path().join("out");
    assert_eq!(
        listing(&out),
        ["runup-events.csv", "runup.csv", "runup.png", "runup.svg"]
    );
    // The run-up jumps off the rub branch near η = 2.5, the coast-down jumps back near 1.4.
    assert!(report.contains("run-up: η 0.506 -> 3.499"), "{report}");
    assert!(report.contains("  jump at η = 2.4"), "{report}");
    assert!(report.contains("coast-down: η 3.499 -> 0.517"), "{report}");
    assert!(report.contains("  jump at η = 1.4"), "{report}");
    let (header, rows) = read_csv(&out.join("runup.csv"));
    assert_eq!(
        header.join(","),
        "direction,period,start,end,speed_ratio,speed_change,max_radius,min_radius,contact_fraction,whirl,whirl_direction,enters,exits"
    );
    assert!(rows.len() > 1900);
    // Consecutive periods, each starting where the last ended.
    for pair in rows.windows(2) {
        assert_eq!(num(&pair[0][1]) + 1.0, num(&pair[1][1]));
        assert_eq!(pair[0][3], pair[1][2]);
    }
    let directions: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(directions.iter().filter(|d| **d == "hold").count(), 20);
    assert!(directions.contains(&"up") && directions.contains(&"down"));
    // The hysteresis: at η ≈ 2.3 the run-up's orbit is far larger than the coast-down's.
    let at = |direction: &str| {
        rows.iter()
            .filter(|r| r[0] == direction)
            .min_by(|a, b| {
                (num(&a[4]) - 2.3)
                    .abs()
                    .total_cmp(&(num(&b[4]) - 2.3).abs())
            })
            .map(|r| num(&r[6]))
            .unwrap()
    };
    assert!(
        at("up") > 2.5 && at("down") < 0.6,
        "{} {}",
        at("up"),
        at("down")
    );
    // Every switch is in the events file, with its period's counts.
    let (header, events) = read_csv(&out.join("runup-events.csv"));
    assert_eq!(
        header.join(","),
        "time,speed_ratio,period,direction,kind,x,y,vx,vy"
    );
    let enters: f64 = rows.iter().map(|r| num(&r[11])).sum();
    assert_eq!(
        events.iter().filter(|e| e[4] == "enter").count() as f64,
        enters
    );
    let svg = fs::read_to_string(out.join("runup.svg")).unwrap();
    assert!(svg.contains("coast-down") && svg.contains("jump η = 2.4"));
}

#[test]
fn a_profile_file_and_one_way_ramps() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("p.csv"),
        "# a slow run-up of a rotor without rub\ntime,speed_ratio\n0,0.6\n60,0.6\n2060,1.4\n",
    )
    .unwrap();
    let report = runs_in(
        dir.path(),
        &[
            "runup",
            "--profile",
            "p.csv",
            "--set",
            "mass_ratio=5e-4",
            "--out",
            "r.csv",
            "--no-plot",
        ],
    );
    assert!(
        report.contains("speed profile p.csv (3 points, τ 0 to 2060)"),
        "{report}"
    );
    assert!(
        report.contains("rubbing in 0 %") && report.contains("no jump"),
        "{report}"
    );
    assert_eq!(listing(dir.path()), ["p.csv", "r-events.csv", "r.csv"]);
    let (_, rows) = read_csv(&dir.path().join("r.csv"));
    assert!(rows.iter().all(|r| r[0] == "up" || r[0] == "hold"));
    assert!(rows.iter().all(|r| num(&r[8]) == 0.0));
    // Once the start transient has died out, the unbalance drives a forward circle.
    assert!(
        rows.iter()
            .filter(|r| r[0] == "up")
            .all(|r| r[10] == "forward")
    );

    // A coast-down alone, over 150 periods of its mean speed, analytic.
    let report = runs_in(
        dir.path(),
        &[
            "runup",
            "--from",
            "1.6",
            "--to",
            "0.8",
            "--ramp-periods",
            "150",
            "--one-way",
            "--settle",
            "0",
            "--method",
            "analytic",
            "--speed-holds",
            "16",
            "--out",
            "c.csv",
            "--no-plot",
        ],
    );
    assert!(
        report.contains("speed held over 16 steps per forcing period"),
        "{report}"
    );
    let (_, rows) = read_csv(&dir.path().join("c.csv"));
    assert_eq!(rows.len(), 150);
    assert!(rows.iter().all(|r| r[0] == "down"));
}

#[test]
fn bad_speed_input_is_refused_with_its_range() {
    refused(
        &["runup", "--rate", "-1e-3"],
        &[],
        &["dη/dτ = -0.001", "(0, 1]"],
    );
    refused(
        &["runup", "--rate", "nan"],
        &[],
        &["--rate", "not a finite number"],
    );
    refused(
        &["runup", "--rate", "5"],
        &[],
        &["dη/dτ = 5 is out of range", "(0, 1]"],
    );
    refused(
        &["runup", "--from", "0"],
        &[],
        &["from = 0 is out of range", "[0.001, 100]"],
    );
    refused(&["runup", "--to", "0.5"], &[], &["same speed ratio 0.5"]);
    refused(
        &["runup", "--ramp-periods", "0.5"],
        &[],
        &["over 0.5 periods", "(0, 1]"],
    );
    refused(
        &["runup", "--settle", "-3"],
        &[],
        &["settle = -3 forcing periods", "[0, 1e7]"],
    );
    refused(
        &["runup", "--rate", "1e-9"],
        &[],
        &["would end at τ = ", "[-1e6, 1e6]"],
    );
    refused(
        &["runup", "--rate", "1e-3", "--ramp-periods", "100"],
        &[],
        &["--ramp-periods"],
    );
    refused(
        &["runup", "--profile", "p.csv", "--rate", "1e-3"],
        &[("p.csv", b"0,1\n9,1.1\n")],
        &["--rate"],
    );
    refused(
        &["runup", "--method", "hybrid", "--speed-holds", "8"],
        &[],
        &["--speed-holds applies only to --method analytic"],
    );
    refused(
        &["runup", "--method", "analytic", "--speed-holds", "99999"],
        &[],
        &["speed_holds = 9.9999e4 is out of range", "[1e0, 4.096e3]"],
    );
    refused(
        &["runup", "--preset", "friction"],
        &[],
        &["friction_coefficient = 0.2", "not supported"],
    );
    refused(
        &["runup", "--program", "fast"],
        &[],
        &["unknown run-up program 'fast'", "paper-hysteresis"],
    );
}

#[test]
fn bad_profile_files_are_refused_naming_line_value_and_range() {
    let cases: [(&[u8], &[&str]); 7] = [
        (
            b"0,1\n10,1.2\n5,1.4\n",
            &[
                "p.csv line 3",
                "time = 5 is not after the previous point's time 10",
            ],
        ),
        (
            b"0,1\n10,NaN\n",
            &["p.csv line 2", "speed_ratio = NaN is not a finite number"],
        ),
        (
            b"t,eta\n0,1\n10,250\n",
            &[
                "p.csv line 3",
                "speed_ratio = 250 is out of range: it must be in [0.001, 100]",
            ],
        ),
        (b"0,1\n1,4\n", &["p.csv line 1", "dη/dτ = 3", "at most 1"]),
        (b"0,1\n", &["p.csv", "at least 2 points"]),
        (
            b"0;1\n5;2\n",
            &["p.csv line 1", "expected two comma-separated values"],
        ),
        (b"\xff\xfe0,1\n", &["p.csv", "not UTF-8"]),
    ];
    for (text, expected) in cases {
        refused(
            &["runup", "--profile", "p.csv"],
            &[("p.csv", text)],
            expected,
        );
    }
    let big = vec![b'#'; (1 << 20) + 1];
    refused(
        &["runup", "--profile", "p.csv"],
        &[("p.csv", &big)],
        &["more than the 1048576", "speed profile may have"],
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().display().to_string();
    refused(
        &["runup", "--profile", &path],
        &[],
        &["not a regular file (a speed profile must be a plain CSV file)"],
    );
}
