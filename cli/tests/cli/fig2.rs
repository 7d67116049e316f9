//! The main job (no subcommand) with a small test-only option set.

use std::fs;

use rotor_rub::Method;

use crate::common::bin;
use crate::require;

#[test]
fn main_job_writes_its_figures() {
    require!(Method::Analytic, Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    let out = bin()
        .current_dir(dir.path())
        .args([
            "--speeds",
            "1,2",
            "--plot-from",
            "3",
            "--plot-to",
            "5",
            "--section",
            "4",
        ])
        .args([
            "--lyapunov",
            "3",
            "--match-periods",
            "3",
            "--out-dir",
            "figs",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = fs::read_to_string(dir.path().join("figs/fig2.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("η = 2"), "svg");
    let png = fs::read(dir.path().join("figs/fig2.png")).unwrap();
    assert_eq!(&png[..4], b"\x89PNG");
    assert!(stdout.contains("figures written to"), "{stdout}");
    let rows: Vec<&str> = stdout
        .lines()
        .filter(|l| l.trim_start().starts_with("1 |") || l.trim_start().starts_with("2 |"))
        .collect();
    assert_eq!(rows.len(), 2, "one table row per η: {stdout}");
}
