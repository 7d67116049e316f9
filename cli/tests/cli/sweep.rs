//! Sweeps: shards joined by `merge` equal the unsharded sweep byte for byte.

use std::fs;

use rotor_rub::Method;

use crate::common::{bin, num, read_csv};
use crate::require;

const SWEEP: [&str; 12] = [
    "sweep",
    "--method",
    "dop853",
    "--from",
    "3",
    "--to",
    "1",
    "--steps",
    "5",
    "--transient",
    "3",
    "--keep",
];

#[test]
fn shards_merge_to_the_unsharded_sweep() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    let sweep = |extra: &[&str]| {
        bin()
            .current_dir(dir.path())
            .args(SWEEP)
            .arg("4")
            .args(extra)
            .assert()
            .success();
    };
    sweep(&["--out", "full.csv"]);
    for (i, spec) in ["0/3", "1/3", "2/3"].iter().enumerate() {
        sweep(&["--shard", spec, "--out", &format!("s{i}.csv")]);
    }
    assert!(dir.path().join("full.svg").exists() && dir.path().join("full.png").exists());
    assert!(!dir.path().join("s0.svg").exists(), "no plot for a shard");

    // Shards given in any order.
    bin()
        .current_dir(dir.path())
        .args([
            "merge",
            "merged.csv",
            "s2.csv",
            "s0.csv",
            "s1.csv",
            "--param",
            "speed_ratio",
        ])
        .assert()
        .success();
    let full = fs::read(dir.path().join("full.csv")).unwrap();
    assert_eq!(fs::read(dir.path().join("merged.csv")).unwrap(), full);
    assert!(dir.path().join("merged.png").exists());

    let (header, rows) = read_csv(&dir.path().join("full.csv"));
    assert_eq!(header, ["value", "period", "x", "y", "vx", "vy"]);
    assert_eq!(rows.len(), 5 * 4);
    let values: Vec<f64> = rows.iter().step_by(4).map(|r| num(&r[0])).collect();
    assert_eq!(
        values,
        [1.0, 1.5, 2.0, 2.5, 3.0],
        "ascending whatever the sweep direction"
    );
    let periods: Vec<&str> = rows[..4].iter().map(|r| r[1].as_str()).collect();
    assert_eq!(periods, ["3", "4", "5", "6"]);
}

#[test]
fn a_diverging_value_fails_the_sweep_or_is_skipped() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("sw.csv"), "keep me\n").unwrap();
    // k_yx = −10 with k_xy = 15 is the flutter case (docs/MODEL.md §6 case 3); k_yx = 20 is not.
    let args = [
        "sweep",
        "--method",
        "dop853",
        "--set",
        "k_xy=15",
        "--param",
        "k_yx",
        "--from",
        "-10",
        "--to",
        "20",
        "--steps",
        "2",
        "--transient",
        "40",
        "--keep",
        "2",
        "--out",
        "sw.csv",
    ];
    let out = bin().current_dir(dir.path()).args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("k_yx = -10") && stderr.contains("diverged"),
        "{stderr}"
    );
    assert_eq!(
        fs::read_to_string(dir.path().join("sw.csv")).unwrap(),
        "keep me\n"
    );
    assert!(!dir.path().join("sw.svg").exists());

    bin()
        .current_dir(dir.path())
        .args(args)
        .arg("--skip-errors")
        .assert()
        .success()
        .stderr(predicates::str::contains("warning: skipped k_yx = -10"));
    let (_, rows) = read_csv(&dir.path().join("sw.csv"));
    assert_eq!(rows.len(), 2);
    assert!(rows.iter().all(|r| num(&r[0]) == 20.0));
}
