//! Friction from the command line (issue 12): the presets, the parameters and their errors, the
//! simulate summary and files, compare and sweep with friction.

use crate::common::{bin, read_csv};

fn stdout(args: &[&str]) -> String {
    let out = bin().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn fails_with(args: &[&str], code: i32, needles: &[&str]) {
    let out = bin().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(code), "{args:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err}");
    }
}

#[test]
fn presets_and_parameters_are_listed() {
    let presets = stdout(&["presets"]);
    assert!(
        presets.contains("friction") && presets.contains("dry-whip"),
        "{presets}"
    );
    let params = stdout(&["params"]);
    for name in ["friction_coefficient", "radius_ratio"] {
        assert!(params.contains(name), "{params}");
    }
}

#[test]
fn bad_friction_input_is_refused_with_its_range() {
    fails_with(
        &["simulate", "--set", "friction_coefficient=-0.1"],
        2,
        &["friction_coefficient", "-0.1", "[0, 10]"],
    );
    fails_with(
        &["simulate", "--set", "radius_ratio=0"],
        2,
        &["radius_ratio", "(0, "],
    );
    // μ > 0 needs a positive definite symmetric part of K_s.
    fails_with(
        &[
            "simulate",
            "--set",
            "friction_coefficient=0.2",
            "--set",
            "k_xy=30",
            "--set",
            "k_yx=30",
        ],
        2,
        &["friction_coefficient", "positive definite"],
    );
}

#[test]
fn dry_whip_summary_and_files_show_rolling() {
    let dir = tempfile::tempdir().unwrap();
    let (e, s) = (dir.path().join("e.csv"), dir.path().join("s.csv"));
    let text = stdout(&[
        "simulate",
        "--preset",
        "dry-whip",
        "--method",
        "hybrid",
        "--periods",
        "40",
        "--events",
        e.to_str().unwrap(),
        "--samples",
        s.to_str().unwrap(),
        "--sample-count",
        "101",
    ]);
    assert!(text.contains("rolling starts"), "{text}");
    assert!(text.contains("(rolling)"), "ends rolling: {text}");
    assert!(text.contains("backward"), "{text}");
    let (_, events) = read_csv(&e);
    let kinds: Vec<&str> = events.iter().map(|r| r[1].as_str()).collect();
    assert!(
        kinds.contains(&"roll") && kinds.contains(&"slip"),
        "{kinds:?}"
    );
    let (header, samples) = read_csv(&s);
    assert_eq!(header.last().map(String::as_str), Some("regime"));
    assert_eq!(samples.last().map(|r| r[6].as_str()), Some("rolling"));
}

#[test]
fn frictionless_summary_is_unchanged() {
    let text = stdout(&["simulate", "--periods", "2"]);
    assert!(
        !text.contains("friction:") && !text.contains("whirl"),
        "{text}"
    );
}

#[test]
fn compare_and_sweep_work_with_friction() {
    let dir = tempfile::tempdir().unwrap();
    let text = stdout(&[
        "compare",
        "--preset",
        "friction",
        "--periods",
        "5",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ]);
    assert!(!text.is_empty());
    let (_, table) = read_csv(&dir.path().join("compare.csv"));
    assert!(!table.is_empty());
    let out = dir.path().join("sweep.csv");
    stdout(&[
        "sweep",
        "--preset",
        "friction",
        "--param",
        "friction_coefficient",
        "--from",
        "0.1",
        "--to",
        "0.3",
        "--steps",
        "3",
        "--transient",
        "5",
        "--keep",
        "3",
        "--no-plot",
        "--out",
        out.to_str().unwrap(),
    ]);
    let (_, rows) = read_csv(&out);
    assert_eq!(rows.len(), 9);
}

#[test]
fn friction_figure_is_drawn() {
    let dir = tempfile::tempdir().unwrap();
    let text = stdout(&[
        "friction",
        "--plot-to",
        "5",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ]);
    assert!(text.contains("rolling episodes"), "{text}");
    for f in ["friction.svg", "friction.png"] {
        let len = std::fs::metadata(dir.path().join(f)).unwrap().len();
        assert!(len > 1000, "{f}: {len} bytes");
    }
    fails_with(
        &[
            "friction",
            "--presets",
            "paper",
            "--out-dir",
            dir.path().to_str().unwrap(),
        ],
        2,
        &["no friction"],
    );
}
