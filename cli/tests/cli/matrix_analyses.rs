//! The analyses (`poincare`, `spectrum`, `sweep`, `runup`) on a model file (`--model FILE`) and
//! on the paper's rotor with a stator ring of mass (issue 29 item 1, issue 28 items 3–4).
//!
//! The independent check: the paper's Jeffcott rotor written as matrices
//! (`cli/tests/data/paper_jeffcott.toml`, in units where SI is the paper's dimensionless form)
//! gives the planar model's Poincaré points, spectra and sweep points within 1e-10 (each run by
//! its own propagator: the matrix methods against the planar ones); the stepped run-up follows
//! the planar model's exact variable-speed run-up.

use std::path::{Path, PathBuf};

use crate::common::{bin, num, read_csv};

fn two_disk() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models/two_disk.toml")
}

fn jeffcott() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/paper_jeffcott.toml")
}

/// Run the binary with `args`; its exit code and stderr.
fn run(args: &[&str]) -> (i32, String, String) {
    let out = bin().args(args).output().expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn ok(args: &[&str]) -> String {
    let (code, stdout, stderr) = run(args);
    assert_eq!(code, 0, "{args:?}: {stderr}");
    stdout
}

fn path(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

/// The largest difference between the numeric fields of two CSV files with the same rows,
/// skipping the first `skip` columns.
fn largest_difference(a: &Path, b: &Path, skip: usize) -> f64 {
    let (_, ra) = read_csv(a);
    let (_, rb) = read_csv(b);
    assert_eq!(ra.len(), rb.len(), "{} vs {}", a.display(), b.display());
    assert!(!ra.is_empty());
    ra.iter()
        .zip(&rb)
        .flat_map(|(x, y)| {
            assert_eq!(x.len(), y.len());
            x.iter()
                .zip(y)
                .skip(skip)
                .map(|(p, q)| (num(p) - num(q)).abs())
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_jeffcott_as_matrices_gives_the_planar_sections_spectra_and_sweeps() {
    let dir = tempfile::tempdir().expect("tempdir");
    let model = jeffcott();
    for method in ["hybrid", "taylor", "dop853", "analytic"] {
        let tol = if method == "analytic" {
            "1e-12"
        } else {
            "1e-13"
        };
        let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
        let common = [
            "--transient",
            "0",
            "--keep",
            "10",
            "--method",
            method,
            "--tol",
            tol,
        ];
        let mut args = vec!["poincare", "--model", path(&model), "--out", path(&a)];
        args.extend(common);
        ok(&args);
        let mut args = vec!["poincare", "--preset", "paper", "--out", path(&b)];
        args.extend(common);
        ok(&args);
        assert_eq!(
            read_csv(&a).0,
            ["period", "rub_x", "rub_y", "rub_vx", "rub_vy"]
        );
        assert_eq!(read_csv(&b).0, ["period", "x", "y", "vx", "vy"]);
        let d = largest_difference(&a, &b, 0);
        assert!(d < 1e-10, "{method}: Poincaré points differ by {d:e}");
    }

    let (a, b) = (dir.path().join("sa.csv"), dir.path().join("sb.csv"));
    let common = [
        "--transient",
        "0",
        "--periods",
        "6",
        "--samples-per-period",
        "16",
        "--method",
        "taylor",
        "--tol",
        "1e-13",
    ];
    let mut args = vec!["spectrum", "--model", path(&model), "--out", path(&a)];
    args.extend(common);
    ok(&args);
    let mut args = vec!["spectrum", "--out", path(&b)];
    args.extend(common);
    ok(&args);
    assert_eq!(read_csv(&a).0, ["order", "rub_x", "rub_y"]);
    let d = largest_difference(&a, &b, 0);
    assert!(d < 1e-10, "spectra differ by {d:e}");

    let (a, b) = (dir.path().join("wa.csv"), dir.path().join("wb.csv"));
    let common = [
        "--from",
        "1.5",
        "--to",
        "2.5",
        "--steps",
        "3",
        "--transient",
        "0",
        "--keep",
        "6",
        "--method",
        "hybrid",
        "--tol",
        "1e-13",
        "--no-plot",
    ];
    let mut args = vec![
        "sweep",
        "--model",
        path(&model),
        "--param",
        "speed",
        "--out",
        path(&a),
    ];
    args.extend(common);
    ok(&args);
    let mut args = vec!["sweep", "--param", "speed_ratio", "--out", path(&b)];
    args.extend(common);
    ok(&args);
    assert_eq!(read_csv(&a).1.len(), 18);
    let d = largest_difference(&a, &b, 0);
    assert!(d < 1e-10, "sweep points differ by {d:e}");
}

#[test]
fn compare_runs_on_model_files_and_the_ring() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let model = jeffcott();
    let common = [
        "--periods",
        "5",
        "--reference-tol",
        "1e-13",
        "--tol",
        "1e-13",
    ];
    let mut args = vec!["compare", "--model", path(&model), "--out-dir", path(&a)];
    args.extend(common);
    let report = ok(&args);
    assert!(report.contains("unmatched 0"), "{report}");
    let mut args = vec!["compare", "--out-dir", path(&b)];
    args.extend(common);
    ok(&args);
    let (ha, ra) = read_csv(&a.join("compare.csv"));
    let (hb, rb) = read_csv(&b.join("compare.csv"));
    assert_eq!(ha, ["kind", "t_analytic", "t_reference", "dt", "dstate"]);
    assert_eq!(hb[1], "tau_analytic");
    assert_eq!(ra.len(), rb.len());
    assert!(!ra.is_empty());
    // Both methods, matrix against planar: the same switches within 1e-10.
    for (x, y) in ra.iter().zip(&rb) {
        assert_eq!(x[0], y[0]);
        for i in [1, 2] {
            assert!((num(&x[i]) - num(&y[i])).abs() < 1e-10, "{x:?} vs {y:?}");
        }
    }
    let ring = dir.path().join("r");
    let report = ok(&[
        "compare",
        "--set",
        "stator_mass_ratio=1",
        "--periods",
        "3",
        "--out-dir",
        path(&ring),
    ]);
    assert!(report.contains("unmatched 0"), "{report}");
    assert!(ring.join("compare.svg").exists());
}

#[test]
fn the_stepped_runup_follows_the_exact_variable_speed_runup() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (a, b) = (dir.path().join("ra.csv"), dir.path().join("rb.csv"));
    let common = [
        "--from",
        "1.0",
        "--to",
        "2.0",
        "--ramp-periods",
        "100",
        "--one-way",
        "--settle",
        "10",
        "--method",
        "taylor",
        "--no-plot",
    ];
    let model = jeffcott();
    let mut args = vec!["runup", "--model", path(&model), "--out", path(&a)];
    args.extend(common);
    let report = ok(&args);
    assert!(report.contains("stepped"), "{report}");
    let mut args = vec!["runup", "--preset", "paper", "--out", path(&b)];
    args.extend(common);
    ok(&args);
    let (ha, ra) = read_csv(&a);
    let (hb, rb) = read_csv(&b);
    assert_eq!(ha[4], "speed");
    assert_eq!(hb[4], "speed_ratio");
    assert_eq!(ra.len(), rb.len());
    // The planar run is exact for the continuous ramp; the stepped one holds each period's
    // speed: the largest radius per period agrees to 2 % outside the sensitive rub band
    // η ∈ [1.3, 1.6] and to 1 % on average.
    let mut total = 0.0;
    for (x, y) in ra.iter().zip(&rb) {
        let speed = num(&y[4]);
        assert!((num(&x[4]) - speed).abs() < 2e-3, "{x:?} vs {y:?}");
        let e = (num(&x[6]) / num(&y[6]) - 1.0).abs();
        total += e;
        if !(1.3..=1.6).contains(&speed) {
            assert!(e < 0.02, "largest radius differs by {e} at η = {speed}");
        }
    }
    assert!(total / (ra.len() as f64) < 0.01);
    assert!(dir.path().join("ra-events.csv").exists());
}

#[test]
fn every_analysis_runs_on_the_two_disk_model() {
    let dir = tempfile::tempdir().expect("tempdir");
    let model = two_disk();
    let out = dir.path().join("p.csv");
    let report = ok(&[
        "poincare",
        "--model",
        path(&model),
        "--transient",
        "2",
        "--keep",
        "3",
        "--method",
        "hybrid",
        "--columns",
        "x2,y2,rub_x,rub_y",
        "--out",
        path(&out),
    ]);
    assert!(report.contains("response:"), "{report}");
    let (header, rows) = read_csv(&out);
    assert_eq!(header, ["period", "x2", "y2", "rub_x", "rub_y"]);
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[0][0], "2");
    // SI: the station within a few clearances (0.2 mm).
    assert!(rows.iter().all(|r| num(&r[3]).hypot(num(&r[4])) < 1e-3));
    assert!(dir.path().join("p.svg").exists() && dir.path().join("p.png").exists());

    let out = dir.path().join("s.csv");
    ok(&[
        "spectrum",
        "--model",
        path(&model),
        "--transient",
        "2",
        "--periods",
        "4",
        "--samples-per-period",
        "8",
        "--whirl",
        "--method",
        "hybrid",
        "--out",
        path(&out),
    ]);
    let (header, rows) = read_csv(&out);
    assert_eq!(header, ["order", "whirl"]);
    assert_eq!(rows.len(), 32);

    // A speed sweep of the file with speed-dependent matrices listed at 280 and 320 rad/s (K at
    // the one, C at the other, both the base matrices): re-evaluated per speed, they give the
    // same points as the file without them.
    let text = std::fs::read_to_string(&model).expect("model");
    let block = |name: &str| {
        text.split(&format!("\n{name} = ["))
            .nth(1)
            .and_then(|s| s.split("\n]").next())
            .map(|m| format!("{name} = [{m}\n]\n"))
            .expect("the matrix")
    };
    let speed_file = dir.path().join("speed.toml");
    std::fs::write(
        &speed_file,
        format!(
            "{text}\n[[speed_dependent]]\nspeed = 280.0\n{}[[speed_dependent]]\nspeed = 320.0\n{}",
            block("stiffness"),
            block("damping")
        ),
    )
    .expect("write");
    let mut outs = Vec::new();
    for (file, name) in [(&speed_file, "w.csv"), (&model, "w0.csv")] {
        let out = dir.path().join(name);
        let report = ok(&[
            "sweep",
            "--model",
            path(file),
            "--param",
            "speed",
            "--from",
            "290",
            "--to",
            "310",
            "--steps",
            "2",
            "--transient",
            "1",
            "--keep",
            "2",
            "--method",
            "hybrid",
            "--out",
            path(&out),
        ]);
        assert!(report.contains("2 values of speed"), "{report}");
        outs.push(out);
    }
    let (header, rows) = read_csv(&outs[0]);
    assert_eq!(
        header,
        ["value", "period", "rub_x", "rub_y", "rub_vx", "rub_vy"]
    );
    assert_eq!(rows.len(), 4);
    assert_eq!(
        std::fs::read(&outs[0]).expect("w"),
        std::fs::read(&outs[1]).expect("w0")
    );
    // The matrices are re-evaluated at each speed: K listed as K at 280 and 1.1 K at 320 rad/s
    // is 1.05 K at 300, the same run as the file stating 1.05 K (to rounding).
    let scaled = |factor: f64| {
        let k = block("stiffness");
        let numbers: String = k
            .split_inclusive(['[', ']', ','])
            .map(|piece| {
                let (head, tail) = piece.split_at(piece.len() - 1);
                match head.trim().parse::<f64>() {
                    Ok(x) => format!(" {:?}{tail}", x * factor),
                    Err(_) => piece.to_string(),
                }
            })
            .collect();
        numbers
    };
    let listed = dir.path().join("listed.toml");
    std::fs::write(
        &listed,
        format!(
            "{text}\n[[speed_dependent]]\nspeed = 280.0\n{}[[speed_dependent]]\nspeed = 320.0\n{}",
            block("stiffness"),
            scaled(1.1)
        ),
    )
    .expect("write");
    let stated = dir.path().join("stated.toml");
    std::fs::write(
        &stated,
        text.replacen(&block("stiffness"), &scaled(1.05), 1),
    )
    .expect("write");
    let mut outs = Vec::new();
    for (file, name) in [(&listed, "l.csv"), (&stated, "s.csv"), (&model, "m.csv")] {
        let out = dir.path().join(name);
        ok(&[
            "sweep",
            "--model",
            path(file),
            "--param",
            "speed",
            "--from",
            "300",
            "--steps",
            "1",
            "--transient",
            "2",
            "--keep",
            "3",
            "--method",
            "hybrid",
            "--tol",
            "1e-12",
            "--no-plot",
            "--out",
            path(&out),
        ]);
        outs.push(out);
    }
    let d = largest_difference(&outs[0], &outs[1], 2);
    assert!(d < 1e-12, "listed and stated K differ by {d:e} m");
    assert!(
        largest_difference(&outs[0], &outs[2], 2) > 1e-7,
        "the listed K must change the run"
    );
    // Outside the listed speeds: refused, naming the value and the range, no file.
    let bad = dir.path().join("bad.csv");
    let (code, _, err) = run(&[
        "sweep",
        "--model",
        path(&speed_file),
        "--param",
        "speed",
        "--from",
        "290",
        "--to",
        "330",
        "--steps",
        "2",
        "--out",
        path(&bad),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("330") && err.contains("[280, 320]"), "{err}");
    assert!(!bad.exists());

    let out = dir.path().join("r.csv");
    ok(&[
        "runup",
        "--model",
        path(&model),
        "--from",
        "290",
        "--to",
        "300",
        "--ramp-periods",
        "4",
        "--settle",
        "1",
        "--one-way",
        "--samples-per-period",
        "16",
        "--method",
        "hybrid",
        "--out",
        path(&out),
    ]);
    let (header, rows) = read_csv(&out);
    assert_eq!(header[4], "speed");
    assert!(rows.len() >= 4);
    let (events, _) = read_csv(&dir.path().join("r-events.csv"));
    assert_eq!(events[..5], ["t", "speed", "period", "direction", "kind"]);
    assert_eq!(events.last().map(String::as_str), Some("rub_vy"));
}

#[test]
fn every_analysis_runs_on_the_ring_with_mass() {
    let dir = tempfile::tempdir().expect("tempdir");
    let ring = ["--set", "stator_mass_ratio=1"];
    let out = dir.path().join("p.csv");
    let mut args = vec![
        "poincare",
        "--transient",
        "5",
        "--keep",
        "4",
        "--out",
        path(&out),
    ];
    args.extend(ring);
    ok(&args);
    let (header, rows) = read_csv(&out);
    assert_eq!(
        header,
        ["period", "x", "y", "vx", "vy", "xs", "ys", "vxs", "vys"]
    );
    assert_eq!(rows.len(), 4);
    assert!(rows.iter().any(|r| num(&r[5]) != 0.0), "the ring moves");

    let out = dir.path().join("s.csv");
    let mut args = vec![
        "spectrum",
        "--transient",
        "5",
        "--periods",
        "6",
        "--columns",
        "x,xs",
        "--out",
        path(&out),
    ];
    args.extend(ring);
    ok(&args);
    assert_eq!(read_csv(&out).0, ["order", "x", "xs"]);

    let out = dir.path().join("w.csv");
    let mut args = vec![
        "sweep",
        "--param",
        "stator_mass_ratio",
        "--from",
        "0.5",
        "--to",
        "2",
        "--steps",
        "2",
        "--transient",
        "3",
        "--keep",
        "2",
        "--no-plot",
        "--out",
        path(&out),
    ];
    args.extend(ring);
    ok(&args);
    let (header, rows) = read_csv(&out);
    assert_eq!(header.len(), 10);
    assert_eq!(rows.len(), 4);
    assert_eq!(rows[0][0], "0.5");

    let out = dir.path().join("r.csv");
    let mut args = vec![
        "runup",
        "--ramp-periods",
        "6",
        "--settle",
        "1",
        "--dwell",
        "1",
        "--samples-per-period",
        "16",
        "--hold",
        "2",
        "--out",
        path(&out),
    ];
    args.extend(ring);
    let report = ok(&args);
    assert!(
        report.contains("2 forcing period(s) per held speed"),
        "{report}"
    );
    let (header, rows) = read_csv(&out);
    assert_eq!(header[4], "speed_ratio");
    assert!(rows.iter().any(|r| r[0] == "up") && rows.iter().any(|r| r[0] == "down"));
    // Periods come in held pairs: the same speed twice.
    assert_eq!(rows[2][4], rows[3][4]);
}

#[test]
fn matrix_analyses_refuse_bad_input_naming_the_value() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("x.csv");
    let model = two_disk();
    let m = path(&model);
    let o = path(&out);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["poincare", "--model", m, "--lyapunov", "--out", o],
            "--lyapunov applies only to the paper's planar model",
        ),
        (
            vec!["poincare", "--model", m, "--columns", "x9", "--out", o],
            "unknown column 'x9'",
        ),
        (
            vec!["poincare", "--columns", "x", "--out", o],
            "--columns applies only to a model file",
        ),
        (
            vec![
                "spectrum",
                "--model",
                m,
                "--whirl",
                "--columns",
                "x1",
                "--out",
                o,
            ],
            "exactly two --columns",
        ),
        (
            vec!["sweep", "--model", m, "--out", o],
            "--param speed_ratio is a parameter of the paper's model",
        ),
        (
            vec!["sweep", "--param", "speed", "--out", o],
            "give the model with --model",
        ),
        (
            vec![
                "sweep", "--model", m, "--param", "speed", "--shard", "0/2", "--out", o,
            ],
            "--shard applies only to the paper's planar model",
        ),
        (
            vec![
                "sweep",
                "--model",
                m,
                "--param",
                "clearance",
                "--from",
                "-1",
                "--to",
                "1",
                "--steps",
                "2",
                "--out",
                o,
            ],
            "rub.clearance = -1",
        ),
        (
            vec!["runup", "--model", m, "--to", "300", "--out", o],
            "--from is required with --model",
        ),
        (
            vec![
                "runup",
                "--model",
                m,
                "--from",
                "200",
                "--to",
                "300",
                "--speed-holds",
                "4",
                "--out",
                o,
            ],
            "--speed-holds applies only",
        ),
        (
            vec![
                "poincare",
                "--model",
                m,
                "--method",
                "analytic",
                "--contact-scheme",
                "exprb2",
                "--out",
                o,
            ],
            "contact scheme exprb2 is not available for a rotor from matrices",
        ),
        (
            vec!["runup", "--hold", "2", "--out", o],
            "--hold applies only",
        ),
        (
            vec![
                "sweep",
                "--set",
                "stator_mass_ratio=1",
                "--param",
                "stator_mass_ratio",
                "--from",
                "0",
                "--to",
                "1",
                "--steps",
                "2",
                "--out",
                o,
            ],
            "makes the ring massless",
        ),
        (
            vec!["poincare", "--model", m, "--preset", "paper", "--out", o],
            "cannot be used with",
        ),
    ];
    for (args, expected) in cases {
        let (code, _, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(expected), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} left {}", out.display());
    }
}
